//! One level of the acceleration structure: a BVH over primitives, with the
//! primitives (and the triangles' vertices) stored in leaf order. The world's
//! own primitives form one level; each instanced object forms another.

use super::mem::prefetch_lines;
use super::tri4::{PacketRay, TriPackets, PADDING};
use super::{Bvh, PrimInfo};
use crate::geometry::triangle::{triangle_geometry_at, triangle_point_at};
use crate::geometry::{Aabb, Prim, Ray, Shapes, SurfaceGeom};
use lumis_math::{Vec2, Vec3};

#[derive(Clone, Debug, Default)]
pub struct PrimBvh {
    /// Primitives in BVH leaf order.
    pub prims: Vec<PrimInfo>,
    /// A triangle's corners' vertex indices, by its index in `prims`
    /// (zeros for the others): a hit's geometry reads them from here, in
    /// leaf order and prefetched with the hit's record, rather than from
    /// its mesh's index list, a second dependent cache miss.
    corners: Vec<[u32; 3]>,
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
        let prims: Vec<PrimInfo> = bvh
            .order
            .iter()
            .filter(|&&i| i != PADDING)
            .map(|&i| prims[i as usize])
            .collect();
        let corners = prims
            .iter()
            .map(|p| match p.prim {
                Prim::Triangle { mesh, tri } => shapes.meshes[mesh as usize].corners(tri),
                _ => [0; 3],
            })
            .collect();
        bvh.order = Vec::new();
        PrimBvh {
            prims,
            corners,
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
            + self.corners.len() * std::mem::size_of::<[u32; 3]>()
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
                prefetch_lines::<1>(self.corners.as_ptr().wrapping_add(id as usize) as *const u8);
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
        match self.prims[h.slot as usize].prim {
            Prim::Triangle { mesh, .. } => triangle_geometry_at(
                &shapes.meshes[mesh as usize],
                self.corners[h.slot as usize],
                h.uv.x,
                h.uv.y,
            ),
            p => shapes.geometry(p, ray, h.t, h.uv),
        }
    }

    /// A hit's point and geometric normal, as [`PrimBvh::geometry`] gives
    /// them, for triangles and spheres ([`Shapes::point_normal`]).
    #[inline]
    pub fn point_normal(&self, shapes: &Shapes, h: &LevelHit, ray: &Ray) -> Option<(Vec3, Vec3)> {
        match self.prims[h.slot as usize].prim {
            Prim::Triangle { mesh, .. } => Some(triangle_point_at(
                &shapes.meshes[mesh as usize],
                self.corners[h.slot as usize],
                h.uv.x,
                h.uv.y,
            )),
            p => shapes.point_normal(p, ray, h.t, h.uv),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::bench::bumpy_sphere;
    use crate::accel::NO_LIGHT;
    use lumis_math::Pcg32;

    #[test]
    fn hits_have_their_meshs_geometry_bit_for_bit() {
        // Vertex normals, so the shading normal reads the corners too.
        let mut mesh = bumpy_sphere(2000, 3);
        let normals = mesh.positions.iter().map(|p| p.normalize()).collect();
        mesh.normals = Some(normals);
        let n = mesh.indices.len() as u32 / 3;
        let shapes = Shapes {
            meshes: vec![mesh],
            ..Default::default()
        };
        let prims = (0..n)
            .map(|tri| PrimInfo {
                prim: Prim::Triangle { mesh: 0, tri },
                material: 0,
                light: NO_LIGHT,
            })
            .collect();
        let level = PrimBvh::build(&shapes, prims);
        let mut rng = Pcg32::new(5, 0);
        let mut hits = 0;
        for _ in 0..500 {
            let o = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 6.0 - 3.0;
            let ray = Ray::new(o, -o.normalize());
            let Some(h) = level.closest(&shapes, &ray) else {
                continue;
            };
            hits += 1;
            let prim = level.prims[h.slot as usize].prim;
            let want = shapes.geometry(prim, &ray, h.t, h.uv);
            let got = level.geometry(&shapes, &h, &ray);
            assert_eq!(format!("{got:?}"), format!("{want:?}"));
            let pn = level.point_normal(&shapes, &h, &ray).unwrap();
            assert_eq!(pn, shapes.point_normal(prim, &ray, h.t, h.uv).unwrap());
        }
        assert!(hits > 400, "{hits} hits");
    }
}
