//! Henyey-Greenstein phase function of the medium between the layers.
//!
//! Directions follow the BSDF convention: `wo` points back along the path
//! (away from the scattering point), `wi` is the new propagation direction,
//! so the scattering angle's cosine is `-wo·wi`.

use lumis_math::{Frame, Vec2, Vec3, INV_4PI, PI};

/// Phase function value for the scattering-angle cosine `mu` (propagation
/// in · propagation out) and asymmetry `g` in (-1, 1).
pub fn hg(mu: f32, g: f32) -> f32 {
    let denom = 1.0 + g * g - 2.0 * g * mu;
    INV_4PI * (1.0 - g * g) / (denom * denom.max(0.0).sqrt())
}

/// `p(wo, wi)` in the BSDF convention.
pub fn p(g: f32, wo: Vec3, wi: Vec3) -> f32 {
    hg(-wo.dot(wi), g)
}

/// Sample `wi` with density `p(g, wo, wi)`; returns the direction and its
/// density (equal to the value: the phase function is normalised).
pub fn sample(g: f32, wo: Vec3, u: Vec2) -> (Vec3, f32) {
    let mu = if g.abs() < 1e-3 {
        1.0 - 2.0 * u.x
    } else {
        // Inverse of the cumulative distribution of mu.
        let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
        (1.0 + g * g - s * s) / (2.0 * g)
    }
    .clamp(-1.0, 1.0);
    let sin = (1.0 - mu * mu).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    let local = Vec3::new(sin * phi.cos(), sin * phi.sin(), mu);
    let wi = Frame::from_normal(-wo).to_world(local);
    (wi, hg(mu, g))
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::Pcg32;

    /// Normalised, mean cosine `g`, and sampling follows the density.
    #[test]
    fn normalised_with_mean_cosine_g() {
        for g in [-0.7f32, 0.0, 0.3, 0.9] {
            // Midpoint rule in mu (the density is smooth for |g| <= 0.9).
            let n = 200_000;
            let (mut mass, mut mean) = (0.0f64, 0.0f64);
            for i in 0..n {
                let mu = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
                let v = 2.0 * std::f64::consts::PI * hg(mu as f32, g) as f64 * 2.0 / n as f64;
                mass += v;
                mean += v * mu;
            }
            assert!((mass - 1.0).abs() < 1e-3, "g {g}: mass {mass}");
            assert!((mean - g as f64).abs() < 2e-3, "g {g}: mean {mean}");
            // Sampled mean cosine: g within 4.5 standard errors.
            let wo = Vec3::new(0.3, -0.4, 0.866).normalize();
            let mut rng = Pcg32::new(5, 7);
            let m = 100_000;
            let (mut s, mut s2) = (0.0f64, 0.0f64);
            for _ in 0..m {
                let (wi, pdf) = sample(g, wo, Vec2::new(rng.next_f32(), rng.next_f32()));
                assert!((wi.length() - 1.0).abs() < 1e-4);
                assert!((pdf - p(g, wo, wi)).abs() <= 1e-3 * pdf.max(1.0));
                let mu = -wo.dot(wi) as f64;
                s += mu;
                s2 += mu * mu;
            }
            let mean = s / m as f64;
            let se = ((s2 / m as f64 - mean * mean) / m as f64).sqrt();
            assert!((mean - g as f64).abs() < 4.5 * se, "g {g}: {mean} +- {se}");
        }
    }
}
