//! The gather rays of a shading point found together: each ray's first
//! hit, then the radiance photons at the hits that read them looked up as
//! one batch, so that the lookups' cache misses (a grid cell, its
//! candidates, the irradiance found) overlap instead of following one
//! another. `gather.rs` then traces each ray on from its first hit; the
//! values are bit for bit those of one ray at a time.

use super::gather::{global_radius, PhotonCtx};
use super::radiance::BATCH;
use crate::geometry::Ray;
use crate::scene::LazyHit;
use lumis_math::{Rgb, Vec3, PI};

/// A gather ray's first hit and what the radiance photons said there.
pub(super) struct First {
    pub hit: Option<LazyHit>,
    /// On a plain diffuse surface: `Some(l)`, the light the radiance
    /// photons give towards the ray, or `None`, they do not cover the hit.
    /// Elsewhere (or without a hit) nothing was read.
    pub radiance: Option<Option<Rgb>>,
}

/// The first hit of each ray of `rays` (up to [`BATCH`]; `None` for no
/// ray) into `out`. Scenes with media do not come here: their rays start
/// with free flights.
pub(super) fn first_hits(ctx: &PhotonCtx, rays: &[Option<Ray>], out: &mut [Option<First>]) {
    assert!(rays.len() <= BATCH && out.len() == rays.len());
    let scene = ctx.scene;
    // The plain diffuse hits: (point, normal facing the ray) and (ray, albedo).
    let mut qs = [(Vec3::ZERO, Vec3::ZERO); BATCH];
    let mut of = [(0usize, Rgb::BLACK); BATCH];
    let mut m = 0;
    for (j, (o, ray)) in out.iter_mut().zip(rays).enumerate() {
        *o = ray.as_ref().map(|ray| {
            let hit = scene.intersect_lazy(ray);
            if let Some(pd) = hit.as_ref().and_then(|h| scene.plain_diffuse(h, ray)) {
                qs[m] = (pd.p, facing(pd.ng, -ray.d));
                of[m] = (j, pd.albedo);
                m += 1;
            }
            First {
                hit,
                radiance: None,
            }
        });
    }
    let mut e = [None; BATCH];
    if let Some(rp) = ctx.maps.radiance.as_ref() {
        rp.irradiance_each(&qs[..m], global_radius(ctx), &mut e[..m]);
    }
    for (&(j, albedo), e) in of[..m].iter().zip(e) {
        if let Some(f) = out[j].as_mut() {
            f.radiance = Some(e.map(|e| exitant(e, albedo)));
        }
    }
}

/// `ng` turned to the side of `wo`.
#[inline(always)]
pub(super) fn facing(ng: Vec3, wo: Vec3) -> Vec3 {
    if ng.dot(wo) < 0.0 {
        -ng
    } else {
        ng
    }
}

/// Light leaving a diffuse surface of `albedo` under irradiance `e`.
#[inline(always)]
pub(super) fn exitant(e: Rgb, albedo: Rgb) -> Rgb {
    e * albedo * (1.0 / PI)
}
