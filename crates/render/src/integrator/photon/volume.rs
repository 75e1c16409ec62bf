//! `photon` in participating media: volumetric photon mapping with the
//! seed's two-technique weighting carried into the medium.
//!
//! Photons scatter in media (`trace.rs`) and are stored where they do: every
//! event in the global volume map, the first one after a purely specular
//! path (`L S+ V`, volumetric caustics) in the caustic volume map. A camera
//! path that scatters in a medium at `x` (delta tracking, as `path`) takes
//! the radiance scattered there towards the camera, `∫ p L_i`, as
//!
//! - direct light: next-event estimation with the transmittance to the
//!   light, weighted against the gather rays by the power heuristic;
//! - volumetric caustics: the caustic volume photons within a sphere of
//!   radius `r` (volume `DeltaV`), `Σ p(wo, w_j) Phi_j w_1 / (DeltaV
//!   sigma_s(x))`, **and** `m_2` phase-sampled gather rays that reach an
//!   emitter through specular surfaces, weighted `w_2`. The seed's weights
//!   stay as they are with `q_1 = N L_e sigma_s DeltaV / (Phi alpha)` (the
//!   expected number of photons of this path in the query volume per unit
//!   solid angle: photons scatter at a rate `sigma_s` per unit length, where
//!   on a surface `cos(theta) DeltaA` counts them) and `q_2 = m_2 p_phase`,
//!   `sigma_s` being the channels' mean (the rate photon tracing samples);
//! - the rest: the gather rays' first scattering point, read from the
//!   global maps (volume or surface).
//!
//! The photon estimate divides by `sigma_s(x)` because stored photons
//! sample `sigma_s` times the fluence; a channel without scattering has no
//! photons and gets nothing.

use super::gather::{query, PhotonCtx, SCRATCH};
use super::weights::{q1, q2, w1, Alpha};
use super::GLOBAL_RADIUS_SCALE;
use crate::geometry::Ray;
use crate::integrator::volpath::{self, Flight};
use crate::scene::Hit;
use lumis_math::{Pcg32, Rgb, Sampler, Vec3, PI};
use std::cell::RefCell;

thread_local! {
    /// The free flights' random stream of the camera sample being traced.
    static RNG: RefCell<Pcg32> = RefCell::new(Pcg32::new(0, 0));
}

/// Starts the flights' stream for a camera sample (two sampler dimensions).
pub(super) fn seed(sampler: &mut Sampler) {
    let stream = volpath::flight_stream(sampler);
    RNG.with(|r| *r.borrow_mut() = stream);
}

pub(super) fn with_rng<R>(f: impl FnOnce(&mut Pcg32) -> R) -> R {
    RNG.with(|r| f(&mut r.borrow_mut()))
}

/// [`volpath::advance`] with the camera sample's stream: flies `ray`
/// through media and across pure boundaries up to the next surface that
/// scatters (`hit`), or to a scattering or absorption in a medium.
pub(super) fn advance(
    ctx: &PhotonCtx,
    medium: &mut Option<u32>,
    ray: &mut Ray,
    hit: &mut Option<Hit>,
    beta: &mut Rgb,
    emitted: &mut Rgb,
    crossed: &mut u64,
) -> Flight {
    let scene = ctx.scene;
    with_rng(|rng| volpath::advance(scene, medium, ray, hit, rng, beta, Some(emitted), crossed))
}

/// Next-event estimation at a surface point through media, weighted
/// against `m2` BSDF-sampled gather rays.
#[allow(clippy::too_many_arguments)]
pub(super) fn direct_at_surface(
    ctx: &PhotonCtx,
    x: &Hit,
    bsdf: &crate::bsdf::SurfaceBsdf,
    wo: Vec3,
    medium: Option<u32>,
    m2: u32,
    sampler: &mut Sampler,
    rays: &mut crate::integrator::RayCounts,
) -> Rgb {
    let (scene, n) = (ctx.scene, m2 as f32);
    with_rng(|rng| volpath::direct_at_surface(scene, x, bsdf, wo, medium, n, sampler, rng, rays))
}

/// Light scattered towards `wo` at `x` in medium `m` (a camera path's
/// scattering event), without the throughput that brought it there.
#[allow(clippy::too_many_arguments)]
pub(super) fn shade_medium(
    ctx: &PhotonCtx,
    x: Vec3,
    wo: Vec3,
    m: u32,
    alpha: Alpha,
    m2: u32,
    depth: u32,
    sampler: &mut Sampler,
    rays: &mut crate::integrator::RayCounts,
) -> Rgb {
    let (scene, n) = (ctx.scene, m2 as f32);
    let phase = scene.media[m as usize].phase;
    let mut l = with_rng(|rng| volpath::direct_in_medium(scene, x, wo, m, n, sampler, rng, rays));
    let (lc, sigma_s, delta_v, alpha) = caustic_volume_photons(ctx, x, wo, m, alpha, m2);
    l += lc;
    if m2 == 0 {
        return l;
    }
    let mut gathered = Rgb::BLACK;
    for _ in 0..m2 {
        let Some(ps) = phase.sample(wo, sampler.get_2d()) else {
            continue;
        };
        let g = super::gather::Gather {
            origin: x,
            ray: Ray::new(x, ps.wi),
            medium: Some(m),
            pdf: ps.pdf,
            q1_cos: sigma_s,
            q1_measure: delta_v,
            alpha,
            m2,
            // No camera connections with media.
            inv_j: 0.0,
        };
        // The phase function is sampled exactly: its weight is 1.
        gathered += super::gather::trace_gather(ctx, &g, depth, sampler, rays);
    }
    l + gathered / m2 as f32
}

/// The volume of a query sphere of squared radius `r2`.
fn sphere_volume(r2: f32) -> f32 {
    4.0 / 3.0 * PI * r2 * r2.sqrt()
}

/// `sigma_s(x)`'s mean over the channels, and `1 / sigma_s` per channel (0
/// where a channel does not scatter).
fn scattering(ctx: &PhotonCtx, m: u32, x: Vec3) -> (f32, Rgb) {
    let s = ctx.scene.media[m as usize].point(x).sigma_s;
    (s.average(), s.map(|v| if v > 0.0 { 1.0 / v } else { 0.0 }))
}

/// The caustic volume photons' estimate at `x`, each weighted by `w_1`;
/// also `sigma_s` and `DeltaV` (what `q_1` counts photons over) and the
/// `alpha` the gather rays share.
fn caustic_volume_photons(
    ctx: &PhotonCtx,
    x: Vec3,
    wo: Vec3,
    m: u32,
    alpha: Alpha,
    m2: u32,
) -> (Rgb, f32, f32, f32) {
    let map = &ctx.maps.volume_caustic;
    let s = ctx.s;
    let phase = ctx.scene.media[m as usize].phase;
    let (sigma_s, inv_sigma_s) = scattering(ctx, m, x);
    SCRATCH.with(|cell| {
        let mut found = cell.borrow_mut();
        found.clear();
        let (r2, _) = query(
            ctx,
            map,
            x,
            |r| r.caustic_r2(x),
            ctx.maps.max_radius,
            &mut found,
        );
        let delta_v = sphere_volume(r2);
        let alpha = alpha.effective(0.0);
        if found.is_empty() || !(r2 > 0.0) {
            return (Rgb::BLACK, sigma_s, delta_v, alpha);
        }
        let n = map.emitted() as f64;
        let mut sum = Rgb::BLACK;
        for &(i, _) in found.iter() {
            let ph = map.photon(i);
            let wj = ph.dir();
            let f = phase.p(wo, wj);
            let q_1 = if ctx.maps.targets.is_some() {
                q1(
                    1.0,
                    ph.le(),
                    sigma_s,
                    delta_v,
                    ph.power().luminance(),
                    alpha,
                )
            } else {
                q1(n, ph.le(), sigma_s, delta_v, ctx.maps.phi, alpha)
            };
            let w = w1(q_1, q2(m2, phase.pdf(wo, wj)), s.caustics, s.heuristic);
            sum += ph.power() * (f * w);
        }
        (sum * inv_sigma_s / delta_v, sigma_s, delta_v, alpha)
    })
}

/// `∫ p L_i` at `x` in medium `m` from the global volume photons (a gather
/// ray's scattering point).
pub(super) fn global_in_scattering(ctx: &PhotonCtx, x: Vec3, wo: Vec3, m: u32) -> Rgb {
    let map = &ctx.maps.volume_global;
    let phase = ctx.scene.media[m as usize].phase;
    SCRATCH.with(|cell| {
        let mut found = cell.borrow_mut();
        found.clear();
        let max = ctx.maps.max_radius * GLOBAL_RADIUS_SCALE;
        let (r2, _) = query(ctx, map, x, |r| r.global_r2(x), max, &mut found);
        if found.is_empty() || !(r2 > 0.0) {
            return Rgb::BLACK;
        }
        let mut sum = Rgb::BLACK;
        for &(i, _) in found.iter() {
            let ph = map.photon(i);
            sum += ph.power() * phase.p(wo, ph.dir());
        }
        sum * scattering(ctx, m, x).1 / sphere_volume(r2)
    })
}
