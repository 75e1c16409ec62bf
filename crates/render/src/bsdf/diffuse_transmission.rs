//! Lambertian reflection and transmission (pbrt-v4's DiffuseTransmissionBxDF):
//! `f = R / pi` for directions on the side of `wo`, `T / pi` on the other.
//! The lobe is chosen with probability proportional to the largest channel of
//! `R` and `T`, then a cosine-weighted direction on its side.

use super::{same_hemisphere, BsdfSample};
use lumis_math::{
    sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere},
    Rgb, Vec2, Vec3, INV_PI,
};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiffuseTransmission {
    /// Reflectance and transmittance; each channel should be in [0, 1].
    pub r: Rgb,
    pub t: Rgb,
}

impl DiffuseTransmission {
    pub fn new(r: Rgb, t: Rgb) -> Self {
        DiffuseTransmission { r, t }
    }

    /// Probabilities of choosing reflection and transmission.
    fn lobe_probs(&self) -> Option<(f32, f32)> {
        let (pr, pt) = (self.r.max_component(), self.t.max_component());
        if !(pr + pt > 0.0) {
            return None;
        }
        Some((pr / (pr + pt), pt / (pr + pt)))
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z == 0.0 || wi.z == 0.0 {
            return Rgb::BLACK;
        }
        if same_hemisphere(wo, wi) {
            self.r * INV_PI
        } else {
            self.t * INV_PI
        }
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some((pr, pt)) = self.lobe_probs() else {
            return 0.0;
        };
        if wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        let p = if same_hemisphere(wo, wi) { pr } else { pt };
        p * cosine_hemisphere_pdf(wi.z.abs())
    }

    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample> {
        let (pr, pt) = self.lobe_probs()?;
        if wo.z == 0.0 {
            return None;
        }
        let mut wi = square_to_cosine_hemisphere(u);
        let reflect = uc < pr;
        // Reflection on wo's side, transmission on the other.
        if (wo.z < 0.0) == reflect {
            wi.z = -wi.z;
        }
        let (f, p) = if reflect { (self.r, pr) } else { (self.t, pt) };
        Some(BsdfSample {
            wi,
            f: f * INV_PI,
            pdf: p * cosine_hemisphere_pdf(wi.z.abs()),
            delta: false,
            transmission: !reflect,
            eta: 1.0,
        })
    }
}
