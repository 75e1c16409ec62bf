//! Anisotropic microfacet distributions with height-correlated Smith
//! masking-shadowing: Trowbridge-Reitz (GGX, pbrt-v4's only one, sampled by
//! visible normals, Heitz 2018) and Beckmann (as pbrt-v3, Mitsuba and
//! Tungsten have it; sampled by `D(wm) cos(theta_m)`). Directions are in the
//! local shading frame (+z = normal).

mod beckmann;
mod trowbridge_reitz;

use lumis_math::{Vec2, Vec3};

/// Below this roughness a microfacet BSDF is treated as perfectly smooth.
pub const SMOOTH_ALPHA: f32 = 1e-3;

/// Which normal distribution a rough surface has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MicrofacetModel {
    /// Trowbridge-Reitz (GGX): power-law tails, pbrt-v4's model.
    #[default]
    TrowbridgeReitz,
    /// Beckmann: Gaussian slopes, much shorter tails.
    Beckmann,
}

impl MicrofacetModel {
    /// The scene-file name (`"string distribution"`), as Mitsuba spells it.
    pub fn from_name(s: &str) -> Option<Self> {
        match s {
            "trowbridgereitz" | "ggx" => Some(MicrofacetModel::TrowbridgeReitz),
            "beckmann" => Some(MicrofacetModel::Beckmann),
            _ => None,
        }
    }

    pub const NAMES: [&'static str; 3] = ["trowbridgereitz", "ggx", "beckmann"];
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    pub model: MicrofacetModel,
    pub alpha_x: f32,
    pub alpha_y: f32,
}

#[inline]
pub(crate) fn cos2_theta(w: Vec3) -> f32 {
    w.z * w.z
}
#[inline]
pub(crate) fn sin2_theta(w: Vec3) -> f32 {
    (1.0 - cos2_theta(w)).max(0.0)
}
#[inline]
pub(crate) fn tan2_theta(w: Vec3) -> f32 {
    sin2_theta(w) / cos2_theta(w)
}
/// `w` flipped to the upper hemisphere, where microfacet normals live.
#[inline]
fn upper(w: Vec3) -> Vec3 {
    if w.z < 0.0 {
        -w
    } else {
        w
    }
}
/// `(cos^2 phi, sin^2 phi)`; `(1, 0)` at the pole.
#[inline]
fn cos2_sin2_phi(w: Vec3) -> (f32, f32) {
    let s2 = w.x * w.x + w.y * w.y;
    if s2 <= 0.0 {
        (1.0, 0.0)
    } else {
        let c2 = (w.x * w.x / s2).clamp(0.0, 1.0);
        (c2, 1.0 - c2)
    }
}

impl Microfacet {
    pub fn new(model: MicrofacetModel, alpha_x: f32, alpha_y: f32) -> Self {
        Microfacet {
            model,
            alpha_x,
            alpha_y,
        }
    }

    pub fn trowbridge_reitz(alpha_x: f32, alpha_y: f32) -> Self {
        Self::new(MicrofacetModel::TrowbridgeReitz, alpha_x, alpha_y)
    }

    pub fn beckmann(alpha_x: f32, alpha_y: f32) -> Self {
        Self::new(MicrofacetModel::Beckmann, alpha_x, alpha_y)
    }

    /// Too smooth to be sampled as a distribution: use a delta lobe instead.
    pub fn effectively_smooth(&self) -> bool {
        self.alpha_x.max(self.alpha_y) < SMOOTH_ALPHA
    }

    /// `tan^2(theta) (cos^2 phi / alpha_x^2 + sin^2 phi / alpha_y^2)`, the
    /// squared slope scaled by the roughness, shared by both `D`s.
    fn scaled_tan2(&self, wm: Vec3) -> f32 {
        let (c2, s2) = cos2_sin2_phi(wm);
        tan2_theta(wm) * (c2 / (self.alpha_x * self.alpha_x) + s2 / (self.alpha_y * self.alpha_y))
    }

    /// `alpha^2 tan^2(theta)` along `w`'s azimuth, shared by both `Lambda`s.
    fn alpha2_tan2(&self, w: Vec3) -> f32 {
        let (c2, s2) = cos2_sin2_phi(w);
        (c2 * self.alpha_x * self.alpha_x + s2 * self.alpha_y * self.alpha_y) * tan2_theta(w)
    }

    /// Microfacet normal density D(wm), normalized so that the projected area
    /// integrates to one: `∫ D(wm) cos(theta_m) dwm = 1`.
    pub fn d(&self, wm: Vec3) -> f32 {
        let tan2 = tan2_theta(wm);
        let cos4 = cos2_theta(wm) * cos2_theta(wm);
        if !tan2.is_finite() || cos4 < 1e-16 {
            return 0.0;
        }
        let e = self.scaled_tan2(wm);
        let norm = lumis_math::PI * self.alpha_x * self.alpha_y * cos4;
        match self.model {
            MicrofacetModel::TrowbridgeReitz => trowbridge_reitz::d(e, norm),
            MicrofacetModel::Beckmann => beckmann::d(e, norm),
        }
    }

    /// Smith's auxiliary function Lambda(w).
    pub fn lambda(&self, w: Vec3) -> f32 {
        let a2t2 = self.alpha2_tan2(w);
        if !a2t2.is_finite() {
            return 0.0;
        }
        match self.model {
            MicrofacetModel::TrowbridgeReitz => trowbridge_reitz::lambda(a2t2),
            MicrofacetModel::Beckmann => beckmann::lambda(a2t2),
        }
    }

    /// Masking function.
    pub fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking-shadowing.
    pub fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// Distribution of normals visible from `w`:
    /// `D_w(wm) = G1(w) / |cos w| * D(wm) * max(0, w · wm)`, where `w` is
    /// first flipped to the upper hemisphere. Normalized: `∫ D_w(wm) dwm = 1`.
    pub fn d_visible(&self, w: Vec3, wm: Vec3) -> f32 {
        let cos = w.z.abs();
        if cos == 0.0 {
            return 0.0;
        }
        self.g1(w) / cos * self.d(wm) * upper(w).dot(wm).max(0.0)
    }

    /// Density of [`Self::sample_wm`] (per solid angle of `wm`); 0 for
    /// normals facing away from `w` (flipped to the upper hemisphere).
    pub fn pdf(&self, w: Vec3, wm: Vec3) -> f32 {
        match self.model {
            MicrofacetModel::TrowbridgeReitz => self.d_visible(w, wm),
            MicrofacetModel::Beckmann => {
                if upper(w).dot(wm) <= 0.0 {
                    0.0
                } else {
                    self.d(wm) * wm.z.abs()
                }
            }
        }
    }

    /// Sample a microfacet normal seen from `w` (flipped to the upper
    /// hemisphere if below); the result lies in the upper hemisphere. `None`
    /// when the sampled normal faces away from `w` (Beckmann only: its
    /// sampling is not restricted to visible normals).
    pub fn sample_wm(&self, w: Vec3, u: Vec2) -> Option<Vec3> {
        let w_up = upper(w);
        match self.model {
            MicrofacetModel::TrowbridgeReitz => Some(trowbridge_reitz::sample_wm(self, w_up, u)),
            MicrofacetModel::Beckmann => {
                let wm = beckmann::sample_wm(self, u)?;
                (w_up.dot(wm) > 0.0).then_some(wm)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::{sampling::square_to_uniform_hemisphere, Pcg32, INV_2PI};

    fn dists() -> Vec<Microfacet> {
        let mut v = Vec::new();
        for m in [MicrofacetModel::TrowbridgeReitz, MicrofacetModel::Beckmann] {
            for (ax, ay) in [(0.1, 0.1), (0.3, 0.3), (0.8, 0.8), (0.1, 0.4)] {
                v.push(Microfacet::new(m, ax, ay));
            }
        }
        v
    }

    /// Stratified uniform-hemisphere estimate of `∫ f(wm) dwm`.
    fn integrate(f: impl Fn(Vec3) -> f32) -> f64 {
        let mut rng = Pcg32::new(5, 1);
        let (nu, nv) = (1000, 200);
        let mut sum = 0.0f64;
        for i in 0..nu {
            for j in 0..nv {
                let u = Vec2::new(
                    (i as f32 + rng.next_f32()) / nu as f32,
                    (j as f32 + rng.next_f32()) / nv as f32,
                );
                let wm = square_to_uniform_hemisphere(u);
                sum += (f(wm) / INV_2PI) as f64;
            }
        }
        sum / (nu * nv) as f64
    }

    /// `∫ D(wm) cos(theta_m) dwm = 1`.
    #[test]
    fn projected_area_is_one() {
        for dist in dists() {
            let mean = integrate(|wm| dist.d(wm) * wm.z);
            assert!((mean - 1.0).abs() < 0.01, "{dist:?}: {mean}");
        }
    }

    /// Visible normals integrate to one, `∫ D_w(wm) dwm = 1` for any `w`:
    /// this checks `Lambda` against `D` (Smith's normalisation).
    #[test]
    fn visible_normals_normalized() {
        for dist in dists() {
            for cz in [0.95f32, 0.5, 0.1] {
                let w = Vec3::new(
                    (1.0 - cz * cz).sqrt() * 0.6,
                    (1.0 - cz * cz).sqrt() * 0.8,
                    cz,
                );
                let mean = integrate(|wm| dist.d_visible(w, wm));
                // Beckmann's Lambda is Walter et al.'s rational fit (as in
                // pbrt-v3, Mitsuba and Tungsten): within 0.5% of exact.
                assert!((mean - 1.0).abs() < 0.012, "{dist:?} cos {cz}: {mean}");
            }
        }
    }

    /// The density of [`Microfacet::sample_wm`] integrates to the fraction
    /// of samples it returns (all of them for visible-normal sampling).
    #[test]
    fn pdf_mass_matches_the_accepted_fraction() {
        let mut rng = Pcg32::new(3, 7);
        for dist in dists() {
            for w in [
                Vec3::new(0.6, 0.0, 0.8),
                Vec3::new(0.99, 0.0, 0.141).normalize(),
            ] {
                let mass = integrate(|wm| dist.pdf(w, wm));
                let n = 200_000;
                let accepted = (0..n)
                    .filter(|_| {
                        dist.sample_wm(w, Vec2::new(rng.next_f32(), rng.next_f32()))
                            .is_some()
                    })
                    .count() as f64
                    / n as f64;
                assert!(
                    (mass - accepted).abs() < 0.01,
                    "{dist:?} {w:?}: mass {mass} accepted {accepted}"
                );
            }
        }
    }

    #[test]
    fn sampled_normals_face_the_viewer() {
        let mut rng = Pcg32::new(1, 1);
        for dist in dists() {
            for w in [
                Vec3::new(0.6, 0.0, 0.8),
                Vec3::new(-0.3, 0.2, -0.93).normalize(),
            ] {
                for _ in 0..1000 {
                    let u = Vec2::new(rng.next_f32(), rng.next_f32());
                    let Some(wm) = dist.sample_wm(w, u) else {
                        assert_eq!(dist.model, MicrofacetModel::Beckmann);
                        continue;
                    };
                    assert!(wm.z > 0.0 && (wm.length() - 1.0).abs() < 1e-4);
                    // Visible from the (flipped) viewer, up to the unstretch clamp.
                    assert!(w.dot(wm) * w.z.signum() > -1e-3);
                }
            }
        }
    }

    /// Beckmann's tails are Gaussian, GGX's a power law: at a slope of four
    /// alphas GGX's density is orders of magnitude higher.
    #[test]
    fn beckmann_tails_are_short() {
        let a = 0.05;
        let t = 4.0 * a;
        let wm = Vec3::new(t, 0.0, 1.0).normalize();
        let (g, b) = (
            Microfacet::trowbridge_reitz(a, a).d(wm),
            Microfacet::beckmann(a, a).d(wm),
        );
        // GGX: 1/(1+16)^2 = 3.5e-3 of its peak; Beckmann: e^-16 = 1.1e-7.
        let (g0, b0) = (
            Microfacet::trowbridge_reitz(a, a).d(Vec3::Z),
            Microfacet::beckmann(a, a).d(Vec3::Z),
        );
        let sec4 = (1.0 + t * t).powi(2);
        assert!(
            (g / g0 / sec4 * 289.0 - 1.0).abs() < 1e-4,
            "{}",
            g / g0 / sec4
        );
        assert!((b / b0 / sec4 / (-16.0f32).exp() - 1.0).abs() < 1e-3);
    }
}
