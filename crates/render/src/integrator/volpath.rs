//! `path` in scenes with participating media: unbiased volumetric path
//! tracing (pbrt-v4's `volpath` design, in RGB).
//!
//! - Free flights by delta tracking against each medium's majorants
//!   (`media::track`): at a tentative collision the medium's emission is
//!   added, then absorption, real scattering or a null collision is chosen
//!   with probabilities proportional to the channels' average coefficients,
//!   the throughput weighted per channel (no colour bias).
//! - Next-event estimation from surfaces and from scattering points, with
//!   the shadow ray's transmittance through media (exact in homogeneous
//!   media, ratio tracking in grids) and through pure boundaries (shapes
//!   with the `interface` material).
//! - MIS (power heuristic) between light sampling and BSDF or phase
//!   sampling on the directional densities alone, as Mitsuba 3's `volpath`:
//!   both techniques estimate the same transmittance-weighted integrand, so
//!   the weights need not include transmittance to stay unbiased.
//! - Rays keep their medium through surfaces that do not change it; at one
//!   that does, the side the ray leaves on picks the next.

use super::lighting::{emitted_mis, escaped_mis, sample_light, shadow_ray};
use super::path::{roulette, PathState};
use crate::bsdf::{SurfaceBsdf, TransportMode};
use crate::geometry::ray::{spawn_ray, spawn_ray_to};
use crate::geometry::Ray;
use crate::light::LiSample;
use crate::media::{track, Medium, MediumInterface};
use crate::scene::{Hit, Scene};
use lumis_math::mis::power_heuristic;
use lumis_math::{Pcg32, Rgb, Sampler, Vec3};

/// Boundary crossings allowed in one flight or shadow ray (guards against
/// rays caught between coincident boundaries).
pub(crate) const MAX_CROSSINGS: u32 = 256;

/// How a free flight ended.
pub(crate) enum Flight {
    /// Reached the surface (or escaped) with the throughput updated.
    Passed,
    Absorbed,
    /// Scattered at this point of the medium (throughput updated).
    Scattered(Vec3),
}

/// One free flight by delta tracking through `medium` along `o + t d` (`d`
/// unit) within `[0, tmax)`: `beta` takes each collision's per-channel
/// weight, and the medium's emission along the way is added to `emitted`
/// (times `beta`) when asked for. Used by `path` and by `photon`'s photons,
/// camera paths and gather rays.
pub(crate) fn fly(
    medium: &Medium,
    o: Vec3,
    d: Vec3,
    tmax: f32,
    rng: &mut Pcg32,
    beta: &mut Rgb,
    mut emitted: Option<&mut Rgb>,
) -> Flight {
    let mut flight = Flight::Passed;
    track::collisions(medium, o, d, tmax, rng, |rng, p, mp, maj| {
        if let Some(e) = emitted.as_deref_mut() {
            if !mp.le.is_black() {
                *e += *beta * mp.sigma_a * mp.le / maj;
            }
        }
        let pa = mp.sigma_a.average() / maj;
        let ps = mp.sigma_s.average() / maj;
        let u = rng.next_f32();
        if u < pa {
            flight = Flight::Absorbed;
            return false;
        }
        if u < pa + ps {
            *beta *= mp.sigma_s / (maj * ps);
            flight = Flight::Scattered(p);
            return false;
        }
        let sn = track::sigma_n(&mp, maj);
        let pn = sn.average() / maj;
        *beta *= sn / (maj * pn);
        if !beta.is_finite() || beta.is_black() {
            flight = Flight::Absorbed;
            return false;
        }
        true
    });
    flight
}

/// [`fly`] in medium `m` along `ray` (any length of direction) up to `hit`,
/// or without end.
fn fly_ray(
    scene: &Scene,
    m: u32,
    ray: &Ray,
    hit: Option<&Hit>,
    rng: &mut Pcg32,
    beta: &mut Rgb,
    emitted: Option<&mut Rgb>,
) -> Flight {
    let len = ray.d.length();
    let tmax = hit.map_or(f32::INFINITY, |h| h.t * len);
    fly(
        &scene.media[m as usize],
        ray.o,
        ray.d / len,
        tmax,
        rng,
        beta,
        emitted,
    )
}

/// The stream free flights draw from for one sample (they take an
/// unbounded number of random numbers): seeded from two of the sample's
/// own dimensions, as pbrt-v4 does, so images do not depend on threads.
pub(crate) fn flight_stream(sampler: &mut Sampler) -> Pcg32 {
    let bits = |s: &mut Sampler| s.get_1d().to_bits() as u64;
    let seed = (bits(sampler) << 32) | bits(sampler);
    Pcg32::new(lumis_math::rng::mix64(seed), 0)
}

/// Flies `ray` through media and across pure boundaries up to the next
/// surface that scatters (or out of the scene): `hit` becomes that
/// surface, `medium` and `ray` follow the crossings (each counted in
/// `crossed`), `beta` is weighted and the media's emission added to
/// `emitted` when asked for. Used by `photon` (photons, camera paths,
/// gather rays).
#[allow(clippy::too_many_arguments)]
pub(crate) fn advance(
    scene: &Scene,
    medium: &mut Option<u32>,
    ray: &mut Ray,
    hit: &mut Option<Hit>,
    rng: &mut Pcg32,
    beta: &mut Rgb,
    mut emitted: Option<&mut Rgb>,
    crossed: &mut u64,
) -> Flight {
    for _ in 0..MAX_CROSSINGS {
        if let Some(m) = *medium {
            let f = fly_ray(
                scene,
                m,
                ray,
                hit.as_ref(),
                rng,
                beta,
                emitted.as_deref_mut(),
            );
            if !matches!(f, Flight::Passed) {
                return f;
            }
        }
        match hit.as_ref() {
            Some(h) if scene.is_boundary(h) => {
                if let Some(mi) = scene.medium_interface(h) {
                    *medium = mi.towards(ray.d, h.geom.ng);
                }
                *ray = spawn_ray(h.geom.p, h.geom.ng, ray.d);
                *crossed += 1;
                *hit = scene.intersect(ray);
            }
            _ => break,
        }
    }
    Flight::Passed
}

pub fn li(
    scene: &Scene,
    mut ray: Ray,
    sampler: &mut Sampler,
    max_depth: u32,
    rays: &mut super::RayCounts,
) -> Rgb {
    let mut rng = flight_stream(sampler);
    let mut medium = scene.camera_medium;
    let mut l = Rgb::BLACK;
    let mut st = PathState::new();
    let mut depth = 0u32;
    let mut crossings = 0u32;
    let mut first = true;
    loop {
        if first {
            rays.camera += 1;
            first = false;
        } else {
            rays.indirect += 1;
        }
        let hit = scene.intersect(&ray);
        if let Some(m) = medium {
            let emit = (depth < max_depth).then_some(&mut l);
            match fly_ray(scene, m, &ray, hit.as_ref(), &mut rng, &mut st.beta, emit) {
                Flight::Absorbed => break,
                Flight::Scattered(p) => {
                    if depth == max_depth {
                        break;
                    }
                    depth += 1;
                    let wo = -(ray.d / ray.d.length());
                    l += st.beta * direct_in_medium(scene, p, wo, m, 1.0, sampler, &mut rng, rays);
                    let phase = scene.media[m as usize].phase;
                    let Some(ps) = phase.sample(wo, sampler.get_2d()) else {
                        break;
                    };
                    st.specular_bounce = false;
                    st.pdf_prev = ps.pdf;
                    st.p_prev = p;
                    ray = Ray::new(p, ps.wi);
                    if !roulette(&mut st.beta, st.eta_scale, depth, sampler) {
                        break;
                    }
                    continue;
                }
                Flight::Passed => {}
            }
        }
        let count_fully = depth == 0 || st.specular_bounce;
        let Some(hit) = hit else {
            l += st.beta * escaped_mis(scene, &ray, st.p_prev, st.pdf_prev, count_fully);
            break;
        };
        l += st.beta * emitted_mis(scene, &hit, &ray, st.p_prev, st.pdf_prev, count_fully);
        let mi = scene.medium_interface(&hit);
        if scene.is_boundary(&hit) {
            crossings += 1;
            if crossings > MAX_CROSSINGS {
                break;
            }
            if let Some(mi) = mi {
                medium = mi.towards(ray.d, hit.geom.ng);
            }
            ray = spawn_ray(hit.geom.p, hit.geom.ng, ray.d);
            continue;
        }
        if depth == max_depth {
            break;
        }
        depth += 1;
        let wo = -ray.d;
        let bsdf = scene.bsdf(&hit, wo);
        if !bsdf.is_delta() {
            l += st.beta
                * direct_at_surface(scene, &hit, &bsdf, wo, medium, 1.0, sampler, &mut rng, rays);
        }
        let Some(wi) = st.bounce(&hit, &bsdf, wo, sampler) else {
            break;
        };
        if let Some(mi) = mi {
            medium = mi.towards(wi, hit.geom.ng);
        }
        ray = spawn_ray(hit.geom.p, hit.geom.ng, wi);
        if !roulette(&mut st.beta, st.eta_scale, depth, sampler) {
            break;
        }
    }
    l
}

/// [`direct`] at a surface point in `medium` (the side the arriving ray
/// came in), for its BSDF, weighted against `n_scatter` BSDF samples.
#[allow(clippy::too_many_arguments)]
pub(crate) fn direct_at_surface(
    scene: &Scene,
    hit: &Hit,
    bsdf: &SurfaceBsdf,
    wo: Vec3,
    medium: Option<u32>,
    n_scatter: f32,
    sampler: &mut Sampler,
    rng: &mut Pcg32,
    rays: &mut super::RayCounts,
) -> Rgb {
    let ns = hit.geom.ns;
    let eval = |wi: Vec3| {
        let f = bsdf.eval(wo, wi, TransportMode::Radiance) * wi.dot(ns).abs();
        (f, bsdf.pdf(wo, wi, TransportMode::Radiance))
    };
    let at = Surface {
        ng: hit.geom.ng,
        interface: scene.medium_interface(hit),
    };
    direct(
        scene,
        hit.geom.p,
        Some(at),
        medium,
        eval,
        n_scatter,
        sampler,
        rng,
        rays,
    )
}

/// [`direct`] at a scattering point `p` of medium `m`, for its phase
/// function, weighted against `n_scatter` phase samples.
#[allow(clippy::too_many_arguments)]
pub(crate) fn direct_in_medium(
    scene: &Scene,
    p: Vec3,
    wo: Vec3,
    m: u32,
    n_scatter: f32,
    sampler: &mut Sampler,
    rng: &mut Pcg32,
    rays: &mut super::RayCounts,
) -> Rgb {
    let phase = scene.media[m as usize].phase;
    let eval = |wi: Vec3| {
        let v = phase.p(wo, wi);
        (Rgb::splat(v), v)
    };
    direct(scene, p, None, Some(m), eval, n_scatter, sampler, rng, rays)
}

/// The surface a shadow ray leaves from.
#[derive(Clone, Copy)]
struct Surface {
    ng: Vec3,
    interface: Option<MediumInterface>,
}

/// Next-event estimation at `p` (on a surface, or in a medium when `at` is
/// `None`): one light by power, one point on it, the transmittance to it,
/// weighted by the power heuristic against `n_scatter` scattering samples
/// (BSDF or phase) taken at the same point. `eval(wi)` gives the
/// scattering function (times the cosine on surfaces) and its sampling
/// density. Consumes three sampler dimensions.
#[allow(clippy::too_many_arguments)]
fn direct(
    scene: &Scene,
    p: Vec3,
    at: Option<Surface>,
    medium: Option<u32>,
    eval: impl Fn(Vec3) -> (Rgb, f32),
    n_scatter: f32,
    sampler: &mut Sampler,
    rng: &mut Pcg32,
    rays: &mut super::RayCounts,
) -> Rgb {
    let Some((ls, pmf)) = sample_light(scene, p, sampler) else {
        return Rgb::BLACK;
    };
    let (f, scatter_pdf) = eval(ls.wi);
    if f.is_black() {
        return Rgb::BLACK;
    }
    let (ray, medium) = match at {
        Some(s) => (
            shadow_ray(p, s.ng, &ls),
            s.interface.map_or(medium, |mi| mi.towards(ls.wi, s.ng)),
        ),
        None => (ray_to(p, &ls), medium),
    };
    let tr = transmittance(scene, ray, &ls, medium, rng, rays);
    if tr.is_black() {
        return Rgb::BLACK;
    }
    let light_pdf = pmf * ls.pdf;
    if ls.delta {
        return f * ls.li * tr / light_pdf;
    }
    let w = power_heuristic(1.0, light_pdf, n_scatter, scatter_pdf);
    f * ls.li * tr * (w / light_pdf)
}

/// A shadow ray from a point in a medium (no surface to offset from).
fn ray_to(p: Vec3, ls: &LiSample) -> Ray {
    if ls.infinite {
        Ray::new(p, ls.wi)
    } else {
        Ray {
            o: p,
            d: ls.p_light - p,
            tmax: 1.0 - 1e-4,
        }
    }
}

/// Transmittance along a shadow ray to the light sample: through media and
/// across pure boundaries, zero at any other surface.
fn transmittance(
    scene: &Scene,
    mut ray: Ray,
    ls: &LiSample,
    mut medium: Option<u32>,
    rng: &mut Pcg32,
    rays: &mut super::RayCounts,
) -> Rgb {
    let mut tr = Rgb::WHITE;
    for _ in 0..MAX_CROSSINGS {
        rays.shadow += 1;
        let hit = scene.intersect(&ray).filter(|h| h.t < ray.tmax);
        if let Some(m) = medium {
            let len = ray.d.length();
            let t_end = hit.as_ref().map_or(ray.tmax, |h| h.t) * len;
            tr *= track::transmittance(&scene.media[m as usize], ray.o, ray.d / len, t_end, rng);
            if tr.is_black() {
                return tr;
            }
        }
        let Some(h) = hit else {
            return tr;
        };
        if !scene.is_boundary(&h) {
            return Rgb::BLACK;
        }
        if let Some(mi) = scene.medium_interface(&h) {
            medium = mi.towards(ray.d, h.geom.ng);
        }
        ray = if ls.infinite {
            let mut r = spawn_ray(h.geom.p, h.geom.ng, ray.d);
            r.tmax = f32::INFINITY;
            r
        } else {
            spawn_ray_to(h.geom.p, h.geom.ng, ls.p_light)
        };
    }
    Rgb::BLACK
}
