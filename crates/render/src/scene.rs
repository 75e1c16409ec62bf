//! The runtime scene: shapes in the scene's vectors, a BVH over all
//! primitives, materials, lights and the camera.

use crate::accel::Bvh;
use crate::camera::Camera;
use crate::geometry::triangle::{intersect_triangle, triangle_geometry, RayShear};
use crate::geometry::{Aabb, Disk, Prim, Ray, Sphere, SurfaceGeom, TriangleMesh};
use crate::light::{Light, LightSampler};
use crate::material::Material;
use lumis_math::{Vec2, Vec3};
use std::sync::atomic::{AtomicU64, Ordering};

/// Big shape data, referenced by `u32` ids.
#[derive(Clone, Debug, Default)]
pub struct Shapes {
    pub meshes: Vec<TriangleMesh>,
    pub spheres: Vec<Sphere>,
    pub disks: Vec<Disk>,
}

impl Shapes {
    pub fn bounds(&self, p: Prim) -> Aabb {
        match p {
            Prim::Triangle { mesh, tri } => self.meshes[mesh as usize].bounds(tri),
            Prim::Sphere(i) => self.spheres[i as usize].bounds(),
            Prim::Disk(i) => self.disks[i as usize].bounds(),
        }
    }

    pub fn area(&self, p: Prim) -> f32 {
        match p {
            Prim::Triangle { mesh, tri } => self.meshes[mesh as usize].area(tri),
            Prim::Sphere(i) => self.spheres[i as usize].area(),
            Prim::Disk(i) => self.disks[i as usize].area(),
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

/// Tag in `Scene::tri_verts` of a primitive that is not a triangle.
const ANALYTIC: u32 = 1;

/// A surface hit with everything shading needs.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub geom: SurfaceGeom,
    pub material: u32,
    pub light: Option<u32>,
    pub prim: Prim,
}

#[derive(Default)]
pub struct RayCounters {
    pub rays: AtomicU64,
}

pub struct Scene {
    pub shapes: Shapes,
    /// Primitives in BVH leaf order.
    pub prims: Vec<PrimInfo>,
    /// Per primitive in BVH leaf order: the triangle's vertices, or `ANALYTIC`
    /// for a sphere or disk (then `prims` says which), so testing a triangle
    /// reads one array only.
    tri_verts: Vec<([Vec3; 3], u32)>,
    bvh: Bvh,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    pub light_sampler: LightSampler,
    /// Lights seen by rays that escape (infinite, environment).
    pub infinite_lights: Vec<u32>,
    pub camera: Camera,
    pub bounds: Aabb,
    pub counters: RayCounters,
}

impl Scene {
    /// Builds the acceleration structure and light tables.
    pub fn new(
        shapes: Shapes,
        prims: Vec<PrimInfo>,
        materials: Vec<Material>,
        mut lights: Vec<Light>,
        camera: Camera,
    ) -> Scene {
        let boxes: Vec<Aabb> = prims.iter().map(|p| shapes.bounds(p.prim)).collect();
        let bvh = Bvh::build(&boxes);
        let old_prims = prims;
        let prims: Vec<PrimInfo> = bvh.order.iter().map(|&i| old_prims[i as usize]).collect();
        let mut tri_verts = crate::accel::mem::huge_vec(prims.len());
        tri_verts.extend(prims.iter().map(|p| match p.prim {
            Prim::Triangle { mesh, tri } => (shapes.meshes[mesh as usize].vertices(tri), 0),
            _ => ([Vec3::ZERO; 3], ANALYTIC),
        }));
        let bounds = bvh.bounds();
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
        let mut bvh = bvh;
        bvh.order = Vec::new();
        Scene {
            shapes,
            prims,
            tri_verts,
            bvh,
            materials,
            lights,
            light_sampler,
            infinite_lights,
            camera,
            bounds,
            counters: RayCounters::default(),
        }
    }

    /// Starts loading the triangle data of slots `start..start + count`.
    #[inline(always)]
    fn prefetch(&self, start: u32, count: u32) {
        if let Some(t) = self.tri_verts.get(start as usize..(start + count) as usize) {
            crate::accel::mem::prefetch(t);
        }
    }

    /// Closest intersection along the ray, or `None`.
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
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
                match self.prims[slot as usize].prim {
                    Prim::Sphere(i) => self.shapes.spheres[i as usize].intersect(r, tmax),
                    Prim::Disk(i) => self.shapes.disks[i as usize].intersect(r, tmax),
                    Prim::Triangle { .. } => None,
                }
            },
            |start, count| self.prefetch(start, count),
        )?;
        let info = self.prims[slot as usize];
        let geom = match info.prim {
            Prim::Triangle { mesh, tri } => {
                triangle_geometry(&self.shapes.meshes[mesh as usize], tri, uv.x, uv.y)
            }
            Prim::Sphere(i) => self.shapes.spheres[i as usize].geometry_at(ray.at(t)),
            Prim::Disk(i) => self.shapes.disks[i as usize].geometry_at(ray.at(t)),
        };
        Some(Hit {
            t,
            geom,
            material: info.material,
            light: if info.light == NO_LIGHT {
                None
            } else {
                Some(info.light)
            },
            prim: info.prim,
        })
    }

    /// Whether anything blocks the ray before `ray.tmax`.
    pub fn occluded(&self, ray: &Ray) -> bool {
        let sh = RayShear::new(ray.d);
        self.bvh.any_hinted(
            ray,
            |slot, r, tmax| {
                let (v, kind) = &self.tri_verts[slot as usize];
                if *kind != ANALYTIC {
                    return intersect_triangle(r, &sh, v, tmax).is_some();
                }
                match self.prims[slot as usize].prim {
                    Prim::Sphere(i) => self.shapes.spheres[i as usize].intersect(r, tmax).is_some(),
                    Prim::Disk(i) => self.shapes.disks[i as usize].intersect(r, tmax).is_some(),
                    Prim::Triangle { .. } => false,
                }
            },
            |start, count| self.prefetch(start, count),
        )
    }

    #[inline]
    pub fn count_rays(&self, n: u64) {
        self.counters.rays.fetch_add(n, Ordering::Relaxed);
    }
}
