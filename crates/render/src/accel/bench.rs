//! Deterministic workloads for measuring the BVH: a displaced ("bumpy") UV
//! sphere and two ray sets. Shared by `benches/bvh.rs`, `benches/scene.rs`
//! and the `lumis bench` command so all measure the same thing.

use super::tri4::{PacketRay, TriPackets};
use super::Bvh;
use crate::geometry::{Aabb, Ray, TriangleMesh};
use lumis_math::{Pcg32, Vec3};

/// A unit UV sphere with about `n_tris` triangles whose vertices are pushed
/// radially by smooth noise (a sum of random plane waves, amplitude ~0.1) plus a
/// little per-vertex jitter. The same `(n_tris, seed)` always gives the same mesh.
pub fn bumpy_sphere(n_tris: usize, seed: u64) -> TriangleMesh {
    // Triangles = 2 * nu * (nv - 1) with nv = nu / 2, so nu ~ sqrt(n_tris).
    let nu = ((n_tris as f64).sqrt().round() as usize).max(3);
    let nv = (nu / 2).max(2);
    let mut rng = Pcg32::new(seed, 0x5eed);
    let waves: Vec<(Vec3, f32, f32)> = (0..12)
        .map(|k| {
            let dir = uniform_sphere(rng.next_f32(), rng.next_f32());
            let freq = 2.0 + 30.0 * rng.next_f32() * (k as f32 + 1.0) / 12.0;
            let phase = 2.0 * lumis_math::PI * rng.next_f32();
            (dir * freq, phase, 0.1 / (1.0 + k as f32 * 0.5))
        })
        .collect();
    let radius = |d: Vec3, rng: &mut Pcg32| -> f32 {
        let smooth: f32 = waves
            .iter()
            .map(|&(f, ph, a)| a * (f.dot(d) + ph).sin())
            .sum();
        1.0 + 0.4 * smooth + 0.002 * (rng.next_f32() - 0.5)
    };
    let mut positions = Vec::with_capacity(2 + nu * (nv - 1));
    positions.push(Vec3::Z * radius(Vec3::Z, &mut rng));
    positions.push(-Vec3::Z * radius(-Vec3::Z, &mut rng));
    for j in 1..nv {
        let theta = lumis_math::PI * j as f32 / nv as f32;
        let (st, ct) = theta.sin_cos();
        for i in 0..nu {
            let phi = 2.0 * lumis_math::PI * i as f32 / nu as f32;
            let (sp, cp) = phi.sin_cos();
            let d = Vec3::new(st * cp, st * sp, ct);
            positions.push(d * radius(d, &mut rng));
        }
    }
    let ring = |j: usize, i: usize| (2 + (j - 1) * nu + i % nu) as u32;
    let mut indices = Vec::with_capacity(3 * 2 * nu * (nv - 1));
    for i in 0..nu {
        indices.extend_from_slice(&[0, ring(1, i), ring(1, i + 1)]);
        indices.extend_from_slice(&[1, ring(nv - 1, i + 1), ring(nv - 1, i)]);
    }
    for j in 1..nv - 1 {
        for i in 0..nu {
            let (a, b) = (ring(j, i), ring(j, i + 1));
            let (c, d) = (ring(j + 1, i), ring(j + 1, i + 1));
            indices.extend_from_slice(&[a, c, d, a, d, b]);
        }
    }
    TriangleMesh {
        positions,
        normals: None,
        uvs: None,
        indices,
        flip_normals: false,
    }
}

/// Bounds of all vertices of the mesh.
pub fn mesh_bounds(mesh: &TriangleMesh) -> Aabb {
    let mut b = Aabb::EMPTY;
    for &p in &mesh.positions {
        b.grow(p);
    }
    b
}

/// `n` rays with origins uniform in `bounds` scaled 2x about its center and
/// uniformly random directions.
pub fn random_rays(bounds: &Aabb, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Pcg32::new(seed, 1);
    let (c, e) = (bounds.center(), bounds.extent());
    (0..n)
        .map(|_| {
            let u = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            let o = c + (u * 2.0 - Vec3::ONE) * e;
            Ray::new(o, uniform_sphere(rng.next_f32(), rng.next_f32()))
        })
        .collect()
}

/// `n` rays from uniform points on the sphere of twice the bounding radius,
/// aimed at uniform points in the ball of half the bounding radius (inside the mesh).
pub fn inward_rays(bounds: &Aabb, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Pcg32::new(seed, 2);
    let (c, r) = bounds.bounding_sphere();
    (0..n)
        .map(|_| {
            let o = c + 2.0 * r * uniform_sphere(rng.next_f32(), rng.next_f32());
            let target = c + 0.5
                * r
                * rng.next_f32().cbrt()
                * uniform_sphere(rng.next_f32(), rng.next_f32());
            Ray::new(o, (target - o).normalize())
        })
        .collect()
}

fn uniform_sphere(u0: f32, u1: f32) -> Vec3 {
    let z = 1.0 - 2.0 * u0;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * lumis_math::PI * u1;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A single triangle mesh behind a BVH with vertices in leaf order: the
/// triangle path of `Scene::intersect` without shading or analytic shapes.
pub struct MeshAccel {
    pub bvh: Bvh,
    /// Triangle vertices in BVH leaf order, in packets of four, with each
    /// lane's triangle index.
    tris: TriPackets,
}

impl MeshAccel {
    pub fn new(mesh: &TriangleMesh) -> MeshAccel {
        let boxes: Vec<Aabb> = (0..mesh.triangle_count() as u32)
            .map(|t| mesh.bounds(t))
            .collect();
        let mut bvh = Bvh::build_aligned(&boxes, 4, |_| false);
        let tris = TriPackets::build(&bvh.order, |t| (t, Some(mesh.vertices(t))));
        bvh.order = Vec::new();
        MeshAccel { bvh, tris }
    }

    /// Closest hit `(t, triangle index)`.
    #[inline]
    pub fn closest(&self, ray: &Ray) -> Option<(f32, u32)> {
        let pr = PacketRay::new(ray);
        self.bvh.closest_leaves(
            ray,
            |start, count, r, tmax| {
                let (t, tri, _) = self
                    .tris
                    .closest((start, count), r, &pr, tmax, |_, _, _| None)?;
                Some((t, tri))
            },
            |start| self.tris.address(start),
        )
    }

    /// Whether anything is hit before `ray.tmax`.
    #[inline]
    pub fn any(&self, ray: &Ray) -> bool {
        let pr = PacketRay::new(ray);
        self.bvh.any_leaves(
            ray,
            |start, count, r, tmax| self.tris.any((start, count), r, &pr, tmax, |_, _, _| false),
            |start| self.tris.address(start),
        )
    }

    pub fn memory_bytes(&self) -> usize {
        self.bvh.memory_bytes() + self.tris.memory_bytes()
    }
}
