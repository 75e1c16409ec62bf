//! Integrators: settings, per-path tracing and the shared light-sampling
//! module; `render.rs` is the orchestration (passes, threads, budgets).
//!
//! To add an integrator: its tracer in a file here, a variant in
//! [`IntegratorKind`], a branch in [`Integrator::li`], and its parameters in
//! `load/options.rs`.

pub mod direct;
pub mod lighting;
pub mod path;
pub mod photon;
pub mod render;

pub use render::{
    render, render_with, BadSample, Progress, RenderHooks, RenderOutcome, RenderSettings,
    RenderState,
};

use crate::geometry::Ray;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler};

/// Rays traced by kind, counted per thread and merged after each pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Camera rays: one per sample.
    pub camera: u64,
    /// Continuations after the first hit (specular chains, path bounces,
    /// `direct`'s BSDF-sampled rays).
    pub indirect: u64,
    /// Shadow rays of light sampling.
    pub shadow: u64,
    /// Final-gather rays (`photon`).
    pub gather: u64,
}

impl RayCounts {
    pub fn total(&self) -> u64 {
        self.camera + self.indirect + self.shadow + self.gather
    }
    pub fn add(&mut self, o: &RayCounts) {
        self.camera += o.camera;
        self.indirect += o.indirect;
        self.shadow += o.shadow;
        self.gather += o.gather;
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegratorKind {
    /// Unbiased path tracing with NEE and MIS: the reference.
    Path,
    /// Direct lighting only (through specular chains): a debugging aid.
    Direct,
    /// Photon mapping with final gathering and MIS-combined caustics.
    Photon,
}

impl IntegratorKind {
    pub const NAMES: &'static [&'static str] = &["path", "direct", "photon"];

    pub fn from_name(name: &str) -> Option<IntegratorKind> {
        match name {
            "path" => Some(IntegratorKind::Path),
            "direct" => Some(IntegratorKind::Direct),
            "photon" => Some(IntegratorKind::Photon),
            _ => None,
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            IntegratorKind::Path => "path",
            IntegratorKind::Direct => "direct",
            IntegratorKind::Photon => "photon",
        }
    }
}

#[derive(Clone, Debug)]
pub struct Integrator {
    pub kind: IntegratorKind,
    /// pbrt-v4's meaning: the number of scattering events after the camera
    /// ray; 0 shows emitters only, 1 adds direct lighting.
    pub max_depth: u32,
    /// Settings of the `photon` integrator (unused by the others).
    pub photon: photon::PhotonSettings,
}

impl Integrator {
    /// Radiance along a camera ray; `photon` must hold the photon context
    /// for the `photon` integrator (see `render.rs`).
    #[inline]
    pub fn li(
        &self,
        scene: &Scene,
        photon: Option<&photon::gather::PhotonCtx>,
        ray: Ray,
        sampler: &mut Sampler,
        rays: &mut RayCounts,
    ) -> Rgb {
        match (self.kind, photon) {
            (IntegratorKind::Photon, Some(ctx)) => photon::gather::li(ctx, ray, sampler, rays),
            (IntegratorKind::Direct, _) => direct::li(scene, ray, sampler, self.max_depth, rays),
            _ => path::li(scene, ray, sampler, self.max_depth, rays),
        }
    }
}
