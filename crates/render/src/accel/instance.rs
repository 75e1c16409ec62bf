//! Object instancing: one bottom-level [`PrimBvh`] per object (its shapes
//! stored once, in object space) and a top-level BVH over the instances'
//! world bounds. Rays are carried into object space (same parameter `t`:
//! the direction is transformed, not renormalised) and hits are reported
//! in world space.

use super::level::{LevelHit, PrimBvh};
use super::{Bvh, PrimInfo};
use crate::geometry::{transform_box, Aabb, Ray, Shapes, SurfaceGeom};
use lumis_math::Transform;

/// One placement of an object.
#[derive(Clone, Copy, Debug)]
pub struct Instance {
    pub object: u32,
    pub world_from_object: Transform,
}

/// What the loader hands over: each object's primitives (in object space)
/// and the instances.
#[derive(Clone, Debug, Default)]
pub struct InstanceSet {
    pub objects: Vec<Vec<PrimInfo>>,
    pub instances: Vec<Instance>,
}

#[derive(Clone, Debug, Default)]
pub struct Instances {
    pub objects: Vec<PrimBvh>,
    /// In top-level BVH leaf order.
    pub instances: Vec<Instance>,
    bvh: Bvh,
}

/// A hit on an instance: the object-level hit and the instance's leaf slot.
#[derive(Clone, Copy, Debug)]
pub struct InstanceHit {
    pub hit: LevelHit,
    pub instance: u32,
}

impl Instances {
    pub fn build(shapes: &Shapes, set: InstanceSet) -> Instances {
        let objects: Vec<PrimBvh> = set
            .objects
            .into_iter()
            .map(|prims| PrimBvh::build(shapes, prims))
            .collect();
        let boxes: Vec<Aabb> = set
            .instances
            .iter()
            .map(|i| transform_box(&i.world_from_object, &objects[i.object as usize].bounds()))
            .collect();
        let mut bvh = Bvh::build(&boxes);
        let instances = bvh
            .order
            .iter()
            .map(|&i| set.instances[i as usize])
            .collect();
        bvh.order = Vec::new();
        Instances {
            objects,
            instances,
            bvh,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.instances.is_empty()
    }

    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    pub fn memory_bytes(&self) -> usize {
        self.objects.iter().map(|o| o.memory_bytes()).sum::<usize>()
            + self.bvh.memory_bytes()
            + self.instances.len() * std::mem::size_of::<Instance>()
    }

    #[inline]
    fn object_ray(inst: &Instance, r: &Ray, tmax: f32) -> Ray {
        let inv = &inst.world_from_object.inv;
        Ray {
            o: inv.transform_point3(r.o),
            d: inv.transform_vector3(r.d),
            tmax,
        }
    }

    /// Closest instance hit in (0, ray.tmax).
    pub fn closest(&self, shapes: &Shapes, ray: &Ray) -> Option<InstanceHit> {
        let mut best = None;
        self.bvh.closest_hinted(
            ray,
            |slot, r, tmax| {
                let inst = &self.instances[slot as usize];
                let ro = Self::object_ray(inst, r, tmax);
                let hit = self.objects[inst.object as usize].closest(shapes, &ro)?;
                best = Some(InstanceHit {
                    hit,
                    instance: slot,
                });
                Some(hit.t)
            },
            |start| self.address(start),
        )?;
        best
    }

    pub fn any(&self, shapes: &Shapes, ray: &Ray) -> bool {
        self.bvh.any_hinted(
            ray,
            |slot, r, tmax| {
                let inst = &self.instances[slot as usize];
                let ro = Self::object_ray(inst, r, tmax);
                self.objects[inst.object as usize].any(shapes, &ro)
            },
            |start| self.address(start),
        )
    }

    /// Where slot `start`'s instance is, for a prefetch (never read).
    #[inline(always)]
    fn address(&self, start: u32) -> *const u8 {
        self.instances.as_ptr().wrapping_add(start as usize) as *const u8
    }

    /// The primitive that was hit.
    pub fn info(&self, h: &InstanceHit) -> PrimInfo {
        let inst = &self.instances[h.instance as usize];
        self.objects[inst.object as usize].prims[h.hit.slot as usize]
    }

    /// The primitive that was hit, and its world-space geometry.
    pub fn geometry(&self, shapes: &Shapes, h: &InstanceHit, ray: &Ray) -> (PrimInfo, SurfaceGeom) {
        let inst = &self.instances[h.instance as usize];
        let obj = &self.objects[inst.object as usize];
        let ro = Self::object_ray(inst, ray, ray.tmax);
        let g = obj.geometry(shapes, &h.hit, &ro);
        let xf = &inst.world_from_object;
        // As pbrt-v4: normals go through the inverse transpose, keeping the
        // side the object-space normal was on.
        let geom = SurfaceGeom {
            p: xf.point(g.p),
            ng: xf.normal(g.ng).normalize(),
            ns: xf.normal(g.ns).normalize(),
            dpdu: xf.vector(g.dpdu),
            dpdv: xf.vector(g.dpdv),
            uv: g.uv,
        };
        (obj.prims[h.hit.slot as usize], geom)
    }
}
