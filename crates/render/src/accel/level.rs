//! One level of the acceleration structure: a BVH over primitives, with the
//! primitives (and the triangles' vertices) stored in leaf order. The world's
//! own primitives form one level; each instanced object forms another.

use super::mem::prefetch_lines;
use super::tri4::{PacketRay, TriPackets, PADDING};
use super::{Bvh, PrimInfo};
use crate::geometry::{Aabb, Prim, Ray, Shapes, SurfaceGeom};
use lumis_math::Vec2;

#[derive(Clone, Debug, Default)]
pub struct PrimBvh {
    /// Primitives in BVH leaf order.
    pub prims: Vec<PrimInfo>,
    /// The leaves' slots in packets of four: the triangles' vertices, and
    /// each lane's index into `prims`.
    packets: TriPackets,
    bvh: Bvh,
}

/// A hit inside one level: distance, index into the level's `prims`, and
/// the surface parameters (barycentrics b1, b2 for triangles).
#[derive(Clone, Copy, Debug)]
pub struct LevelHit {
    pub t: f32,
    pub slot: u32,
    pub uv: Vec2,
}

impl PrimBvh {
    pub fn build(shapes: &Shapes, prims: Vec<PrimInfo>) -> PrimBvh {
        let boxes: Vec<Aabb> = prims.iter().map(|p| shapes.bounds(p.prim)).collect();
        // Analytic shapes each get a leaf: their boxes skip them cheaply,
        // and a test of one costs about a packet of four triangles.
        let analytic = |i: usize| !matches!(prims[i].prim, Prim::Triangle { .. });
        let mut bvh = Bvh::build_aligned(&boxes, 4, analytic);
        // Each lane's id: its primitive's index in the leaf-ordered `prims`.
        let mut next = 0u32;
        let packets = TriPackets::build(&bvh.order, |i| {
            next += 1;
            (next - 1, shapes.triangle_vertices(prims[i as usize].prim))
        });
        let prims = bvh
            .order
            .iter()
            .filter(|&&i| i != PADDING)
            .map(|&i| prims[i as usize])
            .collect();
        bvh.order = Vec::new();
        PrimBvh {
            prims,
            packets,
            bvh,
        }
    }

    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    pub fn is_empty(&self) -> bool {
        self.prims.is_empty()
    }

    /// Bytes of the BVH, the leaf-ordered primitives and the triangle packets.
    pub fn memory_bytes(&self) -> usize {
        self.bvh.memory_bytes()
            + self.prims.len() * std::mem::size_of::<PrimInfo>()
            + self.packets.memory_bytes()
    }

    #[inline(always)]
    fn analytic(&self, shapes: &Shapes, id: u32, r: &Ray, tmax: f32) -> Option<f32> {
        shapes.intersect_analytic(self.prims[id as usize].prim, r, tmax)
    }

    /// Closest hit in (0, ray.tmax).
    #[inline]
    pub fn closest(&self, shapes: &Shapes, ray: &Ray) -> Option<LevelHit> {
        let pr = PacketRay::new(ray);
        let mut uv = Vec2::ZERO;
        let (t, slot) = self.bvh.closest_leaves(
            ray,
            |start, count, r, tmax| {
                let (t, id, b) =
                    self.packets
                        .closest((start, count), r, &pr, tmax, |id, r, tmax| {
                            self.analytic(shapes, id, r, tmax)
                        })?;
                // The hit's record is read next (material, light, geometry):
                // start loading it while the traversal finishes.
                prefetch_lines::<1>(self.prims.as_ptr().wrapping_add(id as usize) as *const u8);
                uv = b;
                Some((t, id))
            },
            |start| self.packets.address(start),
        )?;
        Some(LevelHit { t, slot, uv })
    }

    /// Whether anything blocks the ray in (0, ray.tmax).
    #[inline]
    pub fn any(&self, shapes: &Shapes, ray: &Ray) -> bool {
        let pr = PacketRay::new(ray);
        self.bvh.any_leaves(
            ray,
            |start, count, r, tmax| {
                self.packets
                    .any((start, count), r, &pr, tmax, |id, r, tmax| {
                        self.analytic(shapes, id, r, tmax).is_some()
                    })
            },
            |start| self.packets.address(start),
        )
    }

    /// Surface geometry of a hit, in this level's space.
    pub fn geometry(&self, shapes: &Shapes, h: &LevelHit, ray: &Ray) -> SurfaceGeom {
        shapes.geometry(self.prims[h.slot as usize].prim, ray, h.t, h.uv)
    }
}
