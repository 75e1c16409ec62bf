//! The runtime scene: the shapes, the acceleration structures over their
//! primitives (world and instances), materials with their textures, lights
//! with their sampler, and the camera; and the queries integrators use on
//! it (closest hit, occlusion, the BSDF at a hit). It only assembles the
//! layers below; the types it is built from are re-exported here.

pub use crate::accel::{Hit, Instance, InstanceSet, PrimInfo, NO_LIGHT};
pub use crate::geometry::Shapes;
pub use lazy::{LazyHit, PlainDiffuse};

mod lazy;

use crate::accel::{Instances, PrimBvh};

use crate::bsdf::SurfaceBsdf;
use crate::camera::Camera;
use crate::geometry::{Aabb, Ray};
use crate::light::{Light, LightSampler};
use crate::material::Material;
use crate::media::{Medium, MediumInterface};
use crate::texture::Textures;
use lumis_math::Vec3;
use std::sync::atomic::{AtomicU64, Ordering};

/// A uniform number in [0, 1) from a ray's origin and direction, the same
/// for the same ray (pbrt-v4's stochastic alpha test).
fn alpha_hash(r: &Ray) -> f32 {
    let b = |v: Vec3| [v.x, v.y, v.z].map(|c| c.to_bits() as u64);
    let [a, b2, c] = b(r.o);
    let [d, e, f] = b(r.d);
    let h = lumis_math::rng::hash(&[a, b2, c, d, e, f]);
    (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
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
    /// Participating media, referenced by id from materials' interfaces.
    pub media: Vec<Medium>,
    /// The medium the camera sits in.
    pub camera_medium: Option<u32>,
    /// The medium each light emits into (by light id; empty without media).
    pub light_media: Vec<crate::media::LightMedium>,
    pub bounds: Aabb,
    /// Whether any material has an `alpha` cutout (then hits are tested).
    pub has_alpha: bool,
    pub counters: RayCounters,
    /// Embree's structures when [`Scene::use_embree`] chose that backend.
    #[cfg(feature = "embree")]
    pub embree: Option<crate::accel::embree::EmbreeAccel>,
}

impl Scene {
    /// One triangle mesh of grey diffuse (reflectance 0.5) under `lights`:
    /// the scene of the benchmarks that measure what a mesh costs.
    pub fn grey_mesh(
        mesh: crate::geometry::TriangleMesh,
        lights: Vec<Light>,
        camera: Camera,
    ) -> Scene {
        let prims = (0..mesh.triangle_count() as u32)
            .map(|tri| PrimInfo {
                prim: crate::geometry::Prim::Triangle { mesh: 0, tri },
                material: 0,
                light: NO_LIGHT,
            })
            .collect();
        let shapes = Shapes {
            meshes: vec![mesh],
            ..Default::default()
        };
        let grey = crate::material::MaterialKind::Diffuse(crate::material::DiffuseMaterial {
            reflectance: crate::texture::TexRgb::Const(lumis_math::Rgb::splat(0.5)),
        });
        Scene::new(shapes, prims, vec![grey.into()], lights, camera)
    }

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
        let has_alpha = materials.iter().any(|m| m.alpha.is_some());
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
            media: Vec::new(),
            camera_medium: None,
            light_media: Vec::new(),
            has_alpha,
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
        self.embree = on.then(|| {
            crate::accel::embree::EmbreeAccel::build(&self.shapes, &self.world, &self.instances)
        });
    }

    /// Closest intersection along the ray, or `None`.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let hit = self.intersect_any_alpha(ray);
        if self.has_alpha {
            return self.skip_cutouts(ray, hit);
        }
        hit
    }

    /// The closest hit ignoring `alpha` cutouts.
    #[inline]
    fn intersect_any_alpha(&self, ray: &Ray) -> Option<Hit> {
        #[cfg(feature = "embree")]
        if let Some(e) = &self.embree {
            return e.intersect(&self.shapes, &self.world, &self.instances, ray);
        }
        self.intersect_bvh(ray)
    }

    /// Whether anything blocks the ray before `ray.tmax`.
    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        if self.has_alpha {
            return self.intersect(ray).is_some();
        }
        #[cfg(feature = "embree")]
        if let Some(e) = &self.embree {
            return e.occluded(ray);
        }
        self.occluded_bvh(ray)
    }

    /// `hit`, or the first hit beyond it that an `alpha` cutout does not
    /// remove: as pbrt-v4, a surface with alpha `a` < 1 stops the rays
    /// whose hash of origin and direction is below `a` (none at 0), and the
    /// others go on from the hit. Distances stay along `ray`.
    #[cold]
    fn skip_cutouts(&self, ray: &Ray, mut hit: Option<Hit>) -> Option<Hit> {
        let mut r = *ray;
        let mut t0 = 0.0f32;
        for _ in 0..1024 {
            let h = hit.as_mut()?;
            let Some(alpha) = &self.materials[h.material as usize].alpha else {
                h.t += t0;
                return hit;
            };
            let c = crate::texture::TexCtx::at(h.geom.p, h.geom.ns, h.geom.uv);
            let a = alpha.eval(&self.textures, &c);
            if a >= 1.0 || (a > 0.0 && alpha_hash(&r) <= a) {
                h.t += t0;
                return hit;
            }
            let mut next = crate::geometry::ray::spawn_ray(h.geom.p, h.geom.ng, r.d);
            // The offset origin is a hair past the hit: keep the end fixed.
            let moved = (next.o - r.o).dot(r.d) / r.d.length_squared();
            next.tmax = r.tmax - moved;
            t0 += moved;
            r = next;
            hit = self.intersect_any_alpha(&r);
        }
        None
    }

    /// [`Scene::intersect`] with the built-in BVH whatever the backend.
    pub fn intersect_bvh(&self, ray: &Ray) -> Option<Hit> {
        crate::accel::closest(&self.shapes, &self.world, &self.instances, ray)
    }

    /// [`Scene::occluded`] with the built-in BVH whatever the backend.
    pub fn occluded_bvh(&self, ray: &Ray) -> bool {
        crate::accel::occluded(&self.shapes, &self.world, &self.instances, ray)
    }

    #[inline]
    /// The BSDF at a hit seen from direction `wo` (pointing away from the surface).
    pub fn bsdf(&self, hit: &Hit, wo: Vec3) -> SurfaceBsdf {
        crate::material::surface_bsdf(&self.materials, &self.textures, hit.material, &hit.geom, wo)
    }

    /// Whether any ray can travel through a medium.
    #[inline]
    pub fn has_media(&self) -> bool {
        !self.media.is_empty()
    }

    /// The media on the two sides of the surface hit, if crossing it
    /// changes the medium.
    #[inline]
    pub fn medium_interface(&self, hit: &Hit) -> Option<MediumInterface> {
        self.materials[hit.material as usize].media
    }

    /// Whether the surface hit only bounds media (pbrt-v4's `interface`
    /// material): rays cross it unchanged.
    #[inline]
    pub fn is_boundary(&self, hit: &Hit) -> bool {
        self.materials[hit.material as usize].is_interface()
    }

    pub fn count_rays(&self, n: u64) {
        self.counters.rays.fetch_add(n, Ordering::Relaxed);
    }
}
