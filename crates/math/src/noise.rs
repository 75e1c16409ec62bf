//! Perlin's gradient noise (Perlin 2002, "Improving noise") with pbrt-v4's
//! conventions: the lattice is hashed through Perlin's 256-entry
//! permutation table, gradients are the 12 cube edge directions chosen by
//! the low 4 bits of the hash, blended with the quintic
//! `6t^5 - 15t^4 + 10t^3`. Textures build octaves on it; media (pbrt-v4's
//! `cloud`) use it and its gradient.

use crate::Vec3;

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

/// The gradient of [`noise`] at `p` (pbrt-v4's `DNoise`), by central
/// differences a thousandth of a lattice cell wide.
pub fn dnoise(p: Vec3) -> Vec3 {
    const H: f32 = 1e-3;
    let d = |e: Vec3| (noise(p + e * H) - noise(p - e * H)) / (2.0 * H);
    Vec3::new(d(Vec3::X), d(Vec3::Y), d(Vec3::Z))
}

#[cfg(test)]
mod tests {
    use super::*;

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
    }

    #[test]
    fn gradient_is_the_slope_of_the_noise() {
        let p = Vec3::new(1.37, -2.61, 0.42);
        let g = dnoise(p);
        let step = Vec3::new(0.3, -0.2, 0.5) * 1e-2;
        let expected = noise(p + step) - noise(p);
        assert!(
            (g.dot(step) - expected).abs() < 1e-4,
            "{} vs {expected}",
            g.dot(step)
        );
        // Zero on lattice points, but not its gradient.
        assert_eq!(noise(Vec3::new(3.0, 4.0, 5.0)), 0.0);
        assert!(dnoise(Vec3::new(3.0, 4.0, 5.0)).length() > 0.1);
    }
}
