//! One level of the acceleration structure: a BVH over primitives, with the
//! primitives (and the triangles' vertices) stored in leaf order. The world's
//! own primitives form one level; each instanced object forms another.

use super::{Bvh, PrimInfo};
use crate::geometry::triangle::{intersect_triangle, RayShear};
use crate::geometry::{Aabb, Ray, Shapes, SurfaceGeom};
use lumis_math::{Vec2, Vec3};

/// Tag in `PrimBvh::tri_verts` of a primitive that is not a triangle.
const ANALYTIC: u32 = 1;

#[derive(Clone, Debug, Default)]
pub struct PrimBvh {
    /// Primitives in BVH leaf order.
    pub prims: Vec<PrimInfo>,
    /// Per primitive in leaf order: the triangle's vertices, or `ANALYTIC`
    /// (then `prims` says which shape), so testing a triangle reads one array.
    tri_verts: Vec<([Vec3; 3], u32)>,
    bvh: Bvh,
}

/// A hit inside one level: distance, leaf slot, and the surface parameters
/// (barycentrics b1, b2 for triangles).
#[derive(Clone, Copy, Debug)]
pub struct LevelHit {
    pub t: f32,
    pub slot: u32,
    pub uv: Vec2,
}

impl PrimBvh {
    pub fn build(shapes: &Shapes, prims: Vec<PrimInfo>) -> PrimBvh {
        let boxes: Vec<Aabb> = prims.iter().map(|p| shapes.bounds(p.prim)).collect();
        let mut bvh = Bvh::build(&boxes);
        let prims: Vec<PrimInfo> = bvh.order.iter().map(|&i| prims[i as usize]).collect();
        let mut tri_verts = super::mem::huge_vec(prims.len());
        tri_verts.extend(
            prims
                .iter()
                .map(|p| match shapes.triangle_vertices(p.prim) {
                    Some(v) => (v, 0),
                    None => ([Vec3::ZERO; 3], ANALYTIC),
                }),
        );
        bvh.order = Vec::new();
        PrimBvh {
            prims,
            tri_verts,
            bvh,
        }
    }

    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    pub fn is_empty(&self) -> bool {
        self.prims.is_empty()
    }

    /// Bytes of the BVH, the leaf-ordered primitives and triangle vertices.
    pub fn memory_bytes(&self) -> usize {
        self.bvh.memory_bytes()
            + self.prims.len() * std::mem::size_of::<PrimInfo>()
            + self.tri_verts.len() * std::mem::size_of::<([Vec3; 3], u32)>()
    }

    /// Starts loading the triangle data of slots `start..start + count`.
    #[inline(always)]
    fn prefetch(&self, start: u32, count: u32) {
        if let Some(t) = self.tri_verts.get(start as usize..(start + count) as usize) {
            super::mem::prefetch(t);
        }
    }

    #[inline(always)]
    fn analytic(&self, shapes: &Shapes, slot: u32, r: &Ray, tmax: f32) -> Option<f32> {
        shapes.intersect_analytic(self.prims[slot as usize].prim, r, tmax)
    }

    /// Closest hit in (0, ray.tmax).
    #[inline]
    pub fn closest(&self, shapes: &Shapes, ray: &Ray) -> Option<LevelHit> {
        let sh = RayShear::new(ray.d);
        let mut uv = Vec2::ZERO;
        let (t, slot) = self.bvh.closest_hinted(
            ray,
            |slot, r, tmax| {
                let (v, kind) = &self.tri_verts[slot as usize];
                if *kind != ANALYTIC {
                    let (t, b1, b2) = intersect_triangle(r, &sh, v, tmax)?;
                    uv = Vec2::new(b1, b2);
                    return Some(t);
                }
                self.analytic(shapes, slot, r, tmax)
            },
            |start, count| self.prefetch(start, count),
        )?;
        Some(LevelHit { t, slot, uv })
    }

    /// Whether anything blocks the ray in (0, ray.tmax).
    #[inline]
    pub fn any(&self, shapes: &Shapes, ray: &Ray) -> bool {
        let sh = RayShear::new(ray.d);
        self.bvh.any_hinted(
            ray,
            |slot, r, tmax| {
                let (v, kind) = &self.tri_verts[slot as usize];
                if *kind != ANALYTIC {
                    return intersect_triangle(r, &sh, v, tmax).is_some();
                }
                self.analytic(shapes, slot, r, tmax).is_some()
            },
            |start, count| self.prefetch(start, count),
        )
    }

    /// Surface geometry of a hit, in this level's space.
    pub fn geometry(&self, shapes: &Shapes, h: &LevelHit, ray: &Ray) -> SurfaceGeom {
        shapes.geometry(self.prims[h.slot as usize].prim, ray, h.t, h.uv)
    }
}
