//! Rays, bounding boxes and shapes (triangle meshes with their subdivision,
//! spheres, disks, cylinders): each shape's intersection, surface geometry
//! and area, [`Shapes`] holding all of a scene's shapes with the dispatch
//! on [`Prim`], and sampling points on a primitive. The bottom layer of the
//! renderer: it depends on `lumis_math` only.

pub mod aabb;
pub mod cylinder;
pub mod disk;
pub mod mesh;
pub mod ray;
pub mod sample;
pub mod shapes;
pub mod sphere;
pub mod square_map;
pub mod subdiv;
pub mod triangle;

pub use aabb::{transform_box, Aabb};
pub use cylinder::Cylinder;
pub use disk::Disk;
pub use mesh::TriangleMesh;
pub use ray::{offset_ray_origin, Ray};
pub use shapes::Shapes;
pub use sphere::Sphere;

use lumis_math::{Vec2, Vec3};

/// A geometric primitive: an id into the scene's vectors, never an owned copy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Prim {
    /// Triangle `tri` of mesh `mesh`.
    Triangle {
        mesh: u32,
        tri: u32,
    },
    Sphere(u32),
    Disk(u32),
    Cylinder(u32),
}

impl Prim {
    /// Which shape the primitive belongs to: its kind (0 triangle mesh,
    /// 1 sphere, 2 disk, 3 cylinder) and the index of the mesh or quadric.
    pub fn shape(self) -> (u8, u32) {
        match self {
            Prim::Triangle { mesh, .. } => (0, mesh),
            Prim::Sphere(i) => (1, i),
            Prim::Disk(i) => (2, i),
            Prim::Cylinder(i) => (3, i),
        }
    }
}

/// What an intersection routine reports before shading data is computed.
#[derive(Clone, Copy, Debug)]
pub struct RawHit {
    pub t: f32,
    /// Surface parameters: barycentrics (b1, b2) for triangles, (u, v) otherwise.
    pub uv: Vec2,
    pub prim_index: u32,
}

/// Full surface description at a hit point, in world space.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceGeom {
    pub p: Vec3,
    /// Geometric normal, oriented as the shape is (flipped by ReverseOrientation
    /// and by handedness-swapping transforms, as in pbrt).
    pub ng: Vec3,
    /// Shading normal, on the same side as `ng`.
    pub ns: Vec3,
    /// Partial derivatives of the position with respect to the surface's
    /// (u, v) parameters, as pbrt defines them (not normalised).
    pub dpdu: Vec3,
    pub dpdv: Vec3,
    pub uv: Vec2,
}

/// Azimuth of an object-space point about the z axis, in [0, 2 pi)
/// (spheres and cylinders).
#[inline]
pub(crate) fn phi_of(p: Vec3) -> f32 {
    let phi = p.y.atan2(p.x);
    if phi < 0.0 {
        phi + 2.0 * lumis_math::PI
    } else {
        phi
    }
}
