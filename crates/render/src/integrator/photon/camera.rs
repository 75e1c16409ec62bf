//! Camera paths of the photon integrator: Whitted-style through perfectly
//! specular surfaces (both lobes of the first smooth dielectrics), then at
//! the first non-delta hit the shading of `gather.rs`.

use super::gather::{delta_lobe_sample, shade, PhotonCtx};
use super::volume;
use super::weights::{Alpha, AlphaMode};
use crate::bsdf::{SurfaceBsdf, TransportMode};
use crate::geometry::ray::spawn_ray;
use crate::geometry::Ray;
use crate::integrator::lighting::{emitted_mis_n, escaped_mis_n};
use crate::integrator::volpath::Flight;
use lumis_math::{Rgb, Sampler, Vec2, Vec3};

/// Radiance along a camera ray.
pub fn li(
    ctx: &PhotonCtx,
    ray: Ray,
    sampler: &mut Sampler,
    rays: &mut crate::integrator::RayCounts,
) -> Rgb {
    let mut splits = ctx.s.specular_splits;
    if ctx.scene.has_media() {
        super::volume::seed(sampler);
    }
    let start = Branch {
        ray,
        beta: Rgb::WHITE,
        depth: 0,
        first: true,
        medium: ctx.scene.camera_medium,
    };
    trace_camera(ctx, start, &mut splits, sampler, rays)
}

/// Where a camera path (or one branch of it) continues.
struct Branch {
    ray: Ray,
    beta: Rgb,
    depth: u32,
    first: bool,
    /// The medium the ray travels in.
    medium: Option<u32>,
}

/// The radiance a camera path brings from `b` on. At a smooth dielectric,
/// while `splits` lasts, both the reflection and the refraction are
/// followed, each weighted by its Fresnel factor, instead of one chosen with
/// that probability: a light seen in a glass surface then comes as a steady
/// few per cent of its radiance rather than as its full radiance in a few
/// per cent of the samples, the brightest outliers of a small light.
fn trace_camera(
    ctx: &PhotonCtx,
    b: Branch,
    splits: &mut u32,
    sampler: &mut Sampler,
    rays: &mut crate::integrator::RayCounts,
) -> Rgb {
    let scene = ctx.scene;
    let Branch {
        mut ray,
        mut beta,
        depth: start,
        mut first,
        mut medium,
    } = b;
    let mut l = Rgb::BLACK;
    for depth in start..=ctx.s.max_depth {
        if depth == 0 {
            rays.camera += 1;
        } else {
            rays.indirect += 1;
        }
        let mut hit = scene.intersect(&ray);
        if scene.has_media() {
            // Free flights, and pure boundaries crossed; a path that
            // scatters in a medium is shaded there and ends.
            let mut emitted = Rgb::BLACK;
            let crossed = &mut rays.indirect;
            let f = volume::advance(
                ctx,
                &mut medium,
                &mut ray,
                &mut hit,
                &mut beta,
                &mut emitted,
                crossed,
            );
            l += emitted;
            match f {
                Flight::Absorbed => return l,
                Flight::Scattered(p) => {
                    let alpha = ctx.alpha(first, || 0.0);
                    let m = medium.expect("a flight scatters in a medium");
                    let wo = -ray.d.normalize();
                    let m2 = ctx.s.gather_rays;
                    return l + beta
                        * volume::shade_medium(ctx, p, wo, m, alpha, m2, depth, sampler, rays);
                }
                Flight::Passed => {}
            }
        }
        let Some(hit) = hit else {
            return l + beta * escaped_mis_n(scene, &ray, ray.o, 0.0, 0.0, true);
        };
        let mi = scene.medium_interface(&hit);
        let side = |w: Vec3| mi.map_or(medium, |mi| mi.towards(w, hit.geom.ng));
        l += beta * emitted_mis_n(scene, &hit, &ray, ray.o, 0.0, 0.0, true);
        let bsdf = scene.bsdf(&hit, -ray.d);
        let wo = -ray.d;
        if bsdf.is_delta() {
            if *splits > 0 && bsdf.has_transmission() {
                if let Some([(r_w, r_wi), (t_w, t_wi)]) = fresnel_lobes(&bsdf, wo, hit.geom.ns) {
                    *splits -= 1;
                    let reflected = Branch {
                        ray: spawn_ray(hit.geom.p, hit.geom.ng, r_wi),
                        beta: beta * r_w,
                        depth: depth + 1,
                        first,
                        medium: side(r_wi),
                    };
                    l += trace_camera(ctx, reflected, splits, sampler, rays);
                    beta *= t_w;
                    medium = side(t_wi);
                    ray = spawn_ray(hit.geom.p, hit.geom.ng, t_wi);
                    continue;
                }
            }
            let (uc, u) = (sampler.get_1d(), sampler.get_2d());
            let Some(bs) = bsdf.sample(wo, uc, u, TransportMode::Radiance) else {
                return l;
            };
            beta *= bs.weight(hit.geom.ns);
            medium = side(bs.wi);
            ray = spawn_ray(hit.geom.p, hit.geom.ng, bs.wi);
            continue;
        }
        let alpha = ctx.alpha(first, || {
            let f = &scene.textures.footprint;
            f.pixel_area(hit.geom.p, hit.geom.ng) * ctx.pixel_spread
        });
        // Progressive: the caustic disc and the gather rays' share here,
        // from one search of the radius field.
        let disc = ctx.maps.radii.as_ref().map(|r| r.caustic_at(hit.geom.p));
        let m2 = ctx.gather_rays(disc.map_or(0.0, |d| d.1));
        let at = (alpha, m2, disc.map(|d| d.0));
        l += beta * shade(ctx, &hit, &bsdf, wo, medium, at, depth, sampler, rays);
        // `shade` covers the non-delta part; a BSDF with a delta lobe (a
        // smooth coat) also continues along one sample when it is delta.
        match delta_lobe_sample(&hit, &bsdf, wo, sampler) {
            Some((weight, next)) => {
                beta *= weight;
                medium = side(next.d);
                ray = next;
                first = false;
            }
            None => return l,
        }
    }
    l
}

/// The reflection and the refraction of a smooth two-lobe interface, each
/// with its throughput factor `f |cos|` (the Fresnel weight, without the
/// probability of choosing it) and direction; `None` where only one lobe
/// exists (total internal reflection, a conductor).
fn fresnel_lobes(bsdf: &SurfaceBsdf, wo: Vec3, ns: Vec3) -> Option<[(Rgb, Vec3); 2]> {
    // Smooth interfaces choose reflection for `uc` below its probability
    // and refraction above it.
    let lobe = |uc: f32| {
        let bs = bsdf.sample(wo, uc, Vec2::new(0.5, 0.5), TransportMode::Radiance)?;
        Some((bs.transmission, bs.f * bs.wi.dot(ns).abs(), bs.wi))
    };
    let (r_trans, r_w, r_wi) = lobe(0.0)?;
    let (t_trans, t_w, t_wi) = lobe(1.0 - f32::EPSILON / 2.0)?;
    (!r_trans && t_trans).then_some([(r_w, r_wi), (t_w, t_wi)])
}

impl PhotonCtx<'_> {
    /// [`alpha_at`] with this render's mode, first-hit sample count and gain.
    pub(super) fn alpha(&self, first_camera_hit: bool, pixel_area: impl FnOnce() -> f32) -> Alpha {
        let first = (self.alpha_first, self.s.gather_gain);
        alpha_at(self.s.alpha, first, first_camera_hit, pixel_area)
    }

    /// `m_2` at a camera path's non-delta hit where the gather rays carry
    /// `share` of the light of the caustics (`Radii::caustic_at`, measured
    /// on the first iteration's maps; 0 with one map): `gather_rays`, and up
    /// to `gather_boost` times that. The share is a function of the point
    /// alone within an iteration, so every technique's weights of a path
    /// see the same `m_2` (the connections' too, `connect::weigh`).
    pub(super) fn gather_rays(&self, share: f32) -> u32 {
        let m2 = self.s.gather_rays;
        if self.s.gather_boost > 1.0 && m2 > 0 {
            // Rounded down: a faint caustic share adds no ray.
            let extra = (self.s.gather_boost - 1.0) * share;
            m2 + (m2 as f32 * extra) as u32
        } else {
            m2
        }
    }
}

/// `alpha` of `q_1` at a shading point (seed, A.10): from the samples per
/// pixel at the camera path's first non-delta hit (and, in `footprint` mode,
/// the area there that the pixel's samples spread over), times the gather
/// rays' `gain` there; 1 elsewhere.
fn alpha_at(
    mode: AlphaMode,
    (alpha_first, gain): (f32, f32),
    first_camera_hit: bool,
    pixel_area: impl FnOnce() -> f32,
) -> Alpha {
    if !first_camera_hit {
        return Alpha::ONE;
    }
    match mode {
        AlphaMode::One => Alpha { gain, ..Alpha::ONE },
        AlphaMode::Spp => Alpha {
            spp: alpha_first,
            pixel_area: 0.0,
            gain,
        },
        AlphaMode::Footprint => Alpha {
            spp: alpha_first,
            pixel_area: pixel_area(),
            gain,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::photon::PhotonSettings;

    #[test]
    fn alpha_applies_only_at_the_first_camera_hit() {
        assert_eq!(PhotonSettings::default().alpha, AlphaMode::Footprint);
        let area = || 2e-3;
        let at = |m, first| alpha_at(m, (64.0, 1.0), first, area).effective(1e-3);
        // The seed's: spp at the first hit, whatever the footprint.
        assert_eq!(at(AlphaMode::Spp, true), 64.0);
        // Footprint twice the disc: rho = 1/3.
        assert!((at(AlphaMode::Footprint, true) - 22.0).abs() < 1e-4);
        for m in [AlphaMode::Spp, AlphaMode::Footprint, AlphaMode::One] {
            assert_eq!(at(m, false), 1.0);
        }
        assert_eq!(at(AlphaMode::One, true), 1.0);
        // The gather rays' gain: at the first hit only, in every mode.
        for m in [AlphaMode::Spp, AlphaMode::Footprint, AlphaMode::One] {
            let a = |first| alpha_at(m, (64.0, 3.0), first, area).effective(1e-3);
            assert!((a(true) - 3.0 * at(m, true)).abs() < 1e-3);
            assert_eq!(a(false), 1.0);
        }
    }

    /// Following both lobes with their Fresnel weights has the expectation
    /// of choosing one: at every angle, from either side, the two weights
    /// sum to the mean weight of many stochastic samples, and total
    /// internal reflection (one lobe) is not split.
    #[test]
    fn fresnel_branches_have_the_expectation_of_one_chosen_lobe() {
        use crate::bsdf::{Bsdf, Dielectric, ThinDielectric};
        use lumis_math::Frame;
        let n = Vec3::Z;
        let interfaces = [
            Bsdf::Dielectric(Dielectric::new(1.5, 0.0, 0.0)),
            Bsdf::Dielectric(Dielectric::new(1.33, 0.0, 0.0)),
            Bsdf::ThinDielectric(ThinDielectric::new(1.5)),
        ];
        let mut split = 0;
        for b in interfaces {
            let bsdf = SurfaceBsdf::new(Frame::from_normal(n), n, b);
            for k in 0..24 {
                let cos = -0.98 + 1.96 * (k as f32 + 0.5) / 24.0;
                let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
                let runs = 4096;
                let mut mean = 0.0f64;
                let mut lobes = [false, false];
                for j in 0..runs {
                    let uc = (j as f32 + 0.5) / runs as f32;
                    let bs = bsdf.sample(wo, uc, Vec2::new(0.5, 0.5), TransportMode::Radiance);
                    if let Some(bs) = bs {
                        mean += bs.weight(n).r as f64 / runs as f64;
                        lobes[bs.transmission as usize] = true;
                    }
                }
                match fresnel_lobes(&bsdf, wo, n) {
                    Some([r, t]) => {
                        split += 1;
                        let sum = (r.0.r + t.0.r) as f64;
                        assert!(
                            (sum - mean).abs() < 2e-3 * mean.max(1.0),
                            "{b:?} cos {cos}: {sum} vs {mean}"
                        );
                        assert!(r.1.z * wo.z > 0.0 && t.1.z * wo.z < 0.0);
                    }
                    None => assert!(
                        !(lobes[0] && lobes[1]),
                        "{b:?} cos {cos}: two lobes, not split"
                    ),
                }
            }
        }
        assert!(split > 50, "{split} of 72 split");
    }
}
