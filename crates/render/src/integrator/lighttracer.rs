//! Light tracing (pbrt-v4's `lightpath`): every camera sample traces one
//! path from a light and connects each of its vertices that is not purely
//! specular to the camera, splatting the contribution where it lands on the
//! film. Unbiased for every path a camera connection can see, which makes
//! it the oracle for caustics from point, spot and distant lights (`L S+ D
//! E`), which `path` cannot render. It cannot see what only a specular
//! bounce shows the camera (`L ... S E`: a light seen in a mirror or through
//! glass, glass itself), nor infinite lights seen directly.
//!
//! With `N` light paths, one per camera sample of the rendered pixels, the
//! film divides each pixel's splats by the samples per pixel; splats carry
//! the camera's importance `W_e`, which integrates to one over the whole
//! film, so a crop window's share of the paths is made up by the ratio of
//! the film's pixels to the crop's.

use super::driver::SampleCx;
use crate::bsdf::TransportMode;
use crate::geometry::ray::{spawn_ray, spawn_ray_to};
use crate::light::Light;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler, Vec3};

/// One light path of at most `max_depth` scattering events, connected to
/// the camera at the light (area lights) and at every non-delta surface
/// vertex; contributions go to `cx`'s splats, scaled by `scale`.
pub fn trace(scene: &Scene, sampler: &mut Sampler, max_depth: u32, scale: f32, cx: &mut SampleCx) {
    let Some((li, pmf)) = scene.light_sampler.sample(sampler.get_1d()) else {
        return;
    };
    let light = &scene.lights[li as usize];
    let (u1, u2) = (sampler.get_2d(), sampler.get_2d());
    let Some(le) = light.sample_le(&scene.shapes, u1, u2) else {
        return;
    };
    // An area light's own point seen by the camera. The emission's origin
    // is offset to the side it leaves from (a two-sided light picks one
    // side, each with probability 1/2), so the camera is connected on that
    // side only, twice as strongly for a two-sided light.
    if let Light::Area(area) = light {
        let p = le.ray.o;
        if let Some(c) = scene
            .camera
            .sample_wi(p, sampler.get_2d(), cx.filter.radius)
        {
            let cos = le.n.dot(c.wi);
            if cos > 0.0 {
                let sides = if area.two_sided { 2.0 } else { 1.0 };
                let l = le.le * (sides * c.we * cos / (pmf * le.pdf_pos * c.pdf));
                connect(scene, p, le.n, &c, l * scale, cx);
            }
        }
    }
    let mut beta = le.flux_weight() / pmf;
    if !beta.is_finite() || beta.is_black() {
        return;
    }
    let mut ray = le.ray;
    for depth in 1..=max_depth {
        cx.rays.indirect += 1;
        let Some(hit) = scene.intersect(&ray) else {
            return;
        };
        let wo = -ray.d;
        let bsdf = scene.bsdf(&hit, wo);
        let (p, ns) = (hit.geom.p, hit.geom.ns);
        if !bsdf.is_delta() {
            if let Some(c) = scene
                .camera
                .sample_wi(p, sampler.get_2d(), cx.filter.radius)
            {
                let f = bsdf.eval(wo, c.wi, TransportMode::Importance);
                if !f.is_black() {
                    let l = beta * f * (c.wi.dot(ns).abs() * c.we / c.pdf);
                    connect(scene, p, hit.geom.ng, &c, l * scale, cx);
                }
            }
        }
        if depth == max_depth {
            return;
        }
        let Some(bs) = bsdf.sample(
            wo,
            sampler.get_1d(),
            sampler.get_2d(),
            TransportMode::Importance,
        ) else {
            return;
        };
        let weight = bs.weight(ns);
        // Russian roulette with survival = the bounce's transmittance (as
        // photon tracing): the path's weight keeps its luminance.
        let survive = weight.luminance().min(1.0);
        if !(survive > 0.0) || sampler.get_1d() >= survive {
            return;
        }
        beta = beta * weight / survive;
        ray = spawn_ray(p, hit.geom.ng, bs.wi);
    }
}

/// Splats `l` at the camera sample's raster position if nothing blocks the
/// segment from `p` (normal `ng`) to the lens.
fn connect(
    scene: &Scene,
    p: Vec3,
    ng: Vec3,
    c: &crate::camera::CameraWi,
    l: Rgb,
    cx: &mut SampleCx,
) {
    if l.is_black() || !l.is_finite() {
        return;
    }
    cx.rays.shadow += 1;
    if !scene.occluded(&spawn_ray_to(p, ng, c.p_lens)) {
        cx.splat_at(c.p_raster, l);
    }
}
