//! `lumis bench --rays SCENE`: the rays a path tracer casts in a scene,
//! traced again through the built-in BVH (and Embree, with the `embree`
//! feature), so the two are compared on identical, realistic rays rather
//! than on a synthetic mesh alone.
//!
//! The rays come from paths walked with the scene's own camera, BSDFs and
//! light sampling: every path segment is a closest-hit ray, and every
//! non-specular vertex casts one shadow ray towards a sampled light point.
//! Only the hit is timed (no surface geometry), as `lumis bench`'s mesh rays.

use crate::measure::{median, single_thread};
use anyhow::{Context, Result};
use lumis_math::{Pcg32, Vec2};
use lumis_render::bsdf::TransportMode;
use lumis_render::geometry::ray::spawn_ray;
use lumis_render::geometry::Ray;
use lumis_render::integrator::lighting::shadow_ray;
use lumis_render::load::{load_path, Overrides};
use lumis_render::scene::Scene;
use std::path::Path;
use std::time::Instant;

/// Closest-hit rays (every path segment) and shadow rays of `paths` paths
/// of at most `max_depth` bounces through random pixels. Deterministic.
pub fn harvest(scene: &Scene, paths: usize, max_depth: u32, seed: u64) -> (Vec<Ray>, Vec<Ray>) {
    let mut rng = Pcg32::new(seed, 0xb1a5);
    let (w, h) = scene.camera.resolution;
    let (mut closest, mut shadow) = (Vec::new(), Vec::new());
    for _ in 0..paths {
        let p_film = Vec2::new(rng.next_f32() * w as f32, rng.next_f32() * h as f32);
        let mut ray = scene
            .camera
            .generate_ray(p_film, Vec2::new(rng.next_f32(), rng.next_f32()));
        for _ in 0..=max_depth {
            closest.push(ray);
            let Some(hit) = scene.intersect_bvh(&ray) else {
                break;
            };
            let wo = -ray.d;
            let bsdf = scene.bsdf(&hit, wo);
            if !bsdf.is_delta() {
                if let Some((li, _)) = scene.light_sampler.sample(rng.next_f32()) {
                    let u = Vec2::new(rng.next_f32(), rng.next_f32());
                    let light = &scene.lights[li as usize];
                    if let Some(ls) = light.sample_li(&scene.shapes, hit.geom.p, u) {
                        shadow.push(shadow_ray(hit.geom.p, hit.geom.ng, &ls));
                    }
                }
            }
            let (uc, u) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
            let Some(bs) = bsdf.sample(wo, uc, u, TransportMode::Radiance) else {
                break;
            };
            ray = spawn_ray(hit.geom.p, hit.geom.ng, bs.wi);
        }
    }
    (closest, shadow)
}

/// Rays per second (millions) of one timed pass of `trace` over `rays`.
fn rate(rays: &[Ray], mut trace: impl FnMut(&Ray) -> bool) -> f64 {
    let t = Instant::now();
    let mut hits = 0usize;
    for r in rays {
        hits += trace(r) as usize;
    }
    std::hint::black_box(hits);
    rays.len() as f64 / t.elapsed().as_secs_f64() / 1e6
}

pub fn run(scene_path: &Path, quick: bool) -> Result<()> {
    let l = load_path(scene_path, &Overrides::default())
        .map_err(|d| anyhow::anyhow!("{d}"))
        .with_context(|| format!("loading {}", scene_path.display()))?;
    let scene = l.scene;
    let max_depth = l.options.integrator.max_depth().min(64);
    let paths = if quick { 20_000 } else { 100_000 };
    let reps = if quick { 3 } else { 7 };
    let (closest, shadow) = harvest(&scene, paths, max_depth, 1);
    // Embree beside the built-in BVH, which `closest_found` and `occluded`
    // below use whatever the scene's backend.
    #[cfg(feature = "embree")]
    let scene = {
        let mut s = scene;
        s.use_embree(true);
        s
    };
    outln!(
        "lumis bench --rays {} ({paths} paths, max depth {max_depth}: {} closest-hit rays, {} shadow rays; 1 thread, medians of {reps} passes alternating the backends)",
        scene_path.display(),
        closest.len(),
        shadow.len()
    );
    let ours_closest = |r: &Ray| {
        lumis_render::accel::closest_found(&scene.shapes, &scene.world, &scene.instances, r)
            .is_some()
    };
    let ours_any =
        |r: &Ray| lumis_render::accel::occluded(&scene.shapes, &scene.world, &scene.instances, r);
    #[cfg(feature = "embree")]
    let em = scene.embree.as_ref().expect("built above");
    #[cfg(feature = "embree")]
    let other = Some(|rays: &[Ray], any: bool| {
        if any {
            rate(rays, |r| em.occluded(r))
        } else {
            rate(rays, |r| em.closest_t(r).is_some())
        }
    });
    #[cfg(not(feature = "embree"))]
    let other: Option<fn(&[Ray], bool) -> f64> = None;
    for (label, rays, any) in [
        ("closest hit", &closest, false),
        ("shadow rays", &shadow, true),
    ] {
        let (mut ours, mut theirs) = (Vec::new(), Vec::new());
        single_thread(|| {
            for _ in 0..reps {
                ours.push(if any {
                    rate(rays, ours_any)
                } else {
                    rate(rays, ours_closest)
                });
                if let Some(f) = &other {
                    theirs.push(f(rays, any));
                }
            }
        });
        let ours = median(ours);
        if theirs.is_empty() {
            outln!("| {label}, lumis BVH | {ours:.2} Mrays/s |");
        } else {
            let theirs = median(theirs);
            outln!(
                "| {label}, lumis BVH / Embree 3 | {ours:.2} / {theirs:.2} Mrays/s (lumis/Embree {:.2}) |",
                ours / theirs
            );
        }
    }
    Ok(())
}
