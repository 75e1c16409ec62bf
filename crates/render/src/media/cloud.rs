//! pbrt-v4's `cloud` medium: a procedural cloud in the box `[p0, p1]` of
//! the medium's space, `sigma_a` and `sigma_s` scaled by a density in
//! [0, 1] made of five octaves of Perlin noise (the lookup point perturbed
//! by two octaves of the noise's gradient, `wispiness`), thinning with
//! height `y` and solid below `y = 0.5`, as pbrt-v4 computes it.

use super::voxels::Majorants;
use super::MediumPoint;
use lumis_math::noise::{dnoise, noise};
use lumis_math::{Rgb, Transform, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Cloud {
    /// World space to the medium's space (where the density is defined).
    pub medium_from_world: Transform,
    /// World space to the unit cube of the box (for the majorant walk).
    pub unit_from_world: Transform,
    pub sigma_a: Rgb,
    pub sigma_s: Rgb,
    pub density: f32,
    pub wispiness: f32,
    pub frequency: f32,
    /// One cell: the density is at most 1, so `sigma_t` bounds it.
    pub majorants: Majorants,
}

impl Cloud {
    pub fn new(
        medium_from_world: Transform,
        unit_from_world: Transform,
        sigma_a: Rgb,
        sigma_s: Rgb,
        density: f32,
        wispiness: f32,
        frequency: f32,
    ) -> Cloud {
        let sigma_t = (sigma_a + sigma_s).max_component();
        Cloud {
            medium_from_world,
            unit_from_world,
            sigma_a,
            sigma_s,
            density,
            wispiness,
            frequency,
            majorants: Majorants::build(1, |_, _| sigma_t),
        }
    }

    /// The density at `p` in the medium's space.
    pub fn density_at(&self, p: Vec3) -> f32 {
        let mut pp = p * self.frequency;
        if self.wispiness > 0.0 {
            let (mut omega, mut lambda) = (0.05 * self.wispiness, 10.0);
            for _ in 0..2 {
                pp += dnoise(pp * lambda) * omega;
                omega *= 0.5;
                lambda *= 1.99;
            }
        }
        let (mut d, mut omega, mut lambda) = (0.0, 0.5, 1.0);
        for _ in 0..5 {
            d += omega * noise(pp * lambda);
            omega *= 0.5;
            lambda *= 1.99;
        }
        let d = ((1.0 - p.y) * 4.5 * self.density * d).clamp(0.0, 1.0);
        (d + 2.0 * (0.5 - p.y).max(0.0)).clamp(0.0, 1.0)
    }

    pub fn point(&self, p: Vec3) -> MediumPoint {
        let d = self.density_at(self.medium_from_world.point(p));
        MediumPoint {
            sigma_a: self.sigma_a * d,
            sigma_s: self.sigma_s * d,
            le: Rgb::BLACK,
        }
    }
}
