//! Integrators: each one's settings, orchestration and per-path tracing, the
//! shared render driver and the shared light-sampling module.
//!
//! - `driver.rs` runs passes of samples over the film for any integrator:
//!   rows in parallel, sample indexing, clamping, bad-sample accounting,
//!   splats, the time budget, cancellation, progress and checkpoint hooks.
//! - Each integrator is a variant of [`Integrator`] carrying its settings,
//!   and a [`run::Run`] variant that holds what it builds for a render and
//!   its own state between passes (photon maps, `alpha` prediction), which
//!   checkpoints store as bytes without knowing what they are.
//! - `lighting.rs`: light sampling, MIS and the emission weights, shared.
//!
//! To add an integrator: its tracer in a file (or folder) here, a variant in
//! [`Integrator`] and in [`run::Run`] (with what it does before and after each
//! pass), and its parameters read in `load/options.rs` from its own
//! [`lumis_scene::ParamSpec`] table.

pub mod bdpt;
pub mod direct;
pub mod driver;
pub mod lighting;
pub mod lighttracer;
pub mod path;
pub mod photon;
pub mod run;
mod splatted;
pub mod vcm;
pub mod volpath;

pub use driver::{
    render, render_with, BadSample, Progress, RenderHooks, RenderOutcome, RenderSettings,
    RenderState,
};

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

/// An integrator with its settings.
#[derive(Clone, Debug, PartialEq)]
pub enum Integrator {
    /// Unbiased path tracing with NEE and MIS: the reference.
    Path { max_depth: u32 },
    /// Direct lighting only (through specular chains): a debugging aid.
    Direct { max_depth: u32 },
    /// Photon mapping with final gathering and MIS-combined caustics.
    Photon(photon::PhotonSettings),
    /// Light tracing: light paths connected to the camera (pbrt-v4's
    /// `lightpath`), the oracle for caustics from delta lights.
    LightTracer { max_depth: u32 },
    /// Bidirectional path tracing with MIS over all connection strategies.
    Bdpt(bdpt::BdptSettings),
    /// Vertex connection and merging: bdpt's strategies and photon-map
    /// merges, MIS-weighted, with a radius that shrinks over passes.
    Vcm(vcm::VcmSettings),
}

impl Integrator {
    /// Names as written in scene files (`Integrator "photon"`).
    pub const NAMES: &'static [&'static str] = &[
        "path",
        "direct",
        "photon",
        "lighttracer",
        "lightpath",
        "bdpt",
        "vcm",
    ];

    /// The integrator called `name` with its default settings at `max_depth`
    /// (pbrt-v4's meaning: scattering events after the camera ray; 0 shows
    /// emitters only, 1 adds direct lighting).
    pub fn from_name(name: &str, max_depth: u32) -> Option<Integrator> {
        match name {
            "path" => Some(Integrator::Path { max_depth }),
            "direct" => Some(Integrator::Direct { max_depth }),
            "lighttracer" | "lightpath" => Some(Integrator::LightTracer { max_depth }),
            "bdpt" => Some(Integrator::Bdpt(bdpt::BdptSettings::new(max_depth))),
            "vcm" => Some(Integrator::Vcm(vcm::VcmSettings::new(max_depth))),
            "photon" => Some(Integrator::Photon(photon::PhotonSettings {
                max_depth,
                ..Default::default()
            })),
            _ => None,
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            Integrator::Path { .. } => "path",
            Integrator::Direct { .. } => "direct",
            Integrator::Photon(_) => "photon",
            Integrator::LightTracer { .. } => "lighttracer",
            Integrator::Bdpt(_) => "bdpt",
            Integrator::Vcm(_) => "vcm",
        }
    }

    pub fn max_depth(&self) -> u32 {
        match self {
            Integrator::Path { max_depth }
            | Integrator::Direct { max_depth }
            | Integrator::LightTracer { max_depth } => *max_depth,
            Integrator::Photon(s) => s.max_depth,
            Integrator::Bdpt(s) => s.max_depth,
            Integrator::Vcm(s) => s.max_depth,
        }
    }

    /// The photon settings, for the `photon` integrator.
    pub fn photon(&self) -> Option<&photon::PhotonSettings> {
        match self {
            Integrator::Photon(s) => Some(s),
            _ => None,
        }
    }
}
