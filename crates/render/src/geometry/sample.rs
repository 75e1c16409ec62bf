//! Sampling points on shapes, by area and by solid angle from a reference point.

use super::triangle::triangle_point;
use super::{Prim, Shapes};
use lumis_math::sampling::{square_to_uniform_cone, square_to_uniform_sphere, uniform_cone_pdf};
use lumis_math::{safe_sqrt, Frame, Vec2, Vec3};

/// A point on a shape with its normal and density (per area or per solid angle).
#[derive(Clone, Copy, Debug)]
pub struct ShapePoint {
    pub p: Vec3,
    pub n: Vec3,
    pub pdf: f32,
}

/// Uniform point by area; `pdf` per unit area.
pub fn sample_area(shapes: &Shapes, prim: Prim, u: Vec2) -> ShapePoint {
    match prim {
        Prim::Triangle { mesh, tri } => {
            let m = &shapes.meshes[mesh as usize];
            let (b0, b1) = lumis_math::sampling::square_to_uniform_triangle(u);
            let (p, n) = triangle_point(m, tri, b1, 1.0 - b0 - b1);
            ShapePoint {
                p,
                n,
                pdf: 1.0 / m.area(tri),
            }
        }
        Prim::Sphere(i) if shapes.spheres[i as usize].is_partial() => {
            let s = &shapes.spheres[i as usize];
            let (p, n) = s.sample_area(u);
            ShapePoint {
                p,
                n,
                pdf: 1.0 / s.area(),
            }
        }
        Prim::Sphere(i) => {
            let s = &shapes.spheres[i as usize];
            let d = square_to_uniform_sphere(u);
            let g = s.geometry_at(s.center + d * s.world_radius);
            ShapePoint {
                p: g.p,
                n: g.ng,
                pdf: 1.0 / s.area(),
            }
        }
        Prim::Disk(i) => {
            let d = &shapes.disks[i as usize];
            let (p, n) = d.sample_area(u);
            ShapePoint {
                p,
                n,
                pdf: 1.0 / d.area(),
            }
        }
        Prim::Cylinder(i) => {
            let c = &shapes.cylinders[i as usize];
            let (p, n) = c.sample_area(u);
            ShapePoint {
                p,
                n,
                pdf: 1.0 / c.area(),
            }
        }
    }
}

/// Point seen from `p_ref`; `pdf` per unit solid angle at `p_ref`.
pub fn sample_solid_angle(shapes: &Shapes, prim: Prim, p_ref: Vec3, u: Vec2) -> Option<ShapePoint> {
    if let Prim::Sphere(i) = prim {
        let s = &shapes.spheres[i as usize];
        // A partial sphere does not fill the cone: sampled by area below.
        let dc2 = (s.center - p_ref).length_squared();
        let r2 = s.world_radius * s.world_radius;
        if dc2 > r2 * 1.0001 && !s.is_partial() {
            // Outside: sample the cone of directions the sphere subtends.
            let sin2_max = r2 / dc2;
            let cos_max = safe_sqrt(1.0 - sin2_max);
            let frame = Frame::from_normal((s.center - p_ref).normalize());
            let w = frame.to_world(square_to_uniform_cone(u, cos_max));
            // Closest intersection of the direction with the sphere.
            let oc = p_ref - s.center;
            let b = oc.dot(w);
            let c = oc.length_squared() - r2;
            let disc = (b * b - c).max(0.0);
            let t = -b - disc.sqrt();
            let g = s.geometry_at(p_ref + w * t.max(0.0));
            return Some(ShapePoint {
                p: g.p,
                n: g.ng,
                pdf: uniform_cone_pdf(cos_max),
            });
        }
    }
    let a = sample_area(shapes, prim, u);
    let d = a.p - p_ref;
    let dist2 = d.length_squared();
    if dist2 == 0.0 {
        return None;
    }
    let wi = d / dist2.sqrt();
    let cos = a.n.dot(-wi).abs();
    if cos == 0.0 {
        return None;
    }
    Some(ShapePoint {
        pdf: a.pdf * dist2 / cos,
        ..a
    })
}

/// Density of `sample_solid_angle` for the light point `p` with normal `n`.
pub fn pdf_solid_angle(shapes: &Shapes, prim: Prim, p_ref: Vec3, p: Vec3, n: Vec3) -> f32 {
    if let Prim::Sphere(i) = prim {
        let s = &shapes.spheres[i as usize];
        // A partial sphere does not fill the cone: sampled by area below.
        let dc2 = (s.center - p_ref).length_squared();
        let r2 = s.world_radius * s.world_radius;
        if dc2 > r2 * 1.0001 && !s.is_partial() {
            return uniform_cone_pdf(safe_sqrt(1.0 - r2 / dc2));
        }
    }
    let d = p - p_ref;
    let dist2 = d.length_squared();
    let cos = n.dot(d).abs() / dist2.sqrt();
    if cos == 0.0 || dist2 == 0.0 {
        return 0.0;
    }
    dist2 / (cos * shapes.area(prim))
}
