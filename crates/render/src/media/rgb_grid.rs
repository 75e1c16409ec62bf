//! pbrt-v4's `rgbgrid` medium: `sigma_a`, `sigma_s` and `Le` given per
//! voxel as colours over the box `[p0, p1]` (a missing coefficient grid is
//! 1 everywhere, as in pbrt-v4), all scaled by `scale` (`Lescale` for `Le`).

use super::voxels::{Majorants, Voxels};
use super::MediumPoint;
use lumis_math::{Rgb, Transform, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct RgbGrid {
    pub unit_from_world: Transform,
    pub sigma_a: Option<Voxels<Rgb>>,
    pub sigma_s: Option<Voxels<Rgb>>,
    pub scale: f32,
    pub le: Option<Voxels<Rgb>>,
    pub le_scale: f32,
    pub majorants: Majorants,
}

impl RgbGrid {
    pub fn new(
        unit_from_world: Transform,
        sigma_a: Option<Voxels<Rgb>>,
        sigma_s: Option<Voxels<Rgb>>,
        scale: f32,
        le: Option<Voxels<Rgb>>,
        le_scale: f32,
    ) -> RgbGrid {
        let max = |g: &Option<Voxels<Rgb>>, lo, hi| g.as_ref().map_or(1.0, |g| g.max_over(lo, hi));
        let majorants = Majorants::build(super::grid::MAJORANT_RES, |lo, hi| {
            scale * (max(&sigma_a, lo, hi) + max(&sigma_s, lo, hi))
        });
        RgbGrid {
            unit_from_world,
            sigma_a,
            sigma_s,
            scale,
            le,
            le_scale,
            majorants,
        }
    }

    pub fn point(&self, p: Vec3) -> MediumPoint {
        let q = self.unit_from_world.point(p);
        let get = |g: &Option<Voxels<Rgb>>| g.as_ref().map_or(Rgb::WHITE, |g| g.lookup(q));
        MediumPoint {
            sigma_a: get(&self.sigma_a) * self.scale,
            sigma_s: get(&self.sigma_s) * self.scale,
            le: self
                .le
                .as_ref()
                .map_or(Rgb::BLACK, |g| g.lookup(q) * self.le_scale),
        }
    }
}
