//! A stored photon in 24 bytes: position, power, incident direction and the
//! emitted luminance at its origin (for the caustic MIS weights).
//!
//! Power is three 16-bit unsigned floats (6-bit exponent, 10-bit mantissa,
//! relative error <= 2^-11 on every component, range ~5e-10..4e9). A shared
//! exponent RGBE in 32 bits cannot keep 1% on a component 1/256 of the largest
//! (it would need 15-bit mantissas), so power and `le` share 8 bytes as four
//! such halves instead; `le` reserves one code for infinity (delta lights).
//! The direction is octahedral, 16 bits per axis, rounded to nearest
//! (error ~0.002 degrees).

// `photon::photon` is the layout the integrator asked for.
#![allow(clippy::module_inception)]

use lumis_math::{Rgb, Vec3};

#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub struct Photon {
    pos: [f32; 3],
    power: [u16; 3],
    le: u16,
    dir: u32,
}

impl Photon {
    /// `dir`: unit vector from the surface back towards where the photon came
    /// from. `le`: emitted luminance at the photon's origin (may be infinite).
    pub fn new(pos: Vec3, power: Rgb, dir: Vec3, le: f32) -> Photon {
        Photon {
            pos: pos.to_array(),
            power: [
                encode_half(power.r),
                encode_half(power.g),
                encode_half(power.b),
            ],
            le: if le == f32::INFINITY {
                LE_INFINITY
            } else {
                encode_half(le).min(LE_INFINITY - 1)
            },
            dir: encode_oct(dir),
        }
    }

    #[inline]
    pub fn pos(&self) -> Vec3 {
        Vec3::from_array(self.pos)
    }

    #[inline]
    pub fn power(&self) -> Rgb {
        Rgb::new(
            decode_half(self.power[0]),
            decode_half(self.power[1]),
            decode_half(self.power[2]),
        )
    }

    /// Unit incident direction (towards where the photon came from).
    #[inline]
    pub fn dir(&self) -> Vec3 {
        decode_oct_unnormalized(self.dir).normalize()
    }

    /// The incident direction up to a positive scale: enough for side tests.
    #[inline]
    pub(crate) fn dir_unnormalized(&self) -> Vec3 {
        decode_oct_unnormalized(self.dir)
    }

    #[inline]
    pub fn le(&self) -> f32 {
        if self.le == LE_INFINITY {
            f32::INFINITY
        } else {
            decode_half(self.le)
        }
    }
}

const LE_INFINITY: u16 = u16::MAX;
/// f32 exponent bias (127) minus ours (32).
const REBIAS: u32 = 95 << 10;

/// Non-negative finite f32 to a 16-bit unsigned float, rounded to nearest;
/// below ~4.7e-10 (and NaN, negatives) flushes to 0, above ~4.3e9 saturates.
#[inline]
fn encode_half(x: f32) -> u16 {
    if !(x > 0.0) {
        return 0;
    }
    let bits = (x.to_bits() + (1 << 12)) >> 13;
    if bits <= REBIAS {
        0
    } else {
        (bits - REBIAS).min(u16::MAX as u32) as u16
    }
}

#[inline]
fn decode_half(h: u16) -> f32 {
    if h == 0 {
        0.0
    } else {
        f32::from_bits((h as u32 + REBIAS) << 13)
    }
}

#[inline]
fn sign_not_zero(v: f32) -> f32 {
    if v >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

fn quantize(v: f32) -> u32 {
    ((v.clamp(-1.0, 1.0) * 0.5 + 0.5) * 65535.0).round() as u32
}

/// Octahedral map (Cigolle et al. 2014), 16 bits per axis.
fn encode_oct(d: Vec3) -> u32 {
    let l1 = d.x.abs() + d.y.abs() + d.z.abs();
    if !(l1 > 0.0) || !l1.is_finite() {
        return quantize(0.0) | quantize(0.0) << 16; // +z for degenerate input
    }
    let (mut u, mut v) = (d.x / l1, d.y / l1);
    if d.z < 0.0 {
        (u, v) = (
            (1.0 - v.abs()) * sign_not_zero(u),
            (1.0 - u.abs()) * sign_not_zero(v),
        );
    }
    quantize(u) | quantize(v) << 16
}

#[inline]
fn decode_oct_unnormalized(e: u32) -> Vec3 {
    const S: f32 = 2.0 / 65535.0;
    let u = (e & 0xffff) as f32 * S - 1.0;
    let v = (e >> 16) as f32 * S - 1.0;
    let z = 1.0 - u.abs() - v.abs();
    let t = (-z).max(0.0);
    Vec3::new(u - t * sign_not_zero(u), v - t * sign_not_zero(v), z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn photon_is_24_bytes() {
        assert!(std::mem::size_of::<Photon>() <= 24);
    }

    #[test]
    fn half_round_trip_and_limits() {
        for &x in &[1e-6f32, 1e-3, 0.1, 1.0, 1.5, 3.0, 1e3, 1e6, 1e9] {
            let y = decode_half(encode_half(x));
            assert!((y - x).abs() <= x * 4.9e-4, "{x} -> {y}");
        }
        assert_eq!(decode_half(encode_half(0.0)), 0.0);
        assert_eq!(decode_half(encode_half(-1.0)), 0.0);
        assert_eq!(decode_half(encode_half(f32::NAN)), 0.0);
        assert_eq!(decode_half(encode_half(1e-12)), 0.0);
        assert!(decode_half(encode_half(1e12)) > 4e9);
        let p = Photon::new(Vec3::ZERO, Rgb::WHITE, Vec3::Z, 1e30);
        assert!(p.le().is_finite() && p.le() > 4e9);
    }

    #[test]
    fn octahedral_axes_exact_enough() {
        for d in [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z] {
            let e = decode_oct_unnormalized(encode_oct(d)).normalize();
            assert!(e.dot(d) > 1.0 - 1e-7, "{d} -> {e}");
        }
    }
}
