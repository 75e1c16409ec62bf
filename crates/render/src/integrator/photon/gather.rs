//! Shading at a camera path's non-delta hit `x` (`camera.rs` brings the
//! paths there): emission, direct
//! light (light sampling MIS'd with the gather rays), caustics (caustic
//! photons and gather rays through specular chains, weighted by the seed's
//! `w_1`, `w_2`) and indirect light (gather rays reading the global map at
//! their first non-delta hit; along glossy surfaces the same rules recurse).

use super::aim::emitted_flux;
use super::connect;
use super::volume;
use super::weights::{q1, q2, w1, w2, Alpha};
use super::{Kernel, PhotonMaps, PhotonSettings, GLOBAL_RADIUS_SCALE};
use crate::bsdf::{SurfaceBsdf, TransportMode};
use crate::geometry::ray::spawn_ray;
use crate::geometry::Ray;
use crate::integrator::lighting::{emitted_mis_n, escaped_mis_n, sample_direct_n};
use crate::integrator::volpath::Flight;
use crate::scene::{Hit, Scene};
use lumis_math::{Rgb, Sampler, Vec2, Vec3, PI};
use std::cell::RefCell;

/// Read-only state shared by all camera paths of a render.
pub struct PhotonCtx<'a> {
    pub scene: &'a Scene,
    pub maps: &'a PhotonMaps,
    pub s: &'a PhotonSettings,
    /// Samples per pixel (known, or predicted under a time budget): the
    /// seed's `alpha` at the first non-delta camera hit.
    pub alpha_first: f32,
    /// The area, in pixels, a pixel's samples spread over (the filter's).
    pub pixel_spread: f32,
    /// The caustic photons are connected to the camera, whose film they
    /// may reach within this margin (pixels): caustics at a camera ray's
    /// first hit are weighed over three techniques (`connect.rs`).
    pub connect: Option<Vec2>,
}

thread_local! {
    /// The photons a density estimate found (reused, one per thread).
    pub(super) static SCRATCH: RefCell<Vec<(u32, f32)>> = const { RefCell::new(Vec::new()) };
}

/// The photons of `map` around `x` into `found`, and the squared radius:
/// the iteration's (`r2_of` the radii, all photons within it), or, with
/// one map, that of the `nearest` photons within `max_radius` (then
/// `true`: the farthest found lies on the boundary).
pub(super) fn query(
    ctx: &PhotonCtx,
    map: &super::map::PhotonMap,
    x: Vec3,
    r2_of: impl Fn(&super::Radii) -> f32,
    max_radius: f32,
    found: &mut Vec<(u32, f32)>,
) -> (f32, bool) {
    match &ctx.maps.radii {
        Some(radii) => {
            let r2 = r2_of(radii);
            map.within(x, r2.sqrt(), found);
            (r2, false)
        }
        None => (map.knn(x, ctx.s.nearest, max_radius, found), true),
    }
}

const CONE_K: f32 = 1.1;

/// For a non-delta BSDF with a delta lobe: one BSDF sample, kept (weight
/// and continuation ray) only when it is delta. The delta part's estimate is
/// then unbiased, and the non-delta part is estimated elsewhere by samples
/// that skip delta ones.
pub(super) fn delta_lobe_sample(
    hit: &Hit,
    bsdf: &SurfaceBsdf,
    wo: Vec3,
    sampler: &mut Sampler,
) -> Option<(Rgb, Ray)> {
    if !bsdf.has_delta_lobe() {
        return None;
    }
    let (uc, u) = (sampler.get_1d(), sampler.get_2d());
    let bs = bsdf.sample(wo, uc, u, TransportMode::Radiance)?;
    if !bs.delta {
        return None;
    }
    let weight = bs.weight(hit.geom.ns);
    Some((weight, spawn_ray(hit.geom.p, hit.geom.ng, bs.wi)))
}

/// Light leaving non-delta point `x` towards `wo`, excluding its emission,
/// with `alpha`, `m2` gather rays and, if the caller has read it, the
/// caustic disc's squared radius there (else read here).
#[allow(clippy::too_many_arguments)]
pub fn shade(
    ctx: &PhotonCtx,
    x: &Hit,
    bsdf: &SurfaceBsdf,
    wo: Vec3,
    medium: Option<u32>,
    (alpha, m2, caustic_r2): (Alpha, u32, Option<f32>),
    depth: u32,
    sampler: &mut Sampler,
    rays: &mut crate::integrator::RayCounts,
) -> Rgb {
    let scene = ctx.scene;
    let mut l = if scene.has_media() {
        volume::direct_at_surface(ctx, x, bsdf, wo, medium, m2, sampler, rays)
    } else {
        sample_direct_n(scene, x, bsdf, wo, m2 as f32, sampler, rays)
    };
    // Seen directly with the caustic photons connected to the camera: the
    // caustics here are weighed over three techniques (`connect.rs`).
    let inv_j = match ctx.connect {
        Some(margin) if depth == 0 => connect::inv_density(scene, x.geom.p, x.geom.ng, margin),
        _ => 0.0,
    };
    let (lc, delta_a, alpha) = caustic_photons(ctx, x, bsdf, wo, (alpha, inv_j), m2, caustic_r2);
    l += lc;
    if m2 == 0 {
        return l;
    }
    // Stratified gather directions: a rank-1 (Fibonacci) lattice over the
    // square, rotated by one random offset per shading point.
    let (jitter, jc) = (sampler.get_2d(), sampler.get_1d());
    let n = m2 as f32;
    let mut gathered = Rgb::BLACK;
    for k in 0..m2 {
        let kf = k as f32;
        let u = Vec2::new(
            ((kf + 0.5) / n + jitter.x).fract(),
            (kf * 0.618_034 + jitter.y).fract(),
        );
        let uc = (jc + kf / n).fract();
        let Some(bs) = bsdf.sample(wo, uc, u, TransportMode::Radiance) else {
            continue;
        };
        if bs.delta {
            continue;
        }
        let cos_x = bs.wi.dot(x.geom.ns).abs();
        let weight = bs.f * (cos_x / bs.pdf);
        let g = Gather {
            origin: x.geom.p,
            ray: spawn_ray(x.geom.p, x.geom.ng, bs.wi),
            medium: scene
                .medium_interface(x)
                .map_or(medium, |mi| mi.towards(bs.wi, x.geom.ng)),
            pdf: bs.pdf,
            q1_cos: cos_x,
            q1_measure: delta_a,
            alpha,
            m2,
            inv_j,
        };
        gathered += weight * trace_gather(ctx, &g, depth, sampler, rays);
    }
    l + gathered / n
}

/// One final-gather direction from a shading point and what its weights need.
pub(super) struct Gather {
    /// The shading point (a surface hit or a scattering point in a medium).
    pub origin: Vec3,
    pub ray: Ray,
    /// The medium the ray starts in.
    pub medium: Option<u32>,
    /// The direction's sampling density (BSDF or phase function).
    pub pdf: f32,
    /// What `q_1` counts photons over besides `N L_e / (Phi alpha)`, as a
    /// factor and a measure: `cos(theta)` and `DeltaA` on a surface,
    /// `sigma_s` and `DeltaV` in a medium.
    pub q1_cos: f32,
    pub q1_measure: f32,
    pub alpha: f32,
    pub m2: u32,
    /// `1 / J` at the shading point where the caustic photons are
    /// connected to the camera (a third caustic technique), else 0.
    pub inv_j: f32,
}

/// Radiance arriving at the shading point along a gather ray, with the MIS
/// weights of the technique that found it applied.
pub(super) fn trace_gather(
    ctx: &PhotonCtx,
    g: &Gather,
    depth: u32,
    sampler: &mut Sampler,
    rays: &mut crate::integrator::RayCounts,
) -> Rgb {
    let scene = ctx.scene;
    let s = ctx.s;
    let mut ray = g.ray;
    let mut medium = g.medium;
    let mut t = Rgb::WHITE;
    let mut acc = Rgb::BLACK;
    let mut specular = false;
    for d in depth + 1..=s.max_depth {
        rays.gather += 1;
        // Whether the radiance photons were read here already (and did not
        // cover the point).
        let mut read = false;
        let mut hit = if scene.has_media() {
            scene.intersect(&ray)
        } else {
            // A plain diffuse surface that the radiance photons cover ends
            // the ray with what `global_radiance` would give there, without
            // the hit's full geometry and BSDF.
            let lazy = scene.intersect_lazy(&ray);
            if let Some(pd) = lazy.as_ref().and_then(|l| scene.plain_diffuse(l, &ray)) {
                if let Some(v) = radiance_photons(ctx, pd.p, pd.ng, -ray.d, pd.albedo) {
                    return acc + t * v;
                }
                read = true;
            }
            lazy.map(|l| scene.finish(l, &ray))
        };
        if scene.has_media() {
            // Free flights, and pure boundaries crossed; a gather ray that
            // scatters reads the global volume photons there.
            let mut emitted = Rgb::BLACK;
            let crossed = &mut rays.gather;
            let f = volume::advance(
                ctx,
                &mut medium,
                &mut ray,
                &mut hit,
                &mut t,
                &mut emitted,
                crossed,
            );
            acc += emitted;
            match f {
                Flight::Absorbed => return acc,
                Flight::Scattered(p) => {
                    let wo = -ray.d.normalize();
                    let m = medium.expect("a flight scatters in a medium");
                    return acc + t * volume::global_in_scattering(ctx, p, wo, m);
                }
                Flight::Passed => {}
            }
        }
        let Some(h) = hit else {
            if !specular {
                return acc + escaped_mis_n(scene, &ray, g.origin, g.m2 as f32, g.pdf, false);
            }
            // Caustic from an environment through a specular chain.
            let mut sum = Rgb::BLACK;
            for &i in &scene.infinite_lights {
                let le = scene.lights[i as usize].le(ray.d);
                let flux = || {
                    emitted_flux(
                        scene,
                        None,
                        i,
                        Vec3::ZERO,
                        Vec3::ZERO,
                        -ray.d,
                        le.luminance(),
                    )
                };
                sum += le * caustic_gather_weight(ctx, g, le.luminance(), flux);
            }
            return acc + t * sum;
        };
        // Emission found here: direct light (MIS with light sampling) or, after
        // a specular chain, a caustic sample (the seed's w_2). The surface may
        // also reflect, which the code below adds.
        let mut emitted = Rgb::BLACK;
        if let Some(li) = h.light {
            emitted = if !specular {
                emitted_mis_n(scene, &h, &ray, g.origin, g.m2 as f32, g.pdf, false)
            } else {
                let le = scene.lights[li as usize].l(h.geom.ng, h.geom.uv, -ray.d);
                let flux = || {
                    let t = ctx.maps.targets.as_ref();
                    emitted_flux(scene, t, li, h.geom.p, h.geom.ng, -ray.d, le.luminance())
                };
                le * caustic_gather_weight(ctx, g, le.luminance(), flux)
            };
        }
        let bsdf = scene.bsdf(&h, -ray.d);
        let wo = -ray.d;
        if bsdf.is_delta() {
            let (uc, u) = (sampler.get_1d(), sampler.get_2d());
            let Some(bs) = bsdf.sample(wo, uc, u, TransportMode::Radiance) else {
                return acc;
            };
            let weight = bs.weight(h.geom.ns);
            // Roulette with survival = the bounce's transmittance gamma (measured
            // without the radiance scaling of refraction, as the photons' is),
            // so gamma cancels between q_1 and q_2 (seed, A.7).
            let eta2 = if bs.transmission {
                bs.eta * bs.eta
            } else {
                1.0
            };
            let gamma = (weight * eta2).luminance().min(1.0);
            if !(gamma > 0.0) || sampler.get_1d() >= gamma {
                return acc + t * emitted;
            }
            if !emitted.is_black() {
                return acc + t * emitted; // a specular emitter: its emission ends the chain
            }
            t *= weight / gamma;
            specular = true;
            if let Some(mi) = scene.medium_interface(&h) {
                medium = mi.towards(bs.wi, h.geom.ng);
            }
            ray = spawn_ray(h.geom.p, h.geom.ng, bs.wi);
            continue;
        }
        let here = if bsdf.is_glossy() && d < s.max_depth {
            emitted
                + shade(
                    ctx,
                    &h,
                    &bsdf,
                    wo,
                    medium,
                    (Alpha::ONE, 1, None),
                    d,
                    sampler,
                    rays,
                )
        } else {
            emitted + global_radiance(ctx, &h, &bsdf, wo, read)
        };
        acc += t * here;
        // A delta lobe on this non-delta surface (a smooth coat) continues
        // the chain as a specular bounce, with the same roulette.
        let Some((weight, next)) = delta_lobe_sample(&h, &bsdf, wo, sampler) else {
            return acc;
        };
        let gamma = weight.luminance().min(1.0);
        if !(gamma > 0.0) || sampler.get_1d() >= gamma {
            return acc;
        }
        t *= weight / gamma;
        specular = true;
        if let Some(mi) = scene.medium_interface(&h) {
            medium = mi.towards(next.d, h.geom.ng);
        }
        ray = next;
    }
    acc
}

/// `w_2` of a gather ray that reached an emitter of luminance `le` through a specular chain.
///
/// With aimed caustic photons the flux per photon varies: `flux` gives the
/// (N times) flux a photon would carry along this path, replacing `Phi`.
fn caustic_gather_weight(ctx: &PhotonCtx, g: &Gather, le: f32, flux: impl Fn() -> f32) -> f32 {
    let n = ctx.maps.caustic.emitted() as f64;
    let phi = if ctx.maps.targets.is_some() {
        flux()
    } else {
        ctx.maps.phi
    };
    let q_1 = q1(n, le, g.q1_cos, g.q1_measure, phi, g.alpha);
    let q_2 = q2(g.m2, g.pdf);
    if g.inv_j > 0.0 {
        let q3 = |m: f32, s: f32| q1(n, le, g.q1_cos, m, phi, s);
        return connect::weights(ctx, (q_1, q_2), (g.q1_measure, g.alpha), g.inv_j, q3)[1];
    }
    w2(q_1, q_2, ctx.s.caustics, ctx.s.heuristic)
}

/// The caustic photon estimate at `x`, each photon weighted by `w_1`; also
/// returns the disc area `DeltaA` of the query and the `alpha` it gives,
/// which the gather rays share.
fn caustic_photons(
    ctx: &PhotonCtx,
    x: &Hit,
    bsdf: &SurfaceBsdf,
    wo: Vec3,
    (alpha, inv_j): (Alpha, f32),
    m2: u32,
    caustic_r2: Option<f32>,
) -> (Rgb, f32, f32) {
    let map = &ctx.maps.caustic;
    let s = ctx.s;
    SCRATCH.with(|cell| {
        let mut found = cell.borrow_mut();
        found.clear();
        // Progressive iterations: every photon in a disc fixed beforehand
        // (its count varies); otherwise the `nearest` ones.
        let p = x.geom.p;
        let max = ctx.maps.max_radius;
        let r2_of = |r: &super::Radii| caustic_r2.unwrap_or_else(|| r.caustic_r2(p));
        let (r2, skip_boundary) = query(ctx, map, p, r2_of, max, &mut found);
        let delta_a = PI * r2;
        let alpha = alpha.effective(delta_a);
        if found.is_empty() || r2 <= 0.0 {
            return (Rgb::BLACK, delta_a, alpha);
        }
        let r = r2.sqrt();
        let skip = skip_boundary
            .then(|| boundary_photon(&found, s.nearest, r2))
            .flatten();
        let mut sum = Rgb::BLACK;
        for (j, &(i, d2)) in found.iter().enumerate() {
            if Some(j) == skip {
                continue;
            }
            let ph = map.photon(i);
            let wj = ph.dir();
            let f = bsdf.eval(wo, wj, TransportMode::Radiance);
            if f.is_black() {
                continue;
            }
            // Aimed photons carry their own flux: Phi / N becomes the photon's power.
            let (le, cos, power) = (ph.le(), wj.dot(x.geom.ns), ph.power().luminance());
            let q_1 = connect::photon_q(ctx, le, cos, delta_a, power, alpha);
            let q_2 = q2(m2, bsdf.pdf(wo, wj, TransportMode::Radiance));
            let w = if inv_j > 0.0 {
                let q3 = |m: f32, s: f32| connect::photon_q(ctx, le, cos, m, power, s);
                connect::weights(ctx, (q_1, q_2), (delta_a, alpha), inv_j, q3)[0]
            } else {
                w1(q_1, q_2, s.caustics, s.heuristic)
            };
            if w == 0.0 {
                continue;
            }
            let kw = match s.kernel {
                Kernel::None => 1.0,
                Kernel::Cone => (1.0 - d2.sqrt() / (CONE_K * r)) / (1.0 - 2.0 / (3.0 * CONE_K)),
            };
            sum += f * ph.power() * (w * kw);
        }
        (sum / delta_a, delta_a, alpha)
    })
}

/// Radiance leaving non-delta `y` towards `wo` from the global photon map:
/// the nearest radiance photon (diffuse surfaces), else a density estimate
/// over the `nearest` photons or, in progressive iterations, over every
/// photon in the iteration's fixed disc.
/// `read`: the radiance photons were read at `y` already, in vain.
fn global_radiance(ctx: &PhotonCtx, y: &Hit, bsdf: &SurfaceBsdf, wo: Vec3, read: bool) -> Rgb {
    if let Some(albedo) = bsdf.bsdf.diffuse_albedo().filter(|_| !read) {
        if let Some(l) = radiance_photons(ctx, y.geom.p, y.geom.ng, wo, albedo) {
            return l;
        }
    }
    let radius = global_radius(ctx);
    let map = &ctx.maps.global;
    SCRATCH.with(|cell| {
        let mut found = cell.borrow_mut();
        found.clear();
        let p = y.geom.p;
        let (r2, knn) = query(ctx, map, p, |r| r.global_r2(p), radius, &mut found);
        let skip = knn
            .then(|| boundary_photon(&found, ctx.s.nearest, r2))
            .flatten();
        if found.is_empty() || r2 <= 0.0 {
            return Rgb::BLACK;
        }
        let mut sum = Rgb::BLACK;
        for (j, &(i, _)) in found.iter().enumerate() {
            if Some(j) != skip {
                let ph = map.photon(i);
                sum += bsdf.eval(wo, ph.dir(), TransportMode::Radiance) * ph.power();
            }
        }
        sum / (PI * r2)
    })
}

/// The global photons' largest radius.
fn global_radius(ctx: &PhotonCtx) -> f32 {
    let fixed = ctx.maps.radii.as_ref();
    fixed.map_or(ctx.maps.max_radius * GLOBAL_RADIUS_SCALE, |r| {
        r.global_max()
    })
}

/// Light leaving diffuse point `p` (geometric normal `ng`, `albedo`)
/// towards `wo` from the radiance photons, if they cover `p`.
#[inline]
fn radiance_photons(ctx: &PhotonCtx, p: Vec3, ng: Vec3, wo: Vec3, albedo: Rgb) -> Option<Rgb> {
    let n = if ng.dot(wo) < 0.0 { -ng } else { ng };
    let e = ctx
        .maps
        .radiance
        .as_ref()?
        .irradiance(p, n, global_radius(ctx))?;
    Some(e * albedo * (1.0 / PI))
}

/// When the disc's radius is set by the k-th nearest photon, that photon lies
/// on the boundary: summing all k over `pi r_k^2` overestimates the density by
/// k / (k - 1) on average (for a locally uniform density). Leaving the
/// boundary photon out makes the estimate unbiased there.
fn boundary_photon(found: &[(u32, f32)], k: usize, r2: f32) -> Option<usize> {
    if found.len() < k || k < 2 {
        return None;
    }
    found.iter().position(|&(_, d2)| d2 == r2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boundary_photon_is_left_out_only_when_k_were_found() {
        let found = [(0u32, 0.1f32), (1, 0.4), (2, 0.2)];
        assert_eq!(boundary_photon(&found, 3, 0.4), Some(1));
        assert_eq!(boundary_photon(&found, 4, 0.4), None);
    }
}
