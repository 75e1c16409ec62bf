//! Participating media (issue "Participating media and volumetric
//! caustics"): so far the phase functions, the first piece; the media
//! themselves (homogeneous, grids), their majorants and the integrators'
//! use of them are still to come.
//!
//! Phase functions are a closed set, as materials and lights are: one
//! variant of [`Phase`] per file, dispatched by `match`. To add one, write
//! its file with `p`, `sample` and `pdf` (directions both pointing away
//! from the scattering point, densities per unit solid angle), add the
//! variant and its arms here, and a chi-square test in
//! `tests/phase_chi2.rs`.

mod henyey_greenstein;

pub use henyey_greenstein::HenyeyGreenstein;

use lumis_math::{Vec2, Vec3};

/// A phase-function sample: the incident direction and its density (the
/// phase function's value, since every phase function here is sampled
/// exactly).
#[derive(Clone, Copy, Debug)]
pub struct PhaseSample {
    pub wi: Vec3,
    pub pdf: f32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    HenyeyGreenstein(HenyeyGreenstein),
}

impl Phase {
    /// The phase function's value for light arriving from `wi` and leaving
    /// towards `wo` (both unit, pointing away from the scattering point).
    pub fn p(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Phase::HenyeyGreenstein(h) => h.p(wo, wi),
        }
    }

    /// An incident direction for `wo`, distributed as `p(wo, .)`.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<PhaseSample> {
        match self {
            Phase::HenyeyGreenstein(h) => h.sample(wo, u),
        }
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Phase::HenyeyGreenstein(h) => h.pdf(wo, wi),
        }
    }
}
