//! Maps between the unit square and the sphere used by environment maps:
//! Clarberg's equal-area octahedral map (pbrt-v4's `EqualAreaSquareToSphere`
//! and inverse; every square area maps to 4 pi times that solid angle) and
//! the latitude-longitude map of pbrt-v3 (`u = phi / 2 pi`, `v = theta / pi`,
//! `+z` at the top row).

use crate::{safe_sqrt, Vec2, Vec3, PI};

/// Equal-area octahedral map of [0,1]² onto the unit sphere.
pub fn equal_area_square_to_sphere(p: Vec2) -> Vec3 {
    let u = 2.0 * p.x - 1.0;
    let v = 2.0 * p.y - 1.0;
    let (up, vp) = (u.abs(), v.abs());
    // Signed distance from the diagonal |u| + |v| = 1: the equator.
    let signed = 1.0 - (up + vp);
    let r = 1.0 - signed.abs();
    let phi = if r == 0.0 { 1.0 } else { (vp - up) / r + 1.0 } * (PI / 4.0);
    let z = (1.0 - r * r).copysign(signed);
    let s = r * safe_sqrt(2.0 - r * r);
    Vec3::new(phi.cos().copysign(u) * s, phi.sin().copysign(v) * s, z)
}

/// Inverse of [`equal_area_square_to_sphere`] for a unit vector.
pub fn equal_area_sphere_to_square(d: Vec3) -> Vec2 {
    let (x, y, z) = (d.x.abs(), d.y.abs(), d.z.abs());
    let r = safe_sqrt(1.0 - z);
    let a = x.max(y);
    let b = if a == 0.0 { 0.0 } else { x.min(y) / a };
    let mut phi = b.atan() * (2.0 / PI);
    if x < y {
        phi = 1.0 - phi;
    }
    let mut v = phi * r;
    let mut u = r - v;
    if d.z < 0.0 {
        std::mem::swap(&mut u, &mut v);
        u = 1.0 - u;
        v = 1.0 - v;
    }
    let u = u.copysign(d.x);
    let v = v.copysign(d.y);
    Vec2::new(
        ((u + 1.0) * 0.5).clamp(0.0, 1.0),
        ((v + 1.0) * 0.5).clamp(0.0, 1.0),
    )
}

/// Maps a pixel index that lies up to one image outside a `w` × `h`
/// equal-area image back inside by the octahedral folding of its edges
/// (pbrt-v4's `OctahedralSphere` wrap): crossing the left or right edge
/// mirrors `y`, crossing the top or bottom edge mirrors `x`. pbrt-v4 maps
/// index `-1` to `1`; this maps it to `0`, the texel that actually borders it.
pub fn wrap_equal_area_pixel(x: i32, y: i32, w: i32, h: i32) -> (i32, i32) {
    let (mut x, mut y) = (x, y);
    if x < 0 {
        x = -1 - x;
        y = h - 1 - y;
    } else if x >= w {
        x = 2 * w - 1 - x;
        y = h - 1 - y;
    }
    if y < 0 {
        x = w - 1 - x;
        y = -1 - y;
    } else if y >= h {
        x = w - 1 - x;
        y = 2 * h - 1 - y;
    }
    (x.clamp(0, w - 1), y.clamp(0, h - 1))
}

/// Latitude-longitude map (pbrt-v3 `InfiniteAreaLight`): `(u, v)` in [0,1]²
/// to the direction with `phi = 2 pi u`, `theta = pi v`, and `sin theta`
/// (the solid angle is `2 pi² sin theta du dv`).
pub fn latlong_to_sphere(p: Vec2) -> (Vec3, f32) {
    let (phi, theta) = (2.0 * PI * p.x, PI * p.y);
    let (st, ct) = theta.sin_cos();
    (Vec3::new(st * phi.cos(), st * phi.sin(), ct), st)
}

/// Inverse of [`latlong_to_sphere`] for a unit vector.
pub fn sphere_to_latlong(d: Vec3) -> Vec2 {
    let theta = d.z.clamp(-1.0, 1.0).acos();
    let mut phi = d.y.atan2(d.x);
    if phi < 0.0 {
        phi += 2.0 * PI;
    }
    Vec2::new(
        (phi / (2.0 * PI)).clamp(0.0, 1.0),
        (theta / PI).clamp(0.0, 1.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Pcg32;

    #[test]
    fn equal_area_round_trips_and_is_unit() {
        let mut rng = Pcg32::new(11, 0);
        for _ in 0..100_000 {
            let p = Vec2::new(rng.next_f32(), rng.next_f32());
            let d = equal_area_square_to_sphere(p);
            assert!((d.length() - 1.0).abs() < 1e-5, "{p} -> {d}");
            let q = equal_area_sphere_to_square(d);
            // The polynomial-free atan keeps the round trip tight.
            assert!((p - q).abs().max_element() < 2e-4, "{p} -> {d} -> {q}");
        }
        // Corners and centre: the centre is +z, the corners -z.
        assert!((equal_area_square_to_sphere(Vec2::splat(0.5)) - Vec3::Z).length() < 1e-6);
        for c in [
            Vec2::ZERO,
            Vec2::ONE,
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 0.0),
        ] {
            assert!((equal_area_square_to_sphere(c) + Vec3::Z).length() < 1e-6);
        }
        // The midpoint of the right edge is -z's neighbour at the equator diamond's corner: +x on the equator.
        assert!((equal_area_square_to_sphere(Vec2::new(1.0, 0.5)) - Vec3::X).length() < 1e-5);
    }

    #[test]
    fn equal_area_preserves_area() {
        // Each cell of a 16x16 grid covers 4 pi / 256 sr: estimated by
        // counting uniform sphere directions that land in it.
        let mut rng = Pcg32::new(2, 7);
        let n = 16usize;
        let samples = 512_000;
        let mut counts = vec![0f64; n * n];
        for _ in 0..samples {
            let d = crate::sampling::square_to_uniform_sphere(Vec2::new(
                rng.next_f32(),
                rng.next_f32(),
            ));
            let q = equal_area_sphere_to_square(d);
            let (i, j) = (
                ((q.x * n as f32) as usize).min(n - 1),
                ((q.y * n as f32) as usize).min(n - 1),
            );
            counts[j * n + i] += 1.0;
        }
        let e = samples as f64 / (n * n) as f64;
        let chi2: f64 = counts.iter().map(|c| (c - e).powi(2) / e).sum();
        // 255 degrees of freedom: mean 255, sd 22.6; 400 is beyond 6 sd.
        assert!(chi2 < 400.0, "chi2 {chi2}");
    }

    #[test]
    fn wrap_gives_the_texel_across_the_fold() {
        // The texel just outside an edge holds directions next to those of
        // the texel the wrap returns.
        let (w, h) = (32, 32);
        let centre = |x: i32, y: i32| {
            equal_area_square_to_sphere(Vec2::new(
                (x as f32 + 0.5) / w as f32,
                (y as f32 + 0.5) / h as f32,
            ))
        };
        let texel = 4.0 * (PI / (w * h) as f32).sqrt(); // a few texel widths, in radians
        for k in 0..w {
            for (x, y) in [(-1, k), (w, k), (k, -1), (k, h)] {
                let (wx, wy) = wrap_equal_area_pixel(x, y, w, h);
                assert!((0..w).contains(&wx) && (0..h).contains(&wy));
                // Outside point: extrapolate the square map by reflecting it back.
                let p = Vec2::new((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
                let inside = Vec2::new(p.x.clamp(0.0, 1.0), p.y.clamp(0.0, 1.0));
                let edge = equal_area_square_to_sphere(inside);
                let angle = edge.dot(centre(wx, wy)).clamp(-1.0, 1.0).acos();
                assert!(angle < texel, "({x},{y}) -> ({wx},{wy}): {angle}");
            }
        }
        assert_eq!(wrap_equal_area_pixel(5, 6, 32, 32), (5, 6));
        assert_eq!(wrap_equal_area_pixel(32, 3, 32, 32), (31, 28));
        assert_eq!(wrap_equal_area_pixel(3, -1, 32, 32), (28, 0));
    }

    #[test]
    fn latlong_round_trips() {
        let mut rng = Pcg32::new(4, 0);
        for _ in 0..10_000 {
            let p = Vec2::new(rng.next_f32(), rng.next_f32() * 0.998 + 0.001);
            let (d, st) = latlong_to_sphere(p);
            assert!((d.length() - 1.0).abs() < 1e-5);
            assert!((st - (1.0 - d.z * d.z).sqrt()).abs() < 1e-3);
            let q = sphere_to_latlong(d);
            let du = (p.x - q.x).abs();
            assert!(
                du.min(1.0 - du) < 1e-4 && (p.y - q.y).abs() < 1e-4,
                "{p} {q}"
            );
        }
        assert!((latlong_to_sphere(Vec2::new(0.3, 0.0)).0 - Vec3::Z).length() < 1e-6);
        assert!((latlong_to_sphere(Vec2::new(0.25, 0.5)).0 - Vec3::Y).length() < 1e-6);
    }
}
