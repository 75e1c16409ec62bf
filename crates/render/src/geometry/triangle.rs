//! Watertight ray-triangle intersection (Woop, Benthin & Wald 2013) and
//! triangle surface geometry.

use super::{Ray, SurfaceGeom, TriangleMesh};
use lumis_math::{Frame, Vec2, Vec3};

/// Per-ray constants of the watertight test: the axis permutation and shear.
#[derive(Clone, Copy, Debug)]
pub struct RayShear {
    pub kx: usize,
    pub ky: usize,
    pub kz: usize,
    pub sx: f32,
    pub sy: f32,
    pub sz: f32,
}

impl RayShear {
    #[inline]
    pub fn new(d: Vec3) -> RayShear {
        let a = d.abs();
        let kz = if a.x > a.y {
            if a.x > a.z {
                0
            } else {
                2
            }
        } else if a.y > a.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let sz = 1.0 / d[kz];
        RayShear {
            kx,
            ky,
            kz,
            sx: d[kx] * sz,
            sy: d[ky] * sz,
            sz,
        }
    }
}

/// Returns `(t, b1, b2)` with barycentrics of `v1` and `v2` if the ray hits in (0, tmax).
#[inline]
pub fn intersect_triangle(
    ray: &Ray,
    sh: &RayShear,
    v: &[Vec3; 3],
    tmax: f32,
) -> Option<(f32, f32, f32)> {
    let a = v[0] - ray.o;
    let b = v[1] - ray.o;
    let c = v[2] - ray.o;
    let (ax, ay) = (a[sh.kx] - sh.sx * a[sh.kz], a[sh.ky] - sh.sy * a[sh.kz]);
    let (bx, by) = (b[sh.kx] - sh.sx * b[sh.kz], b[sh.ky] - sh.sy * b[sh.kz]);
    let (cx, cy) = (c[sh.kx] - sh.sx * c[sh.kz], c[sh.ky] - sh.sy * c[sh.kz]);
    let mut u = cx * by - cy * bx;
    let mut vv = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    if u == 0.0 || vv == 0.0 || w == 0.0 {
        // Edge case: redo the edge functions in double precision.
        u = (cx as f64 * by as f64 - cy as f64 * bx as f64) as f32;
        vv = (ax as f64 * cy as f64 - ay as f64 * cx as f64) as f32;
        w = (bx as f64 * ay as f64 - by as f64 * ax as f64) as f32;
    }
    let (az, bz, cz) = (sh.sz * a[sh.kz], sh.sz * b[sh.kz], sh.sz * c[sh.kz]);
    watertight_tail(u, vv, w, [az, bz, cz], tmax)
}

/// The end of the watertight test from the edge functions `u, vv, w` and
/// the scaled `z` of the three vertices on: the side test, the distance
/// against `(0, tmax)` and the barycentrics. The packet test of the
/// acceleration structure ends with it too, so both give the same bits.
#[inline(always)]
pub fn watertight_tail(u: f32, vv: f32, w: f32, z: [f32; 3], tmax: f32) -> Option<(f32, f32, f32)> {
    if (u < 0.0 || vv < 0.0 || w < 0.0) && (u > 0.0 || vv > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + vv + w;
    if det == 0.0 {
        return None;
    }
    let tt = u * z[0] + vv * z[1] + w * z[2];
    if det < 0.0 && (tt >= 0.0 || tt < tmax * det) {
        return None;
    }
    if det > 0.0 && (tt <= 0.0 || tt > tmax * det) {
        return None;
    }
    let inv = 1.0 / det;
    let t = tt * inv;
    if !(t > 0.0 && t < tmax) {
        return None;
    }
    Some((t, vv * inv, w * inv))
}

/// Surface geometry at barycentrics (b1, b2) of triangle `tri`.
pub fn triangle_geometry(mesh: &TriangleMesh, tri: u32, b1: f32, b2: f32) -> SurfaceGeom {
    triangle_geometry_at(mesh, mesh.corners(tri), b1, b2)
}

/// [`triangle_geometry`] of the triangle whose corners are vertices
/// `corners` ([`TriangleMesh::corners`]).
pub fn triangle_geometry_at(
    mesh: &TriangleMesh,
    corners: [u32; 3],
    b1: f32,
    b2: f32,
) -> SurfaceGeom {
    let (idx, [p0, p1, p2], b0) = corner_points(mesh, corners, b1, b2);
    let p = b0 * p0 + b1 * p1 + b2 * p2;
    let ng = (p0 - p2).cross(p1 - p2).normalize_or_zero();
    let (uv0, uv1, uv2) = match &mesh.uvs {
        Some(uv) => (uv[idx[0]], uv[idx[1]], uv[idx[2]]),
        None => (
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
        ),
    };
    let uv = b0 * uv0 + b1 * uv1 + b2 * uv2;
    // dp/du from the uv parameterisation, falling back to an arbitrary tangent.
    let (duv02, duv12) = (uv0 - uv2, uv1 - uv2);
    let (dp02, dp12) = (p0 - p2, p1 - p2);
    let det = duv02.x * duv12.y - duv02.y * duv12.x;
    let (mut dpdu, mut dpdv) = (Vec3::ZERO, Vec3::ZERO);
    if det.abs() > 1e-12 {
        dpdu = (duv12.y * dp02 - duv02.y * dp12) / det;
        dpdv = (duv02.x * dp12 - duv12.x * dp02) / det;
    }
    if dpdu.cross(dpdv).length_squared() == 0.0 || !dpdu.is_finite() || !dpdv.is_finite() {
        let f = Frame::from_normal(ng);
        (dpdu, dpdv) = (f.s, f.t);
    }
    let (ng, ns) = oriented_normals(mesh, idx, [b0, b1, b2], ng);
    SurfaceGeom {
        p,
        ng,
        ns,
        dpdu,
        dpdv,
        uv,
    }
}

/// The point at barycentrics (`b1`, `b2`) of triangle `tri` and its
/// geometric normal, as [`triangle_geometry`] gives them (area sampling
/// needs no more).
pub fn triangle_point(mesh: &TriangleMesh, tri: u32, b1: f32, b2: f32) -> (Vec3, Vec3) {
    triangle_point_at(mesh, mesh.corners(tri), b1, b2)
}

/// [`triangle_point`] of the triangle whose corners are vertices `corners`.
pub fn triangle_point_at(mesh: &TriangleMesh, corners: [u32; 3], b1: f32, b2: f32) -> (Vec3, Vec3) {
    let (idx, [p0, p1, p2], b0) = corner_points(mesh, corners, b1, b2);
    let p = barycentric_point([p0, p1, p2], b1, b2);
    let ng = (p0 - p2).cross(p1 - p2).normalize_or_zero();
    (p, oriented_normals(mesh, idx, [b0, b1, b2], ng).0)
}

/// The point at barycentrics (`b1`, `b2`) of corners `p`, as
/// [`triangle_point`] computes it.
#[inline]
pub fn barycentric_point([p0, p1, p2]: [Vec3; 3], b1: f32, b2: f32) -> Vec3 {
    let b0 = 1.0 - b1 - b2;
    b0 * p0 + b1 * p1 + b2 * p2
}

/// The corners' vertex indices and positions, and the barycentric
/// `b0 = 1 - b1 - b2`.
#[inline]
fn corner_points(
    mesh: &TriangleMesh,
    corners: [u32; 3],
    b1: f32,
    b2: f32,
) -> ([usize; 3], [Vec3; 3], f32) {
    let idx = corners.map(|i| i as usize);
    (idx, idx.map(|i| mesh.positions[i]), 1.0 - b1 - b2)
}

/// The geometric normal `ng` turned to the side of the interpolated vertex
/// normals, and the shading normal (`ng` without vertex normals), with
/// `ReverseOrientation` applied.
#[inline]
fn oriented_normals(
    mesh: &TriangleMesh,
    idx: [usize; 3],
    b: [f32; 3],
    mut ng: Vec3,
) -> (Vec3, Vec3) {
    let mut ns = ng;
    if let Some(n) = &mesh.normals {
        let interp = b[0] * n[idx[0]] + b[1] * n[idx[1]] + b[2] * n[idx[2]];
        if interp.length_squared() > 0.0 {
            ns = interp.normalize();
            if mesh.flip_normals {
                ns = -ns;
            }
            if ng.dot(ns) < 0.0 {
                ng = -ng;
            }
        } else if mesh.flip_normals {
            ng = -ng;
            ns = ng;
        }
    } else if mesh.flip_normals {
        ng = -ng;
        ns = ng;
    }
    (ng, ns)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> [Vec3; 3] {
        [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]
    }

    #[test]
    fn hits_inside_misses_outside() {
        let v = tri();
        let r = Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::new(0.0, 0.0, -1.0));
        let (t, b1, b2) = intersect_triangle(&r, &RayShear::new(r.d), &v, f32::INFINITY).unwrap();
        assert!((t - 1.0).abs() < 1e-6 && (b1 - 0.25).abs() < 1e-6 && (b2 - 0.25).abs() < 1e-6);
        let r = Ray::new(Vec3::new(0.75, 0.75, 1.0), Vec3::new(0.0, 0.0, -1.0));
        assert!(intersect_triangle(&r, &RayShear::new(r.d), &v, f32::INFINITY).is_none());
        // Behind the origin and beyond tmax.
        let r = Ray::new(Vec3::new(0.25, 0.25, -1.0), Vec3::new(0.0, 0.0, -1.0));
        assert!(intersect_triangle(&r, &RayShear::new(r.d), &v, f32::INFINITY).is_none());
        let r = Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::new(0.0, 0.0, -1.0));
        assert!(intersect_triangle(&r, &RayShear::new(r.d), &v, 0.5).is_none());
    }

    #[test]
    fn shared_edge_is_watertight() {
        // Two triangles sharing the diagonal of a square: rays through the diagonal hit one.
        let a = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ];
        let b = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let mut rng = lumis_math::Pcg32::new(5, 0);
        for _ in 0..10_000 {
            let s = rng.next_f32();
            let o = Vec3::new(s, s, 1.0)
                + Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, 0.0) * 0.3;
            let target = Vec3::new(s, s, 0.0);
            let r = Ray::new(o, (target - o).normalize());
            let sh = RayShear::new(r.d);
            let hits = intersect_triangle(&r, &sh, &a, f32::INFINITY).is_some() as u32
                + intersect_triangle(&r, &sh, &b, f32::INFINITY).is_some() as u32;
            assert!(hits >= 1, "ray through shared edge leaked");
        }
    }

    /// Area sampling's point and normal are `triangle_geometry`'s bit for
    /// bit, with and without vertex normals (some facing away) and flips.
    #[test]
    fn triangle_point_is_the_geometry_s_point_and_normal() {
        let mut rng = lumis_math::Pcg32::new(9, 0);
        let mut v = || Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - 1.0;
        let positions: Vec<Vec3> = (0..30).map(|_| v()).collect();
        let normals: Vec<Vec3> = (0..30).map(|_| v()).collect();
        let indices: Vec<u32> = (0..30).collect();
        let mut rng = lumis_math::Pcg32::new(10, 0);
        for (with_normals, flip) in [(false, false), (false, true), (true, false), (true, true)] {
            let mesh = TriangleMesh {
                positions: positions.clone(),
                normals: with_normals.then(|| normals.clone()),
                uvs: None,
                indices: indices.clone(),
                flip_normals: flip,
            };
            for tri in 0..10 {
                let (b1, b2) = (rng.next_f32() * 0.5, rng.next_f32() * 0.5);
                let g = triangle_geometry(&mesh, tri, b1, b2);
                let (p, n) = triangle_point(&mesh, tri, b1, b2);
                assert_eq!(
                    (p.to_array(), n.to_array()),
                    (g.p.to_array(), g.ng.to_array())
                );
            }
        }
    }
}
