//! A thin dielectric sheet (pbrt-v4's ThinDielectricBxDF, §9.5.4): two
//! parallel smooth interfaces close together, light bouncing between them any
//! number of times. Reflection is a perfect mirror with
//! `R' = R + T^2 R / (1 - R^2)` (`R` the single interface's Fresnel
//! reflectance, `T = 1 - R`), transmission goes straight through (`wi = -wo`,
//! no bending, no radiance scaling) with `T' = 1 - R'`. Both lobes are delta.

use super::fresnel::fr_dielectric;
use super::{reflect_z, BsdfSample};
use lumis_math::{sqr, Rgb, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinDielectric {
    /// Index of refraction of the sheet over that of its surroundings.
    pub eta: f32,
}

impl ThinDielectric {
    pub fn new(eta: f32) -> Self {
        ThinDielectric { eta }
    }

    /// `(R', T')` for an outgoing direction with `|cos theta| = cos_abs`.
    pub fn split(&self, cos_abs: f32) -> (f32, f32) {
        let r = fr_dielectric(cos_abs, self.eta);
        if r >= 1.0 {
            return (1.0, 0.0);
        }
        let t = 1.0 - r;
        let r2 = r + sqr(t) * r / (1.0 - sqr(r));
        (r2, 1.0 - r2)
    }

    pub fn sample(&self, wo: Vec3, uc: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let (r, t) = self.split(wo.z.abs());
        if uc < r / (r + t) {
            let wi = reflect_z(wo);
            return Some(BsdfSample {
                wi,
                f: Rgb::splat(r / wi.z.abs()),
                pdf: r / (r + t),
                delta: true,
                transmission: false,
                eta: 1.0,
            });
        }
        let wi = -wo;
        Some(BsdfSample {
            wi,
            f: Rgb::splat(t / wi.z.abs()),
            pdf: t / (r + t),
            delta: true,
            transmission: true,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_incidence_matches_the_series() {
        // eta 1.5: R = 0.04 at normal incidence; R' = 2R / (1 + R).
        let b = ThinDielectric::new(1.5);
        let (r, t) = b.split(1.0);
        assert!((r - 0.08 / 1.04).abs() < 1e-6, "{r}");
        assert!((r + t - 1.0).abs() < 1e-7);
        // Index-matched: no interface.
        let (r, t) = ThinDielectric::new(1.0).split(0.3);
        assert!(r < 1e-12 && t == 1.0, "{r} {t}");
    }
}
