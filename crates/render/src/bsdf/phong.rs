//! Energy-normalized modified Phong (Lafortune & Willems 1994):
//! `f = kd / pi + ks (n + 2) / (2 pi) cos^n(alpha)` with `alpha` the angle
//! between `wi` and the mirror direction of `wo`.
//!
//! The specular lobe is sampled as `cos^n` around the mirror direction
//! (density `(n + 1) / (2 pi) cos^n(alpha)`); samples falling below the
//! surface are discarded, so that lobe's density is zero there. The lobe is
//! chosen with probability proportional to `average(kd)` vs `average(ks)`.
//! Two-sided like the other reflection BSDFs.

use super::{reflect_z, same_hemisphere, BsdfSample};
use lumis_math::{
    sampling::{cosine_hemisphere_pdf, spherical_direction, square_to_cosine_hemisphere},
    Frame, Rgb, Vec2, Vec3, INV_2PI, INV_PI,
};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Phong {
    pub kd: Rgb,
    pub ks: Rgb,
    pub exponent: f32,
}

impl Phong {
    /// Negative coefficients are clamped to zero, and wherever
    /// `kd + ks > 1` in a channel both are scaled down by their sum so that
    /// `kd + ks <= 1`: the BSDF then never reflects more than it receives
    /// (the normalization makes the specular albedo at most `ks`). A negative
    /// exponent is clamped to zero.
    pub fn new(kd: Rgb, ks: Rgb, exponent: f32) -> Self {
        let (mut kd, mut ks) = (
            kd.map(|v| v.max(0.0)).to_array(),
            ks.map(|v| v.max(0.0)).to_array(),
        );
        for (d, s) in kd.iter_mut().zip(ks.iter_mut()) {
            let sum = *d + *s;
            if sum > 1.0 {
                *d /= sum;
                *s /= sum;
            }
        }
        let (kd, ks) = (Rgb::from_slice(&kd), Rgb::from_slice(&ks));
        Phong {
            kd,
            ks,
            exponent: exponent.max(0.0),
        }
    }

    /// Probability of sampling the diffuse lobe.
    fn diffuse_prob(&self) -> f32 {
        let (d, s) = (self.kd.average(), self.ks.average());
        if d + s > 0.0 {
            d / (d + s)
        } else {
            0.0
        }
    }

    /// `cos(alpha)` clamped at zero.
    fn cos_alpha(wo: Vec3, wi: Vec3) -> f32 {
        reflect_z(wo).dot(wi).max(0.0)
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if !same_hemisphere(wo, wi) {
            return Rgb::BLACK;
        }
        let n = self.exponent;
        let spec = (n + 2.0) * INV_2PI * Self::cos_alpha(wo, wi).powf(n);
        self.kd * INV_PI + self.ks * spec
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if !same_hemisphere(wo, wi) {
            return 0.0;
        }
        let pd = self.diffuse_prob();
        let n = self.exponent;
        let spec = (n + 1.0) * INV_2PI * Self::cos_alpha(wo, wi).powf(n);
        pd * cosine_hemisphere_pdf(wi.z.abs()) + (1.0 - pd) * spec
    }

    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 || (self.kd.is_black() && self.ks.is_black()) {
            return None;
        }
        let wi = if uc < self.diffuse_prob() {
            let mut wi = square_to_cosine_hemisphere(u);
            wi.z = wi.z.copysign(wo.z);
            wi
        } else {
            let cos_a = u.x.powf(1.0 / (self.exponent + 1.0));
            let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
            let local = spherical_direction(sin_a, cos_a, 2.0 * std::f32::consts::PI * u.y);
            Frame::from_normal(reflect_z(wo)).to_world(local)
        };
        if !same_hemisphere(wo, wi) {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            wi,
            f: self.eval(wo, wi),
            pdf,
            delta: false,
            transmission: false,
            eta: 1.0,
        })
    }
}
