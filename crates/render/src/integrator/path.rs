//! Unbiased path tracing: next-event estimation, MIS (power heuristic)
//! between light and BSDF sampling, Russian roulette. Scenes with
//! participating media take the volumetric tracer of `volpath.rs`.

use super::lighting::{emitted_mis, escaped_mis, sample_direct};
use crate::bsdf::{SurfaceBsdf, TransportMode};
use crate::geometry::ray::spawn_ray;
use crate::geometry::Ray;
use crate::scene::Hit;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler, Vec3};

pub fn li(
    scene: &Scene,
    mut ray: Ray,
    sampler: &mut Sampler,
    max_depth: u32,
    rays: &mut super::RayCounts,
) -> Rgb {
    if scene.has_media() {
        return super::volpath::li(scene, ray, sampler, max_depth, rays);
    }
    let mut l = Rgb::BLACK;
    let mut st = PathState::new();
    let mut depth = 0u32;
    loop {
        if depth == 0 {
            rays.camera += 1;
        } else {
            rays.indirect += 1;
        }
        let count_fully = depth == 0 || st.specular_bounce;
        let Some(hit) = scene.intersect(&ray) else {
            l += st.beta * escaped_mis(scene, &ray, st.p_prev, st.pdf_prev, count_fully);
            break;
        };
        l += st.beta * emitted_mis(scene, &hit, &ray, st.p_prev, st.pdf_prev, count_fully);
        if depth == max_depth {
            break;
        }
        depth += 1;
        let bsdf = scene.bsdf(&hit, -ray.d);
        let wo = -ray.d;
        if !bsdf.is_delta() {
            l += st.beta * sample_direct(scene, &hit, &bsdf, wo, sampler, rays);
        }
        let Some(wi) = st.bounce(&hit, &bsdf, wo, sampler) else {
            break;
        };
        ray = spawn_ray(hit.geom.p, hit.geom.ng, wi);
        if !roulette(&mut st.beta, st.eta_scale, depth, sampler) {
            break;
        }
    }
    l
}

/// What a path carries from one vertex to the next: its throughput,
/// whether the last bounce was specular, the radiance scaling of
/// refractions (which roulette leaves out), and the previous vertex with
/// the density it sampled the direction by (for emission's MIS weight).
/// Shared with `volpath`.
pub(super) struct PathState {
    pub beta: Rgb,
    pub specular_bounce: bool,
    pub eta_scale: f32,
    pub p_prev: Vec3,
    pub pdf_prev: f32,
}

impl PathState {
    pub fn new() -> PathState {
        PathState {
            beta: Rgb::WHITE,
            specular_bounce: false,
            eta_scale: 1.0,
            p_prev: Vec3::ZERO,
            pdf_prev: 0.0,
        }
    }

    /// Samples the BSDF at `hit` (three sampler dimensions) and moves past
    /// it: the new direction, or `None` where the path ends.
    #[inline]
    pub fn bounce(
        &mut self,
        hit: &Hit,
        bsdf: &SurfaceBsdf,
        wo: Vec3,
        sampler: &mut Sampler,
    ) -> Option<Vec3> {
        let uc = sampler.get_1d();
        let u = sampler.get_2d();
        let bs = bsdf.sample(wo, uc, u, TransportMode::Radiance)?;
        if bs.pdf == 0.0 || bs.f.is_black() {
            return None;
        }
        self.beta *= bs.weight(hit.geom.ns);
        self.specular_bounce = bs.delta;
        self.pdf_prev = bs.pdf;
        self.p_prev = hit.geom.p;
        if bs.transmission {
            self.eta_scale *= bs.eta * bs.eta;
        }
        Some(bs.wi)
    }
}

/// Russian roulette from the second bounce on, on the throughput without
/// refraction's radiance scaling; false when the path ends (or its
/// throughput is not finite). Shared with `volpath`.
#[inline]
pub(super) fn roulette(beta: &mut Rgb, eta_scale: f32, depth: u32, sampler: &mut Sampler) -> bool {
    let rr = (*beta * eta_scale).max_component();
    if rr < 1.0 && depth > 1 {
        let q = (1.0 - rr).max(0.0);
        if sampler.get_1d() < q {
            return false;
        }
        *beta /= 1.0 - q;
    }
    beta.is_finite()
}
