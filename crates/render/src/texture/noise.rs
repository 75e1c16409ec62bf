//! Perlin's gradient noise (Perlin 2002, "Improving noise") and the sums of
//! octaves built on it, with pbrt-v4's conventions: the lattice is hashed
//! through Perlin's 256-entry permutation table, gradients are the 12 cube
//! edge directions chosen by the low 4 bits of the hash, blended with the
//! quintic `6t^5 - 15t^4 + 10t^3`; octaves grow in frequency by 1.99 and are
//! cut (smoothly) where they would alias across the texture footprint.

use lumis_math::Vec3;

/// Perlin's reference permutation of 0..=255 (public data of his reference
/// implementation; pbrt-v4 uses the same table, so textures line up).
const PERM: [u8; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69,
    142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219,
    203, 117, 35, 11, 32, 57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122, 60, 211, 133, 230,
    220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76,
    132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173,
    186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206,
    59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163,
    70, 221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232,
    178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162,
    241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204,
    176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141,
    128, 195, 78, 66, 215, 61, 156, 180,
];

#[inline]
fn perm(i: i32) -> i32 {
    PERM[(i & 255) as usize] as i32
}

/// Gradient of lattice point `(x, y, z)` dotted with the offset `d` from it.
fn grad(x: i32, y: i32, z: i32, d: Vec3) -> f32 {
    let h = perm(perm(perm(x) + y) + z) & 15;
    let u = if h < 8 || h == 12 || h == 13 {
        d.x
    } else {
        d.y
    };
    let v = if h < 4 || h == 12 || h == 13 {
        d.y
    } else {
        d.z
    };
    (if h & 1 != 0 { -u } else { u }) + (if h & 2 != 0 { -v } else { v })
}

/// Quintic blend: zero first and second derivatives at 0 and 1.
fn weight(t: f32) -> f32 {
    t * t * t * (10.0 + t * (-15.0 + 6.0 * t))
}

fn lerp(t: f32, a: f32, b: f32) -> f32 {
    (1.0 - t) * a + t * b
}

/// Noise at `p`: zero on every lattice point, in [-1, 1], period 256.
pub fn noise(p: Vec3) -> f32 {
    // Large coordinates wrap (as pbrt-v4's fmod by 2^30) before flooring.
    let wrap = |x: f32| x % (1u32 << 30) as f32;
    let (x, y, z) = (wrap(p.x), wrap(p.y), wrap(p.z));
    let (fx, fy, fz) = (x.floor(), y.floor(), z.floor());
    let d = Vec3::new(x - fx, y - fy, z - fz);
    let (ix, iy, iz) = (fx as i32 & 255, fy as i32 & 255, fz as i32 & 255);
    let g = |i: i32, j: i32, k: i32| {
        grad(
            ix + i,
            iy + j,
            iz + k,
            d - Vec3::new(i as f32, j as f32, k as f32),
        )
    };
    let (wx, wy, wz) = (weight(d.x), weight(d.y), weight(d.z));
    let x00 = lerp(wx, g(0, 0, 0), g(1, 0, 0));
    let x10 = lerp(wx, g(0, 1, 0), g(1, 1, 0));
    let x01 = lerp(wx, g(0, 0, 1), g(1, 0, 1));
    let x11 = lerp(wx, g(0, 1, 1), g(1, 1, 1));
    lerp(wz, lerp(wy, x00, x10), lerp(wy, x01, x11))
}

/// 2D noise as pbrt-v4's `Noise(x, y)`: the slice `z = 0.5`.
pub fn noise2(x: f32, y: f32) -> f32 {
    noise(Vec3::new(x, y, 0.5))
}

fn smooth_step(x: f32, a: f32, b: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Octaves that the footprint `(dpdx, dpdy)` can resolve, up to `max`.
fn octaves(dpdx: Vec3, dpdy: Vec3, max: u32) -> f32 {
    let len2 = dpdx.length_squared().max(dpdy.length_squared());
    // len2 = 0 gives +inf: every octave.
    (-1.0 - 0.5 * len2.log2()).clamp(0.0, max as f32)
}

/// Fractional Brownian motion: `sum omega^i noise(1.99^i p)`, the last octave
/// faded in by a smooth step of the fractional octave count.
pub fn fbm(p: Vec3, dpdx: Vec3, dpdy: Vec3, omega: f32, max_octaves: u32) -> f32 {
    let n = octaves(dpdx, dpdy, max_octaves);
    let n_int = n.floor() as u32;
    let (mut sum, mut lambda, mut o) = (0.0, 1.0f32, 1.0f32);
    for _ in 0..n_int {
        sum += o * noise(p * lambda);
        lambda *= 1.99;
        o *= omega;
    }
    sum + o * smooth_step(n - n_int as f32, 0.3, 0.7) * noise(p * lambda)
}

/// Turbulence: as [`fbm`] with `|noise|`; octaves too fine for the footprint
/// count as their mean magnitude, 0.2.
pub fn turbulence(p: Vec3, dpdx: Vec3, dpdy: Vec3, omega: f32, max_octaves: u32) -> f32 {
    let n = octaves(dpdx, dpdy, max_octaves);
    let n_int = n.floor() as u32;
    let (mut sum, mut lambda, mut o) = (0.0, 1.0f32, 1.0f32);
    for _ in 0..n_int {
        sum += o * noise(p * lambda).abs();
        lambda *= 1.99;
        o *= omega;
    }
    let s = smooth_step(n - n_int as f32, 0.3, 0.7);
    sum += o * lerp(s, 0.2, noise(p * lambda).abs());
    for _ in n_int..max_octaves {
        sum += o * 0.2;
        o *= omega;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::Pcg32;

    #[test]
    fn zero_on_the_lattice_and_periodic() {
        for (x, y, z) in [
            (0, 0, 0),
            (1, 2, 3),
            (-4, 7, -1),
            (255, 256, 1000),
            (-300, 5, 9),
        ] {
            let p = Vec3::new(x as f32, y as f32, z as f32);
            assert_eq!(noise(p), 0.0, "{p:?}");
        }
        let p = Vec3::new(0.3, 1.7, -2.2);
        let shifted = p + Vec3::new(256.0, -512.0, 256.0);
        assert!((noise(p) - noise(shifted)).abs() < 1e-4);
        assert!(noise(p) != 0.0);
    }

    #[test]
    fn hand_computed_value() {
        // At (0.25, 0, 0) only the x edge of the cell counts (wy = wz = 0).
        // Hashes: perm(perm(perm(0))) = 4 (gradient x + z), and for the
        // corner (1, 0, 0) 6 (gradient x - z); offsets (0.25, 0, 0) and
        // (-0.75, 0, 0) give 0.25 and -0.75; blend weight w(0.25) =
        // 0.103515625: (1 - w) 0.25 + w (-0.75) = 0.25 - w.
        assert_eq!(perm(perm(perm(0))) & 15, 4);
        assert_eq!(perm(perm(perm(1))) & 15, 6);
        assert!((weight(0.25) - 53.0 / 512.0).abs() < 1e-7); // 0.103515625
        let n = noise(Vec3::new(0.25, 0.0, 0.0));
        assert!((n - 75.0 / 512.0).abs() < 1e-6, "{n}"); // 0.146484375
        assert_eq!(noise2(0.25, 0.0), noise(Vec3::new(0.25, 0.0, 0.5)));
    }

    #[test]
    fn range_and_statistics() {
        let mut rng = Pcg32::new(9, 3);
        let n = 200_000;
        let (mut sum, mut sum2, mut max) = (0.0f64, 0.0f64, 0.0f32);
        for _ in 0..n {
            let p = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 200.0
                - Vec3::splat(100.0);
            let v = noise(p);
            assert!(v.abs() <= 1.0, "{p:?}: {v}");
            max = max.max(v.abs());
            sum += v as f64;
            sum2 += (v * v) as f64;
        }
        let mean = sum / n as f64;
        let sd = (sum2 / n as f64 - mean * mean).sqrt();
        // Symmetric gradients: mean 0 (4.5 standard errors); spread ~0.2.
        assert!(mean.abs() < 4.5 * sd / (n as f64).sqrt(), "{mean}");
        assert!(sd > 0.1 && sd < 0.4 && max > 0.5, "sd {sd} max {max}");
        // fBm's octaves are bounded by the geometric sum of their weights.
        let (omega, oct) = (0.5f32, 8);
        let bound = (1.0 - omega.powi(oct)) / (1.0 - omega);
        for _ in 0..2000 {
            let p = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 50.0;
            let f = fbm(p, Vec3::ZERO, Vec3::ZERO, omega, oct as u32);
            let t = turbulence(p, Vec3::ZERO, Vec3::ZERO, omega, oct as u32);
            assert!(
                f.abs() <= bound && (0.0..=bound + 0.2).contains(&t),
                "{f} {t}"
            );
        }
    }

    #[test]
    fn octaves_follow_the_footprint() {
        let p = Vec3::new(0.37, 1.21, 2.93);
        // A footprint of a whole unit: no octave resolves; turbulence counts
        // every clamped octave as 0.2 (and the partial one too, as pbrt-v4).
        let big = Vec3::new(2.0, 0.0, 0.0);
        assert_eq!(fbm(p, big, big, 0.5, 8), 0.0);
        let want = 0.2 + 0.2 * (1.0 - 0.5f32.powi(8)) / 0.5;
        assert!((turbulence(p, big, big, 0.5, 8) - want).abs() < 1e-5);
        // Footprint 2^-3.5: octaves 2.5, the third octave faded in by half.
        let d = Vec3::new(2f32.powf(-3.5), 0.0, 0.0);
        let two = noise(p) + 0.5 * noise(p * 1.99);
        let third = 0.25 * 0.5 * noise(p * 1.99 * 1.99);
        assert!((fbm(p, d, Vec3::ZERO, 0.5, 8) - (two + third)).abs() < 1e-5);
        // No footprint: all octaves.
        let mut all = 0.0;
        for i in 0..4 {
            all += 0.7f32.powi(i) * noise(p * 1.99f32.powi(i));
        }
        assert!((fbm(p, Vec3::ZERO, Vec3::ZERO, 0.7, 4) - all).abs() < 1e-4);
    }
}
