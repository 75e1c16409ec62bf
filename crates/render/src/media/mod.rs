//! Participating media: what fills space between surfaces (fog, smoke,
//! tea), as pbrt-v4 describes them, and how rays sample them.
//!
//! Media are a closed set, as materials and lights are: one variant of
//! [`MediumKind`] per file (`homogeneous.rs`, `grid.rs` for `uniformgrid`,
//! `rgb_grid.rs`, `cloud.rs`), dispatched by `match`. To add one, write its file with
//! `point` (the coefficients at a world point) and a way to bound them along
//! a ray (one constant, or a [`voxels::Majorants`] grid), add the variant
//! and its arms in [`Medium::point`] and [`Medium::majorants`], and its
//! parameters in `load/medium.rs`.
//!
//! Coefficients are RGB; sampling uses one grey majorant per segment (the
//! largest channel), so every channel shares the same distance density and
//! chromatic media need no spectral MIS (`track.rs`).
//!
//! Phase functions are a closed set too: one variant of [`Phase`] per file.
//! To add one, write its file with `p`, `sample` and `pdf` (directions both
//! pointing away from the scattering point, densities per unit solid
//! angle), add the variant and its arms here, and a chi-square test in
//! `tests/phase_chi2.rs`.

mod cloud;
mod grid;
mod henyey_greenstein;
mod homogeneous;
mod rgb_grid;
pub mod track;
pub mod voxels;

pub use cloud::Cloud;
pub use grid::{Grid, GridEmission};
pub use henyey_greenstein::HenyeyGreenstein;
pub use homogeneous::Homogeneous;
pub use rgb_grid::RgbGrid;

use lumis_math::{Rgb, Vec2, Vec3};

/// The coefficients at a point: absorption, scattering (per unit length)
/// and emitted radiance (the source term is `sigma_a * le`, as pbrt-v4's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MediumPoint {
    pub sigma_a: Rgb,
    pub sigma_s: Rgb,
    pub le: Rgb,
}

#[derive(Clone, Debug, PartialEq)]
pub enum MediumKind {
    Homogeneous(Homogeneous),
    Grid(Grid),
    RgbGrid(RgbGrid),
    Cloud(Cloud),
}

/// A medium: its coefficients and its phase function.
#[derive(Clone, Debug, PartialEq)]
pub struct Medium {
    pub kind: MediumKind,
    pub phase: Phase,
}

impl Medium {
    /// The coefficients at world point `p` (inside the medium's bounds).
    pub fn point(&self, p: Vec3) -> MediumPoint {
        match &self.kind {
            MediumKind::Homogeneous(m) => m.point(),
            MediumKind::Grid(m) => m.point(p),
            MediumKind::RgbGrid(m) => m.point(p),
            MediumKind::Cloud(m) => m.point(p),
        }
    }

    /// Calls `f(t0, t1, majorant)` over the ray `o + t d` (`d` of unit
    /// length, so `t` is a distance) within `[0, tmax)`, segment by segment
    /// in order, until `f` returns false; returns whether it got to the end.
    /// Outside the segments the medium is empty.
    pub fn majorants(
        &self,
        o: Vec3,
        d: Vec3,
        tmax: f32,
        mut f: impl FnMut(f32, f32, f32) -> bool,
    ) -> bool {
        match &self.kind {
            MediumKind::Homogeneous(m) => f(0.0, tmax, m.majorant()),
            MediumKind::Grid(m) => m.majorants.walk_ray(&m.unit_from_world, o, d, tmax, f),
            MediumKind::RgbGrid(m) => m.majorants.walk_ray(&m.unit_from_world, o, d, tmax, f),
            MediumKind::Cloud(m) => m.majorants.walk_ray(&m.unit_from_world, o, d, tmax, f),
        }
    }
}

/// The media on the two sides of a surface: `inside` against its normal,
/// `outside` along it (`None`: vacuum). Only surfaces where the two differ
/// carry one; a ray crossing any other keeps its medium.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MediumInterface {
    pub inside: Option<u32>,
    pub outside: Option<u32>,
}

impl MediumInterface {
    /// The medium a ray leaving the surface along `w` travels in (`ng` is
    /// the surface's geometric normal, as its shape orients it).
    pub fn towards(&self, w: Vec3, ng: Vec3) -> Option<u32> {
        if w.dot(ng) > 0.0 {
            self.outside
        } else {
            self.inside
        }
    }
}

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

/// The medium a light emits into: one medium, or, for an area light on a
/// shape between two media, the side each emitted ray leaves on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightMedium {
    In(Option<u32>),
    Between(MediumInterface),
}
