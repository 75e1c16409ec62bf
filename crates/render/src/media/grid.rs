//! pbrt-v4's `uniformgrid` medium: `sigma_a` and `sigma_s` scaled by a
//! density grid over the box `[p0, p1]` of the medium's space, optionally
//! emitting (`Le` times a grid of scales, or a blackbody per voxel from a
//! temperature grid).

use super::voxels::{Majorants, Voxels};
use super::MediumPoint;
use lumis_math::{Rgb, Transform, Vec3};

/// Cells per axis of the majorant grid (pbrt-v4's 16).
pub const MAJORANT_RES: usize = 16;

#[derive(Clone, Debug, PartialEq)]
pub enum GridEmission {
    None,
    /// The same `Le` wherever the grid is.
    Uniform(Rgb),
    /// `Le` times a scale looked up in a grid.
    Scaled(Rgb, Voxels<f32>),
    /// Radiance per voxel (a temperature grid's blackbodies).
    PerVoxel(Voxels<Rgb>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// World space to the grid's unit cube (`[p0, p1]` mapped to `[0, 1]^3`).
    pub unit_from_world: Transform,
    pub sigma_a: Rgb,
    pub sigma_s: Rgb,
    pub density: Voxels<f32>,
    pub emission: GridEmission,
    pub majorants: Majorants,
}

impl Grid {
    pub fn new(
        unit_from_world: Transform,
        sigma_a: Rgb,
        sigma_s: Rgb,
        density: Voxels<f32>,
        emission: GridEmission,
    ) -> Grid {
        let sigma_t = (sigma_a + sigma_s).max_component();
        let majorants = Majorants::build(MAJORANT_RES, |lo, hi| sigma_t * density.max_over(lo, hi));
        Grid {
            unit_from_world,
            sigma_a,
            sigma_s,
            density,
            emission,
            majorants,
        }
    }

    pub fn point(&self, p: Vec3) -> MediumPoint {
        let q = self.unit_from_world.point(p);
        let d = self.density.lookup(q);
        let le = match &self.emission {
            GridEmission::None => Rgb::BLACK,
            GridEmission::Uniform(le) => *le,
            GridEmission::Scaled(le, s) => *le * s.lookup(q),
            GridEmission::PerVoxel(v) => v.lookup(q),
        };
        MediumPoint {
            sigma_a: self.sigma_a * d,
            sigma_s: self.sigma_s * d,
            le,
        }
    }
}
