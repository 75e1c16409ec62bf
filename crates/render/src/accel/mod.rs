//! Ray queries over [`Shapes`](crate::geometry::Shapes): a binned-SAH BVH in
//! pure Rust ([`Bvh`]), one level of it over primitives ([`PrimBvh`]),
//! object instancing ([`Instances`]), the per-primitive records they store
//! and the hits they report, the combined closest-hit and occlusion queries,
//! and the optional Embree backend. Built from shapes and primitive lists,
//! never from a scene: it depends on `geometry` only, and `scene` owns it.

pub mod bench;
mod build;
pub mod bvh;
#[cfg(feature = "embree")]
pub mod embree;
mod instance;
mod level;
pub mod mem;
mod prim;
mod tri4;

pub use bvh::Bvh;
pub use instance::{Instance, InstanceHit, InstanceSet, Instances};
pub use level::{LevelHit, PrimBvh};
pub use prim::{Hit, PrimInfo, NO_LIGHT};

use crate::geometry::{Ray, Shapes};

/// Closest hit along the ray over the world's primitives and the instances.
#[inline]
pub fn closest(shapes: &Shapes, world: &PrimBvh, instances: &Instances, ray: &Ray) -> Option<Hit> {
    let found = closest_found(shapes, world, instances, ray)?;
    Some(found.finish(shapes, world, instances, ray))
}

/// A closest hit before its geometry: enough to tell its primitive, whose
/// geometry [`Found::finish`] computes only for the hits that need it.
#[derive(Clone, Copy, Debug)]
pub enum Found {
    World(LevelHit),
    Instance(InstanceHit),
}

/// [`closest`] without the hit's geometry.
#[inline]
pub fn closest_found(
    shapes: &Shapes,
    world: &PrimBvh,
    instances: &Instances,
    ray: &Ray,
) -> Option<Found> {
    let world_hit = world.closest(shapes, ray);
    if !instances.is_empty() {
        let mut r = *ray;
        if let Some(h) = &world_hit {
            r.tmax = h.t;
        }
        if let Some(ih) = instances.closest(shapes, &r) {
            return Some(Found::Instance(ih));
        }
    }
    world_hit.map(Found::World)
}

impl Found {
    /// The primitive hit (its material, light and shape).
    #[inline]
    pub fn info(&self, world: &PrimBvh, instances: &Instances) -> PrimInfo {
        match self {
            Found::World(h) => world.prims[h.slot as usize],
            Found::Instance(ih) => instances.info(ih),
        }
    }

    /// The hit with its geometry, for the ray that found it.
    #[inline]
    pub fn finish(
        &self,
        shapes: &Shapes,
        world: &PrimBvh,
        instances: &Instances,
        ray: &Ray,
    ) -> Hit {
        match self {
            Found::Instance(ih) => {
                let (info, geom) = instances.geometry(shapes, ih, ray);
                Hit::new(ih.hit.t, geom, info)
            }
            Found::World(h) => {
                let geom = world.geometry(shapes, h, ray);
                Hit::new(h.t, geom, world.prims[h.slot as usize])
            }
        }
    }
}

/// Whether anything among the world's primitives and the instances blocks
/// the ray before `ray.tmax`.
#[inline]
pub fn occluded(shapes: &Shapes, world: &PrimBvh, instances: &Instances, ray: &Ray) -> bool {
    world.any(shapes, ray) || (!instances.is_empty() && instances.any(shapes, ray))
}
