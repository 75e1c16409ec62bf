//! The runtime scene: shapes in the scene's vectors, a BVH over all
//! primitives, materials, lights and the camera.

mod instance;
mod level;

pub use instance::{transform_box, Instance, InstanceHit, InstanceSet, Instances};
pub use level::{LevelHit, PrimBvh};

use crate::bsdf::SurfaceBsdf;
use crate::camera::Camera;
use crate::geometry::{Aabb, Cylinder, Disk, Prim, Ray, Sphere, SurfaceGeom, TriangleMesh};
use crate::light::{Light, LightSampler};
use crate::material::Material;
use crate::texture::Textures;
use lumis_math::Vec3;
use std::sync::atomic::{AtomicU64, Ordering};

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
}

/// A primitive with what it is made of.
#[derive(Clone, Copy, Debug)]
pub struct PrimInfo {
    pub prim: Prim,
    pub material: u32,
    /// Index of its area light, or `NO_LIGHT`.
    pub light: u32,
}

pub const NO_LIGHT: u32 = u32::MAX;

/// A surface hit with everything shading needs.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub geom: SurfaceGeom,
    pub material: u32,
    pub light: Option<u32>,
    pub prim: Prim,
}

impl Hit {
    #[inline]
    pub fn new(t: f32, geom: SurfaceGeom, info: PrimInfo) -> Hit {
        Hit {
            t,
            geom,
            material: info.material,
            light: (info.light != NO_LIGHT).then_some(info.light),
            prim: info.prim,
        }
    }
}

#[derive(Default)]
pub struct RayCounters {
    pub rays: AtomicU64,
    /// Rays traced by photons (included in `rays`).
    pub photon_rays: AtomicU64,
}

pub struct Scene {
    pub shapes: Shapes,
    /// The primitives not in any instance (the whole scene without instancing).
    pub world: PrimBvh,
    /// Instanced objects; empty for scenes without `ObjectInstance`.
    pub instances: Instances,
    pub materials: Vec<Material>,
    /// Textures and images the materials refer to.
    pub textures: Textures,
    pub lights: Vec<Light>,
    pub light_sampler: LightSampler,
    /// Lights seen by rays that escape (infinite, environment).
    pub infinite_lights: Vec<u32>,
    pub camera: Camera,
    pub bounds: Aabb,
    pub counters: RayCounters,
    /// Embree's structures when [`Scene::use_embree`] chose that backend.
    #[cfg(feature = "embree")]
    pub embree: Option<crate::accel::embree::EmbreeAccel>,
}

impl Scene {
    /// Builds the acceleration structure and light tables (no instances).
    pub fn new(
        shapes: Shapes,
        prims: Vec<PrimInfo>,
        materials: Vec<Material>,
        lights: Vec<Light>,
        camera: Camera,
    ) -> Scene {
        Scene::with_instances(
            shapes,
            prims,
            InstanceSet::default(),
            materials,
            lights,
            camera,
        )
    }

    /// [`Scene::new`] with instanced objects (their primitives in object space).
    pub fn with_instances(
        shapes: Shapes,
        prims: Vec<PrimInfo>,
        instances: InstanceSet,
        materials: Vec<Material>,
        mut lights: Vec<Light>,
        camera: Camera,
    ) -> Scene {
        let world = PrimBvh::build(&shapes, prims);
        let instances = Instances::build(&shapes, instances);
        let bounds = world.bounds().union(&instances.bounds());
        for l in lights.iter_mut() {
            l.preprocess(&bounds);
        }
        let infinite_lights = lights
            .iter()
            .enumerate()
            .filter(|(_, l)| l.is_infinite())
            .map(|(i, _)| i as u32)
            .collect();
        let light_sampler = LightSampler::new(&lights, &shapes);
        Scene {
            shapes,
            world,
            instances,
            materials,
            textures: Textures::default(),
            lights,
            light_sampler,
            infinite_lights,
            camera,
            bounds,
            counters: RayCounters::default(),
            #[cfg(feature = "embree")]
            embree: None,
        }
    }

    /// Bytes of the acceleration structures and the shapes' data.
    pub fn geometry_memory_bytes(&self) -> usize {
        self.world.memory_bytes() + self.instances.memory_bytes() + self.shapes.memory_bytes()
    }

    /// Traces rays with Embree from now on (`on`), or with the built-in BVH.
    #[cfg(feature = "embree")]
    pub fn use_embree(&mut self, on: bool) {
        self.embree = on.then(|| crate::accel::embree::EmbreeAccel::build(self));
    }

    /// Closest intersection along the ray, or `None`.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        #[cfg(feature = "embree")]
        if let Some(e) = &self.embree {
            return e.intersect(self, ray);
        }
        self.intersect_bvh(ray)
    }

    /// Whether anything blocks the ray before `ray.tmax`.
    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        #[cfg(feature = "embree")]
        if let Some(e) = &self.embree {
            return e.occluded(ray);
        }
        self.occluded_bvh(ray)
    }

    /// [`Scene::intersect`] with the built-in BVH whatever the backend.
    pub fn intersect_bvh(&self, ray: &Ray) -> Option<Hit> {
        let world_hit = self.world.closest(&self.shapes, ray);
        if !self.instances.is_empty() {
            let mut r = *ray;
            if let Some(h) = &world_hit {
                r.tmax = h.t;
            }
            if let Some(ih) = self.instances.closest(&self.shapes, &r) {
                let (info, geom) = self.instances.geometry(&self.shapes, &ih, ray);
                return Some(Hit::new(ih.hit.t, geom, info));
            }
        }
        let h = world_hit?;
        let geom = self.world.geometry(&self.shapes, &h, ray);
        Some(Hit::new(h.t, geom, self.world.prims[h.slot as usize]))
    }

    /// [`Scene::occluded`] with the built-in BVH whatever the backend.
    pub fn occluded_bvh(&self, ray: &Ray) -> bool {
        self.world.any(&self.shapes, ray)
            || (!self.instances.is_empty() && self.instances.any(&self.shapes, ray))
    }

    #[inline]
    /// The BSDF at a hit seen from direction `wo` (pointing away from the surface).
    pub fn bsdf(&self, hit: &Hit, wo: Vec3) -> SurfaceBsdf {
        crate::material::surface_bsdf(&self.materials, &self.textures, hit.material, &hit.geom, wo)
    }

    pub fn count_rays(&self, n: u64) {
        self.counters.rays.fetch_add(n, Ordering::Relaxed);
    }
}
