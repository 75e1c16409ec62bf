//! Dielectric interface: smooth (delta reflection and refraction chosen by
//! Fresnel) or rough (Walter et al. 2007 microfacet reflection and
//! transmission with the generalized half vector), as pbrt-v4's
//! DielectricBxDF (§9.5, §9.7).
//!
//! `eta` is the IOR inside (below the surface, -z) over outside (+z). When
//! `wo` is inside, the interface is seen with the inverse ratio.

use super::fresnel::{fr_dielectric, reflect, refract};
use super::microfacet::Microfacet;
use super::{reflect_z, same_hemisphere, BsdfSample, Lobes, TransportMode};
use lumis_math::{sqr, Rgb, Vec2, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric {
    pub eta: f32,
    pub distrib: Microfacet,
}

/// Generalized half vector of a pair of directions, the relative IOR crossed
/// (1 for reflection) and whether it is a reflection. `None` for degenerate
/// configurations and back-facing microfacets.
fn half_vector(eta: f32, wo: Vec3, wi: Vec3) -> Option<(Vec3, f32, bool)> {
    let (cos_o, cos_i) = (wo.z, wi.z);
    if cos_o == 0.0 || cos_i == 0.0 {
        return None;
    }
    let reflect = cos_i * cos_o > 0.0;
    let etap = if reflect {
        1.0
    } else if cos_o > 0.0 {
        eta
    } else {
        1.0 / eta
    };
    let wm = wi * etap + wo;
    if wm.length_squared() == 0.0 {
        return None;
    }
    let wm = wm.normalize();
    let wm = if wm.z < 0.0 { -wm } else { wm };
    // Both directions must see the front of the microfacet.
    if wm.dot(wi) * cos_i < 0.0 || wm.dot(wo) * cos_o < 0.0 {
        return None;
    }
    Some((wm, etap, reflect))
}

/// Fresnel reflectance for the microfacet `wm` of a pair found by
/// [`half_vector`]. For transmission both directions give the same value in
/// exact arithmetic; the cosine on the optically thinner side is used since
/// the Fresnel term is ill-conditioned near the critical angle on the denser
/// side (this keeps `eval` reciprocal to float precision).
fn pair_fresnel(eta: f32, wo: Vec3, wi: Vec3, wm: Vec3, reflect: bool) -> f32 {
    if reflect {
        return fr_dielectric(wo.dot(wm), eta);
    }
    let thinner_is_outside = eta >= 1.0;
    let w = if (wo.z > 0.0) == thinner_is_outside {
        wo
    } else {
        wi
    };
    fr_dielectric(w.dot(wm), eta)
}

impl Dielectric {
    /// `alpha_x`, `alpha_y`: GGX roughness; below 1e-3 (or with `eta == 1`)
    /// the interface is smooth.
    pub fn new(eta: f32, alpha_x: f32, alpha_y: f32) -> Self {
        Self::with_microfacet(eta, Microfacet::trowbridge_reitz(alpha_x, alpha_y))
    }

    /// A dielectric with any microfacet distribution.
    pub fn with_microfacet(eta: f32, distrib: Microfacet) -> Self {
        Dielectric { eta, distrib }
    }

    pub fn is_delta(&self) -> bool {
        self.eta == 1.0 || self.distrib.effectively_smooth()
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        if self.is_delta() {
            return Rgb::BLACK;
        }
        let Some((wm, etap, reflect)) = half_vector(self.eta, wo, wi) else {
            return Rgb::BLACK;
        };
        let (cos_o, cos_i) = (wo.z, wi.z);
        let fr = pair_fresnel(self.eta, wo, wi, wm, reflect);
        let d = self.distrib.d(wm);
        let g = self.distrib.g(wo, wi);
        if reflect {
            return Rgb::splat(d * g * fr / (4.0 * cos_i * cos_o).abs());
        }
        let denom = sqr(wi.dot(wm) + wo.dot(wm) / etap) * cos_i * cos_o;
        let mut ft = d * (1.0 - fr) * g * (wi.dot(wm) * wo.dot(wm) / denom).abs();
        if mode == TransportMode::Radiance {
            ft /= sqr(etap);
        }
        Rgb::splat(ft)
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.pdf_lobes(wo, wi, Lobes::All)
    }

    /// [`Self::pdf`] of [`Self::sample_lobes`] restricted to `lobes`.
    pub fn pdf_lobes(&self, wo: Vec3, wi: Vec3, lobes: Lobes) -> f32 {
        if self.is_delta() {
            return 0.0;
        }
        let Some((wm, etap, reflect)) = half_vector(self.eta, wo, wi) else {
            return 0.0;
        };
        let r = pair_fresnel(self.eta, wo, wi, wm, reflect);
        let (p_r, p_t) = lobes.choice(r);
        if reflect {
            self.distrib.pdf(wo, wm) / (4.0 * wo.dot(wm).abs()) * p_r
        } else {
            let denom = sqr(wi.dot(wm) + wo.dot(wm) / etap);
            let dwm_dwi = wi.dot(wm).abs() / denom;
            self.distrib.pdf(wo, wm) * dwm_dwi * p_t
        }
    }

    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample> {
        self.sample_lobes(wo, uc, u, mode, Lobes::All)
    }

    /// Sample only reflection or only transmission (pbrt-v4's sample flags):
    /// the lobe is chosen by its Fresnel weight among the allowed ones.
    pub fn sample_lobes(
        &self,
        wo: Vec3,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
        lobes: Lobes,
    ) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        if self.is_delta() {
            self.sample_smooth(wo, uc, mode, lobes)
        } else {
            self.sample_rough(wo, uc, u, mode, lobes)
        }
    }

    fn sample_smooth(
        &self,
        wo: Vec3,
        uc: f32,
        mode: TransportMode,
        lobes: Lobes,
    ) -> Option<BsdfSample> {
        if self.eta == 1.0 {
            if lobes == Lobes::Reflection {
                return None;
            }
            // Index-matched: the interface does not exist.
            return Some(BsdfSample {
                wi: -wo,
                f: Rgb::splat(1.0 / wo.z.abs()),
                pdf: 1.0,
                delta: true,
                transmission: true,
                eta: 1.0,
            });
        }
        let r = fr_dielectric(wo.z, self.eta);
        let t = 1.0 - r;
        let (p_r, p_t) = lobes.choice(r);
        if p_r + p_t <= 0.0 {
            return None;
        }
        if uc < p_r {
            let wi = reflect_z(wo);
            return Some(BsdfSample {
                wi,
                f: Rgb::splat(r / wi.z.abs()),
                pdf: p_r,
                delta: true,
                transmission: false,
                eta: 1.0,
            });
        }
        let (wi, etap) = refract(wo, Vec3::Z, self.eta)?;
        let mut ft = t / wi.z.abs();
        if mode == TransportMode::Radiance {
            ft /= sqr(etap);
        }
        Some(BsdfSample {
            wi,
            f: Rgb::splat(ft),
            pdf: p_t,
            delta: true,
            transmission: true,
            eta: etap,
        })
    }

    fn sample_rough(
        &self,
        wo: Vec3,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
        lobes: Lobes,
    ) -> Option<BsdfSample> {
        let wm = self.distrib.sample_wm(wo, u)?;
        let r = fr_dielectric(wo.dot(wm), self.eta);
        let t = 1.0 - r;
        let (p_r, p_t) = lobes.choice(r);
        if p_r + p_t <= 0.0 {
            return None;
        }
        let (cos_o, d, pdf_wm) = (wo.z, self.distrib.d(wm), self.distrib.pdf(wo, wm));
        if uc < p_r {
            let wi = reflect(wo, wm);
            if !same_hemisphere(wo, wi) {
                return None;
            }
            let pdf = pdf_wm / (4.0 * wo.dot(wm).abs()) * p_r;
            let f = d * self.distrib.g(wo, wi) * r / (4.0 * wi.z * cos_o).abs();
            return Some(BsdfSample {
                wi,
                f: Rgb::splat(f),
                pdf,
                delta: false,
                transmission: false,
                eta: 1.0,
            });
        }
        let (wi, etap) = refract(wo, wm, self.eta)?;
        if same_hemisphere(wo, wi) || wi.z == 0.0 {
            return None;
        }
        let denom = sqr(wi.dot(wm) + wo.dot(wm) / etap);
        let dwm_dwi = wi.dot(wm).abs() / denom;
        let pdf = pdf_wm * dwm_dwi * p_t;
        let mut ft = t
            * d
            * self.distrib.g(wo, wi)
            * (wi.dot(wm) * wo.dot(wm) / (wi.z * cos_o * denom)).abs();
        if mode == TransportMode::Radiance {
            ft /= sqr(etap);
        }
        Some(BsdfSample {
            wi,
            f: Rgb::splat(ft),
            pdf,
            delta: false,
            transmission: true,
            eta: etap,
        })
    }
}
