//! All of a scene's shapes, and every per-primitive dispatch on [`Prim`]:
//! the rest of the renderer asks [`Shapes`] about a primitive (its bounds,
//! area, intersection, surface geometry) instead of matching on the kind.
//! Sampling points on a primitive is in `sample.rs` and `square_map.rs`.

use super::triangle::{triangle_geometry, triangle_point};
use super::{Aabb, Cylinder, Disk, Prim, Ray, Sphere, SurfaceGeom, TriangleMesh};
use lumis_math::{Vec2, Vec3};

/// Big shape data, referenced by `u32` ids.
#[derive(Clone, Debug, Default)]
pub struct Shapes {
    pub meshes: Vec<TriangleMesh>,
    pub spheres: Vec<Sphere>,
    pub disks: Vec<Disk>,
    pub cylinders: Vec<Cylinder>,
}

impl Shapes {
    pub fn bounds(&self, p: Prim) -> Aabb {
        match p {
            Prim::Triangle { mesh, tri } => self.meshes[mesh as usize].bounds(tri),
            Prim::Sphere(i) => self.spheres[i as usize].bounds(),
            Prim::Disk(i) => self.disks[i as usize].bounds(),
            Prim::Cylinder(i) => self.cylinders[i as usize].bounds(),
        }
    }

    /// Hit distance in (0, tmax) on an analytic shape (`None` for triangles,
    /// which the acceleration structures test themselves).
    #[inline]
    pub fn intersect_analytic(&self, p: Prim, r: &Ray, tmax: f32) -> Option<f32> {
        match p {
            Prim::Sphere(i) => self.spheres[i as usize].intersect(r, tmax),
            Prim::Disk(i) => self.disks[i as usize].intersect(r, tmax),
            Prim::Cylinder(i) => self.cylinders[i as usize].intersect(r, tmax),
            Prim::Triangle { .. } => None,
        }
    }

    /// A triangle's three vertices (`None` for the analytic shapes).
    #[inline]
    pub fn triangle_vertices(&self, p: Prim) -> Option<[Vec3; 3]> {
        match p {
            Prim::Triangle { mesh, tri } => Some(self.meshes[mesh as usize].vertices(tri)),
            _ => None,
        }
    }

    /// Surface geometry of a hit at distance `t` along `ray` (in the
    /// primitive's own space); `b` holds the barycentrics (b1, b2) of a
    /// triangle hit and is unused otherwise.
    pub fn geometry(&self, p: Prim, ray: &Ray, t: f32, b: Vec2) -> SurfaceGeom {
        match p {
            Prim::Triangle { mesh, tri } => {
                triangle_geometry(&self.meshes[mesh as usize], tri, b.x, b.y)
            }
            Prim::Sphere(i) => self.spheres[i as usize].geometry_at(ray.at(t)),
            Prim::Disk(i) => self.disks[i as usize].geometry_at(ray.at(t)),
            Prim::Cylinder(i) => self.cylinders[i as usize].geometry_at(ray.at(t)),
        }
    }

    /// The point and geometric normal of [`Shapes::geometry`], bit for bit,
    /// for triangles and spheres (the shapes whose rest costs most); `None`
    /// for the others.
    #[inline]
    pub fn point_normal(&self, p: Prim, ray: &Ray, t: f32, b: Vec2) -> Option<(Vec3, Vec3)> {
        match p {
            Prim::Triangle { mesh, tri } => {
                Some(triangle_point(&self.meshes[mesh as usize], tri, b.x, b.y))
            }
            Prim::Sphere(i) => Some(self.spheres[i as usize].point_normal_at(ray.at(t))),
            _ => None,
        }
    }

    /// Bytes of vertex, index, normal and uv data and the analytic shapes.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let mesh = |m: &TriangleMesh| {
            m.positions.len() * size_of::<lumis_math::Vec3>()
                + m.normals
                    .as_ref()
                    .map_or(0, |n| n.len() * size_of::<lumis_math::Vec3>())
                + m.uvs
                    .as_ref()
                    .map_or(0, |u| u.len() * size_of::<lumis_math::Vec2>())
                + m.indices.len() * 4
        };
        self.meshes.iter().map(mesh).sum::<usize>()
            + self.spheres.len() * size_of::<Sphere>()
            + self.disks.len() * size_of::<Disk>()
            + self.cylinders.len() * size_of::<Cylinder>()
    }

    pub fn area(&self, p: Prim) -> f32 {
        match p {
            Prim::Triangle { mesh, tri } => self.meshes[mesh as usize].area(tri),
            Prim::Sphere(i) => self.spheres[i as usize].area(),
            Prim::Disk(i) => self.disks[i as usize].area(),
            Prim::Cylinder(i) => self.cylinders[i as usize].area(),
        }
    }

    /// Area of the primitive's footprint in uv space: pbrt's default uvs
    /// for triangles without them, the unit square for quadrics.
    pub fn uv_area(&self, p: Prim) -> f32 {
        match p {
            Prim::Triangle { mesh, tri } => {
                let m = &self.meshes[mesh as usize];
                let Some(uv) = &m.uvs else {
                    return 0.5;
                };
                let i = 3 * tri as usize;
                let [a, b, c] = [0, 1, 2].map(|k| uv[m.indices[i + k] as usize]);
                0.5 * (b - a).perp_dot(c - a).abs()
            }
            Prim::Sphere(_) | Prim::Disk(_) | Prim::Cylinder(_) => 1.0,
        }
    }
}
