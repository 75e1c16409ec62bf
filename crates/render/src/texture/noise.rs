//! Perlin's gradient noise (Perlin 2002, "Improving noise") and the sums of
//! octaves built on it, with pbrt-v4's conventions: the lattice is hashed
//! through Perlin's 256-entry permutation table, gradients are the 12 cube
//! edge directions chosen by the low 4 bits of the hash, blended with the
//! quintic `6t^5 - 15t^4 + 10t^3`; octaves grow in frequency by 1.99 and are
//! cut (smoothly) where they would alias across the texture footprint.

use lumis_math::Vec3;

pub use lumis_math::noise::noise;

fn lerp(t: f32, a: f32, b: f32) -> f32 {
    (1.0 - t) * a + t * b
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
    fn noise2_is_the_half_slice() {
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
