//! Vertex merging: a camera vertex's estimate from the light vertices
//! within the pass's radius, each weighted against every other strategy,
//! and the automatic first radius.

use super::VcmRun;
use crate::bsdf::TransportMode;
use crate::integrator::bdpt::mis;
use crate::integrator::bdpt::vertex::{Kind, Vertex};
use crate::scene::Scene;
use lumis_math::{Rgb, Vec2};

/// The merges at every camera vertex past the lens: `sum f beta_light /
/// (pi r^2 N)` over the light vertices within `r`, each with its MIS weight.
pub fn all(run: &VcmRun, camera: &[Vertex], margin: Vec2) -> Rgb {
    let mut l = Rgb::BLACK;
    if run.eta <= 0.0 {
        return l;
    }
    let depth = run.bdpt.max_depth as usize;
    for i in 1..camera.len() {
        let pt = &camera[i];
        if pt.kind != Kind::Surface || !pt.connectible() {
            continue;
        }
        let mut sum = Rgb::BLACK;
        run.paths.within(pt.p, run.radius, |light| {
            let y = light.last().expect("a light vertex");
            // The path's vertices: the light subpath's and the camera's
            // up to `pt`, which share the merged vertex.
            if light.len() + i > depth + 2 {
                return;
            }
            let f = pt.f(y.wo, TransportMode::Radiance);
            let c = f * y.beta;
            if c.is_black() || !c.is_finite() {
                return;
            }
            let w = mis::merge_weight(run.scene, margin, light, &camera[..=i], run.eta);
            sum += c * w;
        });
        l += pt.beta * sum / run.eta;
    }
    l
}

/// One pixel's footprint (the side of its square) at the median distance
/// of the first hits of a grid of camera rays (1 if none hits).
pub fn footprint_radius(scene: &Scene) -> f32 {
    let cam = &scene.camera;
    let (w, h) = cam.resolution;
    const GRID: u32 = 16;
    let mut sides = Vec::new();
    for gy in 0..GRID {
        for gx in 0..GRID {
            let p = Vec2::new(
                (gx as f32 + 0.5) / GRID as f32 * w as f32,
                (gy as f32 + 0.5) / GRID as f32 * h as f32,
            );
            let ray = cam.generate_ray(p, Vec2::new(0.5, 0.5));
            let Some(hit) = scene.intersect(&ray) else {
                continue;
            };
            let pdf = cam.pdf_dir(ray.o, ray.d, Vec2::ZERO);
            if pdf > 0.0 {
                let solid_angle = 1.0 / (pdf * w as f32 * h as f32);
                sides.push((hit.geom.p - ray.o).length() * solid_angle.sqrt());
            }
        }
    }
    if sides.is_empty() {
        return 1.0;
    }
    sides.sort_by(f32::total_cmp);
    sides[sides.len() / 2]
}
