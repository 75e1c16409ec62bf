//! Sampling points on shapes, by area and by solid angle from a reference point.

use super::triangle::{barycentric_point, triangle_point};
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

/// A triangle without vertex normals, ready to be sampled by area many
/// times (an area light's photons): its corners, normal and density,
/// computed once. [`FlatTriangle::sample`] gives [`sample_area`]'s points
/// bit for bit.
#[derive(Clone, Copy, Debug)]
pub struct FlatTriangle {
    corners: [Vec3; 3],
    n: Vec3,
    pdf: f32,
}

impl FlatTriangle {
    /// None unless `prim` is a triangle of a mesh without normals.
    pub fn new(shapes: &Shapes, prim: Prim) -> Option<FlatTriangle> {
        let Prim::Triangle { mesh, tri } = prim else {
            return None;
        };
        let m = &shapes.meshes[mesh as usize];
        if m.normals.is_some() {
            return None;
        }
        // Without vertex normals the normal is the same at every point.
        let (_, n) = triangle_point(m, tri, 1.0 / 3.0, 1.0 / 3.0);
        Some(FlatTriangle {
            corners: m.vertices(tri),
            n,
            pdf: 1.0 / m.area(tri),
        })
    }

    /// The corners, which bound every sampled point, and the normal.
    pub fn corners_and_normal(&self) -> ([Vec3; 3], Vec3) {
        (self.corners, self.n)
    }

    #[inline]
    pub fn sample(&self, u: Vec2) -> ShapePoint {
        let (b0, b1) = lumis_math::sampling::square_to_uniform_triangle(u);
        ShapePoint {
            p: barycentric_point(self.corners, b1, 1.0 - b0 - b1),
            n: self.n,
            pdf: self.pdf,
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::TriangleMesh;

    #[test]
    fn flat_triangles_sample_the_points_of_sample_area() {
        let mesh = |flip: bool, normals: Option<Vec<Vec3>>| TriangleMesh {
            positions: vec![
                Vec3::new(0.3, -1.0, 2.0),
                Vec3::new(1.7, 0.2, 1.1),
                Vec3::new(-0.4, 0.9, 0.35),
            ],
            normals,
            uvs: None,
            indices: vec![0, 1, 2],
            flip_normals: flip,
        };
        let shapes = Shapes {
            meshes: vec![
                mesh(false, None),
                mesh(true, None),
                mesh(false, Some(vec![Vec3::Z; 3])),
            ],
            ..Shapes::default()
        };
        let prim = |mesh| Prim::Triangle { mesh, tri: 0 };
        assert!(
            FlatTriangle::new(&shapes, prim(2)).is_none(),
            "vertex normals vary"
        );
        for m in 0..2 {
            let flat = FlatTriangle::new(&shapes, prim(m)).unwrap();
            for i in 0..1000u32 {
                let u = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 + 0.5) / 1000.0);
                let (a, b) = (flat.sample(u), sample_area(&shapes, prim(m), u));
                assert_eq!((a.p, a.n, a.pdf), (b.p, b.n, b.pdf), "mesh {m}, u {u:?}");
            }
        }
    }
}
