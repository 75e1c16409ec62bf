//! pbrt-v4's `homogeneous` medium: the same coefficients everywhere, so one
//! majorant segment (the largest channel of `sigma_t`) covers any ray.

use super::MediumPoint;
use lumis_math::Rgb;

#[derive(Clone, Debug, PartialEq)]
pub struct Homogeneous {
    pub sigma_a: Rgb,
    pub sigma_s: Rgb,
    /// Emitted radiance (the RTE's source is `sigma_a * le`).
    pub le: Rgb,
}

impl Homogeneous {
    pub fn point(&self) -> MediumPoint {
        MediumPoint {
            sigma_a: self.sigma_a,
            sigma_s: self.sigma_s,
            le: self.le,
        }
    }

    pub fn majorant(&self) -> f32 {
        (self.sigma_a + self.sigma_s).max_component()
    }
}
