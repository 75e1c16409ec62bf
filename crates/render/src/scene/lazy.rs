//! Closest hits whose surface geometry waits until it is needed: a caller
//! that only reads the radiance photons at a plain diffuse surface needs
//! the point, the geometric normal and the albedo, not the shading frame,
//! the surface parameters or a BSDF.

use super::{Hit, Scene};
use crate::accel::Found;
use crate::geometry::Ray;
use crate::material::Material;
use lumis_math::{Rgb, Vec3};

/// A closest hit before its geometry (with Embree or `alpha` cutouts, the
/// full hit: those compute it first either way).
#[derive(Clone, Copy, Debug)]
pub enum LazyHit {
    Found(Found),
    Hit(Hit),
}

/// What a hit on a plain diffuse surface is: its point, its geometric
/// normal and its albedo (clamped to [0, 1]), exactly as the full hit and
/// its BSDF would give them.
#[derive(Clone, Copy, Debug)]
pub struct PlainDiffuse {
    pub p: Vec3,
    pub ng: Vec3,
    pub albedo: Rgb,
}

impl Scene {
    /// [`Scene::intersect`] with the geometry left for
    /// [`Scene::plain_diffuse`] or [`Scene::finish`].
    #[inline]
    pub fn intersect_lazy(&self, ray: &Ray) -> Option<LazyHit> {
        #[cfg(feature = "embree")]
        let eager = self.has_alpha || self.embree.is_some();
        #[cfg(not(feature = "embree"))]
        let eager = self.has_alpha;
        if eager {
            return self.intersect(ray).map(LazyHit::Hit);
        }
        crate::accel::closest_found(&self.shapes, &self.world, &self.instances, ray)
            .map(LazyHit::Found)
    }

    /// The hit's point, normal and albedo if it is on a world triangle or
    /// sphere of a diffuse material with a constant reflectance that emits
    /// no light; `None` otherwise (then [`Scene::finish`] it).
    #[inline]
    pub fn plain_diffuse(&self, h: &LazyHit, ray: &Ray) -> Option<PlainDiffuse> {
        let LazyHit::Found(Found::World(lh)) = h else {
            return None;
        };
        let info = self.world.prims[lh.slot as usize];
        if info.light != super::NO_LIGHT {
            return None;
        }
        let albedo = self.materials[info.material as usize].constant_diffuse()?;
        let (p, ng) = self.world.point_normal(&self.shapes, lh, ray)?;
        Some(PlainDiffuse { p, ng, albedo })
    }

    /// [`Scene::intersect`], except that a hit on a material for which
    /// `ends` holds comes back without its geometry (`Some(None)`): a
    /// caller whose path ends there by the material alone saves it.
    pub fn intersect_unless(
        &self,
        ray: &Ray,
        ends: impl FnOnce(&Material) -> bool,
    ) -> Option<Option<Hit>> {
        let h = self.intersect_lazy(ray)?;
        let material = match &h {
            LazyHit::Found(f) => f.info(&self.world, &self.instances).material,
            LazyHit::Hit(h) => h.material,
        };
        if ends(&self.materials[material as usize]) {
            return Some(None);
        }
        Some(Some(self.finish(h, ray)))
    }

    /// The full hit, as [`Scene::intersect`] gives it.
    #[inline]
    pub fn finish(&self, h: LazyHit, ray: &Ray) -> Hit {
        match h {
            LazyHit::Found(f) => f.finish(&self.shapes, &self.world, &self.instances, ray),
            LazyHit::Hit(h) => h,
        }
    }
}
