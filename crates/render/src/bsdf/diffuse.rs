//! Lambertian reflection with cosine-weighted sampling.

use super::{same_hemisphere, BsdfSample};
use lumis_math::{
    sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere},
    Rgb, Vec2, Vec3, INV_PI,
};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diffuse {
    /// Albedo; each channel should be in [0, 1].
    pub r: Rgb,
}

impl Diffuse {
    pub fn new(r: Rgb) -> Self {
        Diffuse { r }
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if !same_hemisphere(wo, wi) {
            return Rgb::BLACK;
        }
        self.r * INV_PI
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if !same_hemisphere(wo, wi) {
            return 0.0;
        }
        cosine_hemisphere_pdf(wi.z.abs())
    }

    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        let mut wi = square_to_cosine_hemisphere(u);
        if wo.z < 0.0 {
            wi.z = -wi.z;
        }
        let pdf = cosine_hemisphere_pdf(wi.z.abs());
        if pdf == 0.0 || wo.z == 0.0 {
            return None;
        }
        Some(BsdfSample {
            wi,
            f: self.r * INV_PI,
            pdf,
            delta: false,
            transmission: false,
            eta: 1.0,
        })
    }
}
