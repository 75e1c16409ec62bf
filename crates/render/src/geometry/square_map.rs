//! An area-preserving map from the unit square onto each primitive, and its
//! inverse: textured emitters sample a piecewise-constant density over the
//! square (`light/area_texture.rs`), so a point's area density is the square's
//! density divided by the primitive's area, and a hit point's density is
//! found by mapping it back.
//!
//! - triangles: Heitz's low-distortion square-to-triangle map (the one
//!   `sample_area` uses), inverted through the barycentrics of the point;
//! - spheres and cylinders: `z` and `phi` linear in the square (Archimedes);
//! - disks: `r^2` and `phi` linear (polar, not the concentric map).

use super::triangle::triangle_geometry;
use super::{phi_of, Prim, Shapes, SurfaceGeom};
use lumis_math::sampling::square_to_uniform_triangle;
use lumis_math::{Vec2, Vec3, PI};

/// The surface point (with its uv and normals) at square coordinates `u`.
pub fn square_to_surface(shapes: &Shapes, prim: Prim, u: Vec2) -> SurfaceGeom {
    match prim {
        Prim::Triangle { mesh, tri } => {
            let m = &shapes.meshes[mesh as usize];
            let (b0, b1) = square_to_uniform_triangle(u);
            triangle_geometry(m, tri, b1, 1.0 - b0 - b1)
        }
        Prim::Sphere(i) => {
            let s = &shapes.spheres[i as usize];
            let (p, _) = s.sample_area(u);
            s.geometry_at(p)
        }
        Prim::Cylinder(i) => {
            let c = &shapes.cylinders[i as usize];
            let (p, _) = c.sample_area(u);
            c.geometry_at(p)
        }
        Prim::Disk(i) => {
            let d = &shapes.disks[i as usize];
            let ri2 = (d.inner_radius / d.radius).powi(2);
            let r = d.radius * (ri2 + (1.0 - ri2) * u.x).max(0.0).sqrt();
            let phi = 2.0 * PI * u.y;
            let po = Vec3::new(r * phi.cos(), r * phi.sin(), d.height);
            d.geometry_at(d.object_to_world.point(po))
        }
    }
}

/// Square coordinates of the world point `p` on the primitive (the inverse
/// of [`square_to_surface`], clamped to the unit square).
pub fn surface_to_square(shapes: &Shapes, prim: Prim, p: Vec3) -> Vec2 {
    let u = match prim {
        Prim::Triangle { mesh, tri } => {
            let [p0, p1, p2] = shapes.meshes[mesh as usize].vertices(tri);
            let (b0, b1) = barycentrics(p0, p1, p2, p);
            // Heitz's map: b0 < b1 came from u.x < u.y.
            if b0 < b1 {
                Vec2::new(2.0 * b0, b1 + b0)
            } else {
                Vec2::new(b0 + b1, 2.0 * b1)
            }
        }
        Prim::Sphere(i) => {
            let s = &shapes.spheres[i as usize];
            let po = s.object_to_world.inv.transform_point3(p);
            let po = po * (s.radius / po.length().max(1e-30));
            let z = (po.z - s.zmin) / (s.zmax - s.zmin).max(1e-30);
            Vec2::new(z, phi_of(po) / s.phi_max.max(1e-30))
        }
        Prim::Cylinder(i) => {
            let c = &shapes.cylinders[i as usize];
            let po = c.object_to_world.inv.transform_point3(p);
            let z = (po.z - c.zmin) / (c.zmax - c.zmin).max(1e-30);
            Vec2::new(z, phi_of(po) / c.phi_max.max(1e-30))
        }
        Prim::Disk(i) => {
            let d = &shapes.disks[i as usize];
            let po = d.object_to_world.inv.transform_point3(p);
            let r2 = (po.x * po.x + po.y * po.y) / (d.radius * d.radius);
            let ri2 = (d.inner_radius / d.radius).powi(2);
            let x = (r2 - ri2) / (1.0 - ri2).max(1e-30);
            Vec2::new(x, phi_of(po) / (2.0 * PI))
        }
    };
    u.clamp(Vec2::ZERO, Vec2::ONE)
}

/// Weights of `p0` and `p1` in the point `p` of the triangle's plane.
fn barycentrics(p0: Vec3, p1: Vec3, p2: Vec3, p: Vec3) -> (f32, f32) {
    // Solve p - p2 = b0 (p0 - p2) + b1 (p1 - p2) by least squares (exact in the plane).
    let (e0, e1, d) = (p0 - p2, p1 - p2, p - p2);
    let (a00, a01, a11) = (e0.dot(e0), e0.dot(e1), e1.dot(e1));
    let (r0, r1) = (d.dot(e0), d.dot(e1));
    let det = a00 * a11 - a01 * a01;
    if det.abs() < 1e-30 {
        return (1.0 / 3.0, 1.0 / 3.0);
    }
    let b0 = (a11 * r0 - a01 * r1) / det;
    let b1 = (a00 * r1 - a01 * r0) / det;
    (b0.clamp(0.0, 1.0), b1.clamp(0.0, 1.0 - b0.clamp(0.0, 1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Cylinder, Disk, Sphere, TriangleMesh};
    use lumis_math::{Mat4, Transform};

    fn shapes() -> Shapes {
        let xf = Transform::new(
            Mat4::from_translation(Vec3::new(0.3, -1.0, 2.0))
                * Mat4::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.7)
                * Mat4::from_scale(Vec3::splat(1.5)),
        )
        .unwrap();
        Shapes {
            meshes: vec![TriangleMesh {
                positions: vec![
                    Vec3::new(-1.0, -1.0, 2.0),
                    Vec3::new(1.0, -1.0, 2.5),
                    Vec3::new(0.2, 1.0, 2.0),
                ],
                indices: vec![0, 1, 2],
                ..Default::default()
            }],
            spheres: vec![
                Sphere::new(xf, 0.8, false),
                Sphere::partial(xf, 1.0, -0.4, 0.9, 250.0, true),
            ],
            disks: vec![Disk::new(xf, 0.2, 1.2, 0.3, false)],
            cylinders: vec![Cylinder::new(xf, 0.7, -0.5, 1.0, 300.0, false)],
        }
    }

    fn prims() -> Vec<Prim> {
        vec![
            Prim::Triangle { mesh: 0, tri: 0 },
            Prim::Sphere(0),
            Prim::Sphere(1),
            Prim::Disk(0),
            Prim::Cylinder(0),
        ]
    }

    #[test]
    fn square_to_surface_and_back_is_the_identity() {
        let s = shapes();
        let mut rng = lumis_math::Pcg32::new(3, 3);
        for prim in prims() {
            for _ in 0..2000 {
                let u = Vec2::new(rng.next_f32(), rng.next_f32()) * 0.998 + Vec2::splat(0.001);
                let g = square_to_surface(&s, prim, u);
                let back = surface_to_square(&s, prim, g.p);
                assert!(
                    (back - u).abs().max_element() < 2e-3,
                    "{prim:?}: {u:?} -> {back:?}"
                );
            }
        }
    }

    /// Equal areas of the square map to equal areas of the surface: the
    /// parallelogram spanned by small steps has the same area everywhere.
    #[test]
    fn the_map_preserves_area() {
        let s = shapes();
        let h = 1e-3;
        for prim in prims() {
            let total = s.area(prim);
            for i in 1..8 {
                for j in 1..8 {
                    let u = Vec2::new(i as f32 / 8.0 + 0.013, j as f32 / 8.0 - 0.021);
                    let p = square_to_surface(&s, prim, u).p;
                    let px = square_to_surface(&s, prim, u + Vec2::new(h, 0.0)).p;
                    let py = square_to_surface(&s, prim, u + Vec2::new(0.0, h)).p;
                    let jac = (px - p).cross(py - p).length() / (h * h);
                    assert!(
                        (jac / total - 1.0).abs() < 0.02,
                        "{prim:?} at {u:?}: jacobian {jac} vs area {total}"
                    );
                }
            }
        }
    }
}
