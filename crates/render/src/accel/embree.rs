//! Optional ray-tracing backend: Intel Embree 3 (cargo feature `embree`,
//! Debian `libembree-dev`), through the `embree3` crate (safe bindings that
//! target Embree 3.13.5, the version Debian ships; no bindgen or C toolchain
//! at build time, only `libembree3` at link time).
//!
//! It mirrors the built-in structure level by level: the world's primitives
//! and each instanced object become an Embree scene holding one triangle
//! geometry (the level's triangles, vertices copied in leaf-slot order) and
//! one user geometry (its spheres, disks and cylinders, intersected by
//! lumis' own code); instances are Embree instances of the object scenes. A hit is
//! mapped back to the level's leaf slot, so surface geometry, materials and
//! lights come from exactly the same code as with the built-in BVH.

use super::{Hit, InstanceHit, Instances, LevelHit, PrimBvh};
use crate::geometry::{Prim, Ray, Shapes};
use embree3::{
    Bounds, BufferUsage, Device, Format, Geometry, GeometryKind, IntersectContext,
    IntersectFunctionNArgs, OccludedFunctionNArgs, INVALID_ID,
};
use lumis_math::{Vec2, Vec3};
use std::sync::Arc;

/// One level (world or object) as an Embree scene.
struct Level {
    scene: embree3::Scene<'static>,
    _geoms: Vec<Geometry<'static>>,
    /// Embree geometry id of the triangles and of the analytic shapes.
    tri_geom: u32,
    user_geom: u32,
    /// Leaf slot of each Embree primitive, per geometry.
    tri_slots: Vec<u32>,
    user_slots: Arc<Vec<u32>>,
}

pub struct EmbreeAccel {
    _device: Device,
    top: Level,
    objects: Vec<Level>,
    /// Instance index (in [`Instances::instances`] order) of each Embree instance id.
    instance_of_geom: Vec<u32>,
    _instance_geoms: Vec<Geometry<'static>>,
}

/// Analytic shapes of one level, shared with Embree's callbacks.
struct Analytic {
    prims: Vec<Prim>,
    shapes: Arc<Shapes>,
}

impl Analytic {
    #[inline]
    fn intersect(&self, i: u32, r: &Ray, tmax: f32) -> Option<f32> {
        self.shapes
            .intersect_analytic(self.prims[i as usize], r, tmax)
    }
}

fn lumis_ray(r: &embree3::Ray) -> Ray {
    Ray {
        o: Vec3::new(r.org_x, r.org_y, r.org_z),
        d: Vec3::new(r.dir_x, r.dir_y, r.dir_z),
        tmax: r.tfar,
    }
}

fn embree_ray(r: &Ray) -> embree3::Ray {
    embree3::Ray::segment(r.o.to_array(), r.d.to_array(), 0.0, r.tmax)
}

fn build_level(
    device: &Device,
    shapes: &Shapes,
    analytic_shapes: &Arc<Shapes>,
    level: &PrimBvh,
) -> Level {
    let mut scene = device.create_scene().expect("embree scene");
    let mut geoms = Vec::new();
    let mut verts: Vec<[f32; 3]> = Vec::new();
    let mut tri_slots = Vec::new();
    let mut analytic = Vec::new();
    let mut user_slots = Vec::new();
    for (slot, info) in level.prims.iter().enumerate() {
        match shapes.triangle_vertices(info.prim) {
            Some(tri) => {
                for v in tri {
                    verts.push(v.to_array());
                }
                tri_slots.push(slot as u32);
            }
            None => {
                analytic.push(info.prim);
                user_slots.push(slot as u32);
            }
        }
    }
    let mut tri_geom = INVALID_ID;
    if !tri_slots.is_empty() {
        let n = tri_slots.len();
        let mut g = device
            .create_geometry(GeometryKind::TRIANGLE)
            .expect("embree geometry");
        g.set_new_buffer::<[f32; 3]>(BufferUsage::VERTEX, 0, Format::FLOAT3, 12, 3 * n)
            .expect("embree vertex buffer")
            .copy_from_slice(&verts);
        let idx: Vec<[u32; 3]> = (0..n as u32)
            .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
            .collect();
        g.set_new_buffer::<[u32; 3]>(BufferUsage::INDEX, 0, Format::UINT3, 12, n)
            .expect("embree index buffer")
            .copy_from_slice(&idx);
        let g = g.commit();
        tri_geom = scene.attach_geometry(&g);
        geoms.push(g);
    }
    let mut user_geom = INVALID_ID;
    if !analytic.is_empty() {
        let data = Arc::new(Analytic {
            prims: analytic,
            shapes: analytic_shapes.clone(),
        });
        let mut g = device
            .create_geometry(GeometryKind::USER)
            .expect("embree geometry");
        g.set_primitive_count(data.prims.len() as u32);
        let d = data.clone();
        g.set_bounds_function::<_, ()>(move |b: &mut Bounds, prim, _time, _: Option<&()>| {
            let bb = d.shapes.bounds(d.prims[prim as usize]);
            (b.lower_x, b.lower_y, b.lower_z) = (bb.min.x, bb.min.y, bb.min.z);
            (b.upper_x, b.upper_y, b.upper_z) = (bb.max.x, bb.max.y, bb.max.z);
        });
        let d = data.clone();
        g.set_intersect_function::<_, ()>(move |args: &mut IntersectFunctionNArgs<'_, ()>| {
            let inst = args.context().instID[0];
            for i in 0..args.len() {
                if args.valid_n()[i] == 0 {
                    continue;
                }
                let mut ray = args.ray(i);
                let r = lumis_ray(&ray);
                if let Some(t) = d.intersect(args.prim_id(), &r, ray.tfar) {
                    ray.tfar = t;
                    let hit = embree3::Hit {
                        Ng_x: 0.0,
                        Ng_y: 0.0,
                        Ng_z: 1.0,
                        u: 0.0,
                        v: 0.0,
                        primID: args.prim_id(),
                        geomID: args.geom_id(),
                        instID: [inst],
                    };
                    args.commit_hit(i, &ray, &hit);
                }
            }
        });
        let d = data;
        g.set_occluded_function::<_, ()>(move |args: &mut OccludedFunctionNArgs<'_, ()>| {
            for i in 0..args.len() {
                if args.valid_n()[i] == 0 {
                    continue;
                }
                let ray = args.ray(i);
                if d.intersect(args.prim_id(), &lumis_ray(&ray), ray.tfar)
                    .is_some()
                {
                    args.set_occluded(i);
                }
            }
        });
        let g = g.commit();
        user_geom = scene.attach_geometry(&g);
        geoms.push(g);
    }
    Level {
        scene,
        _geoms: geoms,
        tri_geom,
        user_geom,
        tri_slots,
        user_slots: Arc::new(user_slots),
    }
}

impl Level {
    /// Leaf slot of an Embree hit in this level.
    #[inline]
    fn slot(&self, h: &embree3::Hit) -> u32 {
        if h.geomID == self.tri_geom {
            self.tri_slots[h.primID as usize]
        } else {
            debug_assert_eq!(h.geomID, self.user_geom);
            self.user_slots[h.primID as usize]
        }
    }
}

impl EmbreeAccel {
    /// Builds Embree scenes for the world level and the instanced objects
    /// (the analytic shapes are copied for Embree's callbacks; the meshes'
    /// triangles go into Embree's own buffers, in the levels' slot order).
    pub fn build(shapes: &Shapes, world: &PrimBvh, instances: &Instances) -> EmbreeAccel {
        let device = Device::new().expect("embree device");
        let analytic = Arc::new(Shapes {
            meshes: Vec::new(),
            spheres: shapes.spheres.clone(),
            disks: shapes.disks.clone(),
            cylinders: shapes.cylinders.clone(),
        });
        let objects: Vec<Level> = instances
            .objects
            .iter()
            .map(|o| {
                let mut l = build_level(&device, shapes, &analytic, o);
                l.scene.commit();
                l
            })
            .collect();
        let mut top = build_level(&device, shapes, &analytic, world);
        let mut instance_of_geom = Vec::new();
        let mut instance_geoms = Vec::new();
        for (i, inst) in instances.instances.iter().enumerate() {
            let mut g = device
                .create_geometry(GeometryKind::INSTANCE)
                .expect("embree instance");
            g.set_instanced_scene(&objects[inst.object as usize].scene);
            g.set_transform(0, &inst.world_from_object.m.to_cols_array());
            let g = g.commit();
            let id = top.scene.attach_geometry(&g) as usize;
            if instance_of_geom.len() <= id {
                instance_of_geom.resize(id + 1, u32::MAX);
            }
            instance_of_geom[id] = i as u32;
            instance_geoms.push(g);
        }
        top.scene.commit();
        EmbreeAccel {
            _device: device,
            top,
            objects,
            instance_of_geom,
            _instance_geoms: instance_geoms,
        }
    }

    /// Closest hit, as [`super::closest`] on the structures this was built
    /// from.
    pub fn intersect(
        &self,
        shapes: &Shapes,
        world: &PrimBvh,
        instances: &Instances,
        ray: &Ray,
    ) -> Option<Hit> {
        let mut ctx = IntersectContext::incoherent();
        let mut rh = embree3::RayHit::from(embree_ray(ray));
        self.top.scene.intersect(&mut ctx, &mut rh);
        let h = rh.hit;
        if h.geomID == INVALID_ID {
            return None;
        }
        let t = rh.ray.tfar;
        let uv = Vec2::new(h.u, h.v);
        let inst = h.instID[0];
        if inst != INVALID_ID {
            let instance = self.instance_of_geom[inst as usize];
            let object = instances.instances[instance as usize].object as usize;
            let o = &self.objects[object];
            let ih = InstanceHit {
                hit: LevelHit {
                    t,
                    slot: o.slot(&h),
                    uv,
                },
                instance,
            };
            let (info, geom) = instances.geometry(shapes, &ih, ray);
            return Some(Hit::new(t, geom, info));
        }
        let lh = LevelHit {
            t,
            slot: self.top.slot(&h),
            uv,
        };
        let geom = world.geometry(shapes, &lh, ray);
        Some(Hit::new(t, geom, world.prims[lh.slot as usize]))
    }

    /// The closest hit's distance only, without its geometry: the
    /// counterpart of [`super::closest_found`] for `lumis bench --rays`.
    pub fn closest_t(&self, ray: &Ray) -> Option<f32> {
        let mut ctx = IntersectContext::incoherent();
        let mut rh = embree3::RayHit::from(embree_ray(ray));
        self.top.scene.intersect(&mut ctx, &mut rh);
        (rh.hit.geomID != INVALID_ID).then_some(rh.ray.tfar)
    }

    /// Whether anything blocks the ray before `ray.tmax`, as [`super::occluded`].
    pub fn occluded(&self, ray: &Ray) -> bool {
        let mut ctx = IntersectContext::incoherent();
        let mut r = embree_ray(ray);
        self.top.scene.occluded(&mut ctx, &mut r)
    }
}

/// One triangle mesh in Embree: the counterpart of
/// [`MeshAccel`](super::bench::MeshAccel) for `lumis bench`, tracing the
/// identical rays.
pub struct EmbreeMesh {
    _device: Device,
    scene: embree3::Scene<'static>,
    _geom: Geometry<'static>,
}

impl EmbreeMesh {
    pub fn new(mesh: &crate::geometry::TriangleMesh) -> EmbreeMesh {
        let device = Device::new().expect("embree device");
        let mut scene = device.create_scene().expect("embree scene");
        let mut g = device
            .create_geometry(GeometryKind::TRIANGLE)
            .expect("embree geometry");
        let verts: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.to_array()).collect();
        g.set_new_buffer::<[f32; 3]>(BufferUsage::VERTEX, 0, Format::FLOAT3, 12, verts.len())
            .expect("embree vertex buffer")
            .copy_from_slice(&verts);
        let idx: Vec<[u32; 3]> = mesh
            .indices
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect();
        g.set_new_buffer::<[u32; 3]>(BufferUsage::INDEX, 0, Format::UINT3, 12, idx.len())
            .expect("embree index buffer")
            .copy_from_slice(&idx);
        let g = g.commit();
        scene.attach_geometry(&g);
        scene.commit();
        EmbreeMesh {
            _device: device,
            scene,
            _geom: g,
        }
    }

    /// Closest hit `(t, triangle index)`.
    #[inline]
    pub fn closest(&self, ray: &Ray) -> Option<(f32, u32)> {
        let mut ctx = IntersectContext::incoherent();
        let mut rh = embree3::RayHit::from(embree_ray(ray));
        self.scene.intersect(&mut ctx, &mut rh);
        (rh.hit.geomID != INVALID_ID).then_some((rh.ray.tfar, rh.hit.primID))
    }

    /// Whether anything is hit before `ray.tmax`.
    #[inline]
    pub fn any(&self, ray: &Ray) -> bool {
        let mut ctx = IntersectContext::incoherent();
        self.scene.occluded(&mut ctx, &mut embree_ray(ray))
    }
}
