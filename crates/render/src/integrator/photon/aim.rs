//! Aiming caustic photons at perfectly specular objects (an equivalent of
//! Jensen's projection maps): caustic photons leave area, point and spot
//! lights only in the cones subtended by the bounding spheres of specular
//! shapes. Every caustic path starts with a hit on a specular shape, so
//! nothing is lost; each photon's flux is divided by the density it was
//! really sampled with, so photons no longer have equal power and the seed's
//! q_1 uses each photon's own flux (`N L_e cos DeltaA / (Phi alpha)` with
//! `Phi / N` replaced by the flux the photon carries).

use crate::geometry::{offset_ray_origin, transform_box, Aabb, Ray};
use crate::light::Light;
use crate::scene::Scene;
use lumis_math::sampling::{
    square_to_uniform_cone, square_to_uniform_sphere, uniform_cone_pdf, UNIFORM_SPHERE_PDF,
};
use lumis_math::{Frame, Rgb, Vec2, Vec3};
use std::collections::BTreeMap;

/// Bounding spheres of the specular shapes.
#[derive(Clone, Debug, Default)]
pub struct Targets {
    spheres: Vec<(Vec3, f32)>,
}

impl Targets {
    pub fn from_scene(scene: &Scene) -> Targets {
        // One box per shape (a whole mesh, a sphere, a disk), in a stable
        // order; an instanced object's boxes are placed by each instance.
        let shape_boxes = |prims: &[crate::scene::PrimInfo]| {
            let mut boxes: BTreeMap<(u8, u32), Aabb> = BTreeMap::new();
            for p in prims {
                if !scene.materials[p.material as usize].is_specular() {
                    continue;
                }
                let b = boxes.entry(p.prim.shape()).or_insert(Aabb::EMPTY);
                *b = b.union(&scene.shapes.bounds(p.prim));
            }
            boxes.into_values().collect::<Vec<Aabb>>()
        };
        let mut boxes = shape_boxes(&scene.world.prims);
        let objects: Vec<Vec<Aabb>> = scene
            .instances
            .objects
            .iter()
            .map(|o| shape_boxes(&o.prims))
            .collect();
        for inst in &scene.instances.instances {
            let xf = &inst.world_from_object;
            boxes.extend(
                objects[inst.object as usize]
                    .iter()
                    .map(|b| transform_box(xf, b)),
            );
        }
        Targets {
            spheres: boxes
                .iter()
                .map(|b| b.bounding_sphere())
                .filter(|s| s.1 > 0.0)
                .collect(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.spheres.is_empty()
    }

    /// Cosine of the half-angle of target `t` seen from `from`; None if `from` is inside it.
    fn cos_max(&self, from: Vec3, t: usize) -> Option<(Vec3, f32)> {
        let (c, r) = self.spheres[t];
        let d = c - from;
        let d2 = d.length_squared();
        if d2 <= r * r {
            return None;
        }
        Some((d / d2.sqrt(), (1.0 - r * r / d2).max(0.0).sqrt()))
    }

    /// A direction towards a target chosen uniformly.
    pub fn sample(&self, from: Vec3, uc: f32, u: Vec2) -> Vec3 {
        let t = ((uc * self.spheres.len() as f32) as usize).min(self.spheres.len() - 1);
        match self.cos_max(from, t) {
            None => square_to_uniform_sphere(u),
            Some((axis, cos_max)) => {
                Frame::from_normal(axis).to_world(square_to_uniform_cone(u, cos_max))
            }
        }
    }

    /// Density of [`Targets::sample`] for direction `w` from `from`.
    pub fn pdf(&self, from: Vec3, w: Vec3) -> f32 {
        let n = self.spheres.len() as f32;
        let mut p = 0.0;
        for t in 0..self.spheres.len() {
            p += match self.cos_max(from, t) {
                None => UNIFORM_SPHERE_PDF,
                Some((axis, cos_max)) if w.dot(axis) >= cos_max => uniform_cone_pdf(cos_max),
                Some(_) => 0.0,
            };
        }
        p / n
    }
}

/// An aimed emission: the ray, the flux it carries divided by its density
/// (including the light-choice probability `pmf`) and the emitted radiance. None for lights that are
/// not aimed (distant, infinite: the caller uses ordinary emission).
pub fn aimed_emission(
    scene: &Scene,
    targets: &Targets,
    light: &Light,
    pmf: f32,
    u_pos: Vec2,
    uc: f32,
    u_dir: Vec2,
) -> Option<Option<(Ray, Rgb, Rgb)>> {
    let emit =
        |from: Vec3, n: Vec3, le: &dyn Fn(Vec3) -> Rgb, pdf_pos: f32| -> Option<(Ray, Rgb, Rgb)> {
            let w = targets.sample(from, uc, u_dir);
            let pdf_dir = targets.pdf(from, w);
            let l = le(w);
            if pdf_dir <= 0.0 || l.is_black() {
                return None;
            }
            let cos = if n == Vec3::ZERO { 1.0 } else { n.dot(w).abs() };
            let side = if n.dot(w) < 0.0 { -n } else { n };
            let o = if n == Vec3::ZERO {
                from
            } else {
                offset_ray_origin(from, side)
            };
            Some((Ray::new(o, w), l * (cos / (pdf_pos * pdf_dir * pmf)), l))
        };
    Some(match light {
        Light::Area(a) => {
            let sp = a.sample_point(&scene.shapes, u_pos);
            emit(sp.p, sp.n, &|w| a.l(sp.n, sp.uv, w), sp.pdf)
        }
        Light::Point(p) => emit(p.pos, Vec3::ZERO, &|_| p.intensity, 1.0),
        Light::Goniometric(g) => emit(g.pos, Vec3::ZERO, &|w| g.i(w), 1.0),
        Light::Spot(s) => emit(s.pos, Vec3::ZERO, &|w| s.i(w), 1.0),
        Light::Distant(_) | Light::Infinite(_) | Light::Image(_) => return None,
    })
}

/// Luminance of the flux (times N) a caustic photon would carry had it left
/// light `li` at `p` (normal `n`) in direction `w`: what a gather ray that
/// reached the light there needs for its q_1. The light's own emission
/// densities, with the aimed direction density when photons are aimed.
pub fn emitted_flux(
    scene: &Scene,
    targets: Option<&Targets>,
    li: u32,
    p: Vec3,
    n: Vec3,
    w: Vec3,
    le_lum: f32,
) -> f32 {
    let pmf = scene.light_sampler.pmf(li);
    let light = &scene.lights[li as usize];
    // Only area-light photons are aimed (and need the density).
    let aimed_pdf = match light {
        Light::Area(_) => targets.map(|t| t.pdf(p, w)),
        _ => None,
    };
    light.emitted_flux(&scene.shapes, pmf, p, n, w, le_lum, aimed_pdf)
}
