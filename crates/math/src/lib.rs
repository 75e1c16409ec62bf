//! Math for lumis: vectors (re-exported from glam), frames, transforms, RGB,
//! sampling warps with their densities, MIS heuristics, random numbers and
//! pixel samplers, spectra reduced to RGB. No rendering ideas live here.

pub mod frame;
pub mod mis;
pub mod noise;
pub mod rgb;
pub mod rng;
pub mod sampler;
pub mod sampling;
pub mod sobol;
pub mod spectrum;
pub mod transform;

pub use frame::Frame;
pub use glam::{Mat3, Mat4, Vec2, Vec3, Vec3A, Vec4};
pub use rgb::Rgb;
pub use rng::Pcg32;
pub use sampler::{Sampler, SamplerKind};
pub use transform::Transform;

pub const PI: f32 = std::f32::consts::PI;
pub const INV_PI: f32 = std::f32::consts::FRAC_1_PI;
pub const INV_2PI: f32 = 0.5 * std::f32::consts::FRAC_1_PI;
pub const INV_4PI: f32 = 0.25 * std::f32::consts::FRAC_1_PI;

/// Largest f32 strictly below one: the upper bound of every uniform sample.
pub const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

#[inline]
pub fn sqr(x: f32) -> f32 {
    x * x
}

/// `sqrt(max(0, x))`: guards against tiny negative rounding errors.
#[inline]
pub fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

#[inline]
pub fn lerp(t: f32, a: f32, b: f32) -> f32 {
    (1.0 - t) * a + t * b
}
