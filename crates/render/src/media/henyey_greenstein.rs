//! The Henyey-Greenstein phase function (pbrt-v4's conventions): with `wo`
//! and `wi` both pointing away from the scattering point,
//! `p = (1 - g^2) / (4 pi (1 + g^2 + 2 g cos)^(3/2))`, `cos = wo . wi`, so
//! `g > 0` scatters forward (light keeps going: `wi` near `-wo`), `g < 0`
//! backward, `g = 0` uniformly. Sampled exactly by inverting its CDF in
//! `cos`.

use super::PhaseSample;
use lumis_math::{Frame, Vec2, Vec3, INV_4PI, PI};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    /// Mean cosine of the scattering angle, in (-1, 1).
    pub g: f32,
}

impl HenyeyGreenstein {
    /// `g` clamped into [-0.99, 0.99] (at +-1 the function is a delta).
    pub fn new(g: f32) -> HenyeyGreenstein {
        HenyeyGreenstein {
            g: g.clamp(-0.99, 0.99),
        }
    }

    /// The density as a function of `cos = wo . wi`.
    pub fn of_cos(&self, cos: f32) -> f32 {
        let g = self.g;
        let denom = 1.0 + g * g + 2.0 * g * cos;
        INV_4PI * (1.0 - g * g) / (denom * denom.max(0.0).sqrt())
    }

    pub fn p(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.of_cos(wo.dot(wi))
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.p(wo, wi)
    }

    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<PhaseSample> {
        let g = self.g;
        let cos = if g.abs() < 1e-3 {
            1.0 - 2.0 * u.x
        } else {
            let s = (1.0 - g * g) / (1.0 + g - 2.0 * g * u.x);
            -(1.0 + g * g - s * s) / (2.0 * g)
        }
        .clamp(-1.0, 1.0);
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let local = Vec3::new(sin * phi.cos(), sin * phi.sin(), cos);
        let wi = Frame::from_normal(wo).to_world(local);
        Some(PhaseSample {
            wi,
            pdf: self.of_cos(cos),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integrates to one over the sphere, and its mean cosine of the
    /// scattering angle (between `-wo` and `wi`) is `g`.
    #[test]
    fn normalised_with_mean_cosine_g() {
        for g in [-0.9, -0.3, 0.0, 0.5, 0.95] {
            let h = HenyeyGreenstein::new(g);
            let n = 200_000;
            let (mut total, mut mean) = (0.0f64, 0.0f64);
            for i in 0..n {
                let cos = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
                let p = h.of_cos(cos as f32) as f64 * 2.0 * std::f64::consts::PI * 2.0 / n as f64;
                total += p;
                mean += -cos * p;
            }
            assert!((total - 1.0).abs() < 1e-3, "g {g}: integral {total}");
            assert!((mean - g as f64).abs() < 2e-3, "g {g}: mean cosine {mean}");
        }
    }
}
