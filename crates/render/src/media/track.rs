//! Free-flight sampling and transmittance in a medium, with null collisions.
//!
//! Tentative collisions are sampled against a grey majorant `m` (the largest
//! channel of `sigma_t` on a segment): distance density `m exp(-m t)`, the
//! same for every channel. At a tentative collision the null coefficient
//! `sigma_n = m - sigma_a - sigma_s` is non-negative in every channel.
//! Integrators choose absorption, scattering or a null collision with
//! probabilities proportional to the channels' averages, and weight the
//! throughput by the chosen coefficient over `m` times that probability per
//! channel: unbiased per channel, so chromatic media need no spectral MIS.

use super::{Medium, MediumPoint};
use lumis_math::{Pcg32, Rgb, Vec3};

/// Calls `f(rng, p, coefficients, majorant)` at each tentative
/// collision along `o + t d` (`d` unit) within `[0, tmax)`, in order, until
/// `f` returns false. Returns whether the ray got through to `tmax`.
pub fn collisions(
    medium: &Medium,
    o: Vec3,
    d: Vec3,
    tmax: f32,
    rng: &mut Pcg32,
    mut f: impl FnMut(&mut Pcg32, Vec3, MediumPoint, f32) -> bool,
) -> bool {
    medium.majorants(o, d, tmax, |t0, t1, m| {
        if !(m > 0.0) {
            return true;
        }
        let mut t = t0;
        loop {
            // Memoryless: restarting at each segment's start is exact.
            t -= (1.0 - rng.next_f32()).ln() / m;
            if t >= t1 {
                return true;
            }
            let p = o + d * t;
            if !f(rng, p, medium.point(p), m) {
                return false;
            }
        }
    })
}

/// The null coefficient at a tentative collision, clamped at zero (float
/// rounding can make `m - sigma_t` a hair negative).
pub fn sigma_n(mp: &MediumPoint, m: f32) -> Rgb {
    (Rgb::splat(m) - mp.sigma_a - mp.sigma_s).map(|v| v.max(0.0))
}

/// Transmittance along `o + t d` over `[0, tmax)`: exact in a homogeneous
/// medium, ratio tracking (an unbiased estimate) in grids, with Russian
/// roulette once it is small.
pub fn transmittance(medium: &Medium, o: Vec3, d: Vec3, tmax: f32, rng: &mut Pcg32) -> Rgb {
    if let super::MediumKind::Homogeneous(h) = &medium.kind {
        let st = h.sigma_a + h.sigma_s;
        return st.map(|s| if s == 0.0 { 1.0 } else { (-s * tmax).exp() });
    }
    let mut tr = Rgb::WHITE;
    collisions(medium, o, d, tmax, rng, |rng, _, mp, m| {
        tr = tr * sigma_n(&mp, m) / m;
        let top = tr.max_component();
        if top < 0.05 {
            if rng.next_f32() < 0.75 {
                tr = Rgb::BLACK;
            } else {
                tr /= 0.25;
            }
        }
        !tr.is_black()
    });
    tr
}
