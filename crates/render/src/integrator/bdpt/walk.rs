//! The two subpaths: from the camera (radiance transport) and from a light
//! (importance transport), each a random walk that records its vertices'
//! throughputs and forward and reverse densities. No Russian roulette:
//! `maxdepth` bounds both, so every strategy's density is what the MIS
//! weights compute.

use super::vertex::{to_area, Kind, Vertex};
use crate::bsdf::TransportMode;
use crate::geometry::ray::spawn_ray;
use crate::geometry::Ray;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler};

/// Where a camera subpath ended: the escaped ray (for infinite lights)
/// and the previous vertex's BSDF density of its direction.
pub struct Escape {
    pub ray: Ray,
    pub pdf: f32,
    /// The ray left the camera or a delta bounce (no light sample could
    /// have found what it sees).
    pub specular: bool,
}

/// The camera subpath of `ray` (the driver's camera ray) with up to
/// `max_verts` vertices, camera included.
pub fn camera_path(
    scene: &Scene,
    ray: Ray,
    margin: lumis_math::Vec2,
    sampler: &mut Sampler,
    max_verts: usize,
    path: &mut Vec<Vertex>,
    rays: &mut crate::integrator::RayCounts,
) -> Option<Escape> {
    path.clear();
    path.push(Vertex::camera(ray.o));
    let pdf_dir = scene.camera.pdf_dir(ray.o, ray.d, margin);
    rays.camera += 1;
    walk(
        scene,
        ray,
        Rgb::WHITE,
        pdf_dir,
        sampler,
        max_verts,
        TransportMode::Radiance,
        path,
        rays,
    )
}

/// A light subpath with up to `max_verts` vertices, light included; empty
/// when the chosen light is at infinity (those take part through light
/// sampling and escaped camera rays only).
pub fn light_path(
    scene: &Scene,
    sampler: &mut Sampler,
    max_verts: usize,
    path: &mut Vec<Vertex>,
    rays: &mut crate::integrator::RayCounts,
) {
    path.clear();
    let (ul, u1, u2) = (sampler.get_1d(), sampler.get_2d(), sampler.get_2d());
    if max_verts == 0 {
        return;
    }
    let Some((li, pmf)) = scene.light_sampler.sample(ul) else {
        return;
    };
    let light = &scene.lights[li as usize];
    if light.is_infinite() {
        return;
    }
    let Some(le) = light.sample_le(&scene.shapes, u1, u2) else {
        return;
    };
    if le.pdf_pos == 0.0 || le.pdf_dir == 0.0 || le.le.is_black() {
        return;
    }
    // The ray's origin: the sampled point (offset off an area light).
    path.push(Vertex::light(li, le.ray.o, le.n, pmf * le.pdf_pos));
    let beta = le.flux_weight() / pmf;
    walk(
        scene,
        le.ray,
        beta,
        le.pdf_dir,
        sampler,
        max_verts,
        TransportMode::Importance,
        path,
        rays,
    );
}

/// Extends `path` (holding the first vertex) along `ray` while it has
/// fewer than `max_verts` vertices; `pdf_dir` is the solid-angle density
/// of `ray`'s direction at the last vertex.
#[allow(clippy::too_many_arguments)]
fn walk(
    scene: &Scene,
    mut ray: Ray,
    mut beta: Rgb,
    mut pdf_dir: f32,
    sampler: &mut Sampler,
    max_verts: usize,
    mode: TransportMode,
    path: &mut Vec<Vertex>,
    rays: &mut crate::integrator::RayCounts,
) -> Option<Escape> {
    let mut specular = true;
    while path.len() < max_verts {
        if path.len() > 1 {
            rays.indirect += 1;
        }
        let Some(hit) = scene.intersect(&ray) else {
            return (mode == TransportMode::Radiance).then_some(Escape {
                ray,
                pdf: pdf_dir,
                specular,
            });
        };
        let wo = -ray.d;
        let bsdf = scene.bsdf(&hit, wo);
        let prev_p = path.last().expect("a subpath starts with one vertex").p;
        let mut v = Vertex {
            kind: Kind::Surface,
            p: hit.geom.p,
            ng: hit.geom.ng,
            ns: hit.geom.ns,
            beta,
            pdf_fwd: 0.0,
            pdf_rev: 0.0,
            delta: false,
            bsdf: Some(bsdf),
            wo,
            light: hit.light,
            uv: hit.geom.uv,
        };
        v.pdf_fwd = to_area(pdf_dir, prev_p, &v);
        path.push(v);
        if path.len() == max_verts {
            break;
        }
        let (uc, u) = (sampler.get_1d(), sampler.get_2d());
        let Some(bs) = bsdf.sample(wo, uc, u, mode) else {
            break;
        };
        if bs.pdf == 0.0 || bs.f.is_black() {
            break;
        }
        beta *= bs.weight(hit.geom.ns);
        if !beta.is_finite() || beta.is_black() {
            break;
        }
        let n = path.len();
        let (fwd, rev) = if bs.delta {
            path[n - 1].delta = true;
            (0.0, 0.0)
        } else {
            let back = match mode {
                TransportMode::Radiance => TransportMode::Importance,
                TransportMode::Importance => TransportMode::Radiance,
            };
            (bs.pdf, bsdf.pdf(bs.wi, wo, back))
        };
        pdf_dir = fwd;
        specular = bs.delta;
        let cur_p = path[n - 1].p;
        path[n - 2].pdf_rev = to_area(rev, cur_p, &path[n - 2]);
        ray = spawn_ray(hit.geom.p, hit.geom.ng, bs.wi);
    }
    None
}
