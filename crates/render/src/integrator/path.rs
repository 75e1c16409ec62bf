//! Unbiased path tracing: next-event estimation, MIS (power heuristic)
//! between light and BSDF sampling, Russian roulette. Scenes with
//! participating media take the volumetric tracer of `volpath.rs`.

use super::lighting::{emitted_mis, escaped_mis, sample_direct};
use crate::bsdf::TransportMode;
use crate::geometry::ray::spawn_ray;
use crate::geometry::Ray;
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
    let mut beta = Rgb::WHITE;
    let mut specular_bounce = false;
    let mut eta_scale = 1.0f32;
    let mut p_prev = Vec3::ZERO;
    let mut pdf_prev = 0.0f32;
    let mut depth = 0u32;
    loop {
        if depth == 0 {
            rays.camera += 1;
        } else {
            rays.indirect += 1;
        }
        let Some(hit) = scene.intersect(&ray) else {
            l += beta * escaped_mis(scene, &ray, p_prev, pdf_prev, depth == 0 || specular_bounce);
            break;
        };
        l += beta
            * emitted_mis(
                scene,
                &hit,
                &ray,
                p_prev,
                pdf_prev,
                depth == 0 || specular_bounce,
            );
        if depth == max_depth {
            break;
        }
        depth += 1;
        let bsdf = scene.bsdf(&hit, -ray.d);
        let wo = -ray.d;
        if !bsdf.is_delta() {
            l += beta * sample_direct(scene, &hit, &bsdf, wo, sampler, rays);
        }
        let uc = sampler.get_1d();
        let u = sampler.get_2d();
        let Some(bs) = bsdf.sample(wo, uc, u, TransportMode::Radiance) else {
            break;
        };
        if bs.pdf == 0.0 || bs.f.is_black() {
            break;
        }
        beta *= bs.weight(hit.geom.ns);
        specular_bounce = bs.delta;
        pdf_prev = bs.pdf;
        p_prev = hit.geom.p;
        if bs.transmission {
            eta_scale *= bs.eta * bs.eta;
        }
        ray = spawn_ray(hit.geom.p, hit.geom.ng, bs.wi);
        if !roulette(&mut beta, eta_scale, depth, sampler) {
            break;
        }
    }
    l
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
