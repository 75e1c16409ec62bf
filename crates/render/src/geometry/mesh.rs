use super::Aabb;
use lumis_math::{Vec2, Vec3};

/// Triangle mesh in world space. Vertex data lives here once; triangles are
/// referenced by `(mesh id, triangle index)`.
#[derive(Clone, Debug, Default)]
pub struct TriangleMesh {
    pub positions: Vec<Vec3>,
    pub normals: Option<Vec<Vec3>>,
    pub uvs: Option<Vec<Vec2>>,
    pub indices: Vec<u32>,
    /// Flip geometric (and shading) normals: ReverseOrientation xor a handedness swap.
    pub flip_normals: bool,
}

impl TriangleMesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    #[inline]
    pub fn vertices(&self, tri: u32) -> [Vec3; 3] {
        self.corners(tri).map(|i| self.positions[i as usize])
    }

    /// The vertex indices of triangle `tri`'s corners.
    #[inline]
    pub fn corners(&self, tri: u32) -> [u32; 3] {
        let i = 3 * tri as usize;
        [self.indices[i], self.indices[i + 1], self.indices[i + 2]]
    }

    pub fn bounds(&self, tri: u32) -> Aabb {
        let [a, b, c] = self.vertices(tri);
        let mut bb = Aabb::from_point(a);
        bb.grow(b);
        bb.grow(c);
        bb
    }

    pub fn area(&self, tri: u32) -> f32 {
        let [a, b, c] = self.vertices(tri);
        0.5 * (b - a).cross(c - a).length()
    }
}
