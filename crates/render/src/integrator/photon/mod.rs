//! The `photon` integrator: photon mapping with final gathering, where the
//! caustic part is estimated twice (caustic photon map and final-gather rays)
//! and combined per sample with the seed's weights (`../shared/METHOD.md`).
//!
//! Orchestration is in `run.rs` (the photon passes between the camera
//! passes, `alpha`) and `pass.rs` (a photon pass's maps); per-path tracing in
//! `trace.rs` (photons) and `gather.rs` (camera paths); settings here;
//! weights in `weights.rs`; the progressive mode's iteration schedule and
//! shrinking radius in `progressive.rs`.

pub mod aim;
pub mod budget;
pub mod camera;
pub mod connect;
mod disc_grid;
pub mod gather;
mod kdtree;
pub mod map;
pub mod order;
pub mod pass;
pub mod photon;
pub mod polar;
pub mod progressive;
pub mod radiance;
pub mod radius_field;
pub mod run;
pub mod trace;
pub mod volume;
pub mod weights;

use lumis_scene::ParamSpec;
pub use pass::{PhotonMaps, PhotonStats, Radii, GLOBAL_RADIUS_SCALE, RADIANCE_STRIDE};
pub use progressive::Progressive;
pub use weights::{AlphaMode, CausticMode, Heuristic};

/// Density-estimation filter for the caustic photons.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// Constant over the disc: `sum f Phi / (pi r^2)`.
    None,
    /// Jensen's cone filter with k = 1.1: weight `1 - d / (k r)`, normalised by `1 - 2 / (3 k)`.
    Cone,
}

#[derive(Clone, Debug, PartialEq)]
pub struct PhotonSettings {
    /// Photons emitted for the global map.
    pub global_photons: u64,
    /// Photons emitted for the caustic map (only `L S+ D` paths are stored).
    pub caustic_photons: u64,
    /// `m_1`: nearest photons per estimate.
    pub nearest: usize,
    /// `m_2`: final-gather rays at the first non-delta camera hit.
    pub gather_rays: u32,
    /// The gather rays' weight against the photon techniques at the first
    /// non-delta camera hit: `alpha` of `q_1` (and `q_3`) times this. 1: the
    /// seed's weights.
    pub gather_gain: f32,
    /// Progressive: up to this many times `gather_rays` at a camera hit,
    /// in proportion to the share of the irradiance there that the gather
    /// rays carry of the caustics (`RadiusField::at`, measured on the
    /// first iteration's maps). 1: `gather_rays` everywhere.
    pub gather_boost: f32,
    /// Camera paths follow both lobes of the first this-many smooth
    /// dielectric interfaces they meet (see `camera.rs`).
    pub specular_splits: u32,
    /// Largest photon search radius (scene units); 0 = 2% of the scene's bounding radius.
    pub max_radius: f32,
    pub caustics: CausticMode,
    pub heuristic: Heuristic,
    /// `alpha` in q_1 at the first non-delta camera hit.
    pub alpha: AlphaMode,
    pub max_depth: u32,
    pub kernel: Kernel,
    /// Read the global map through Christensen's precomputed radiance photons
    /// (true) or by direct k-nearest estimation (false).
    pub radiance_photons: bool,
    /// Emit caustic photons only towards perfectly specular shapes
    /// (see `aim.rs`); their fluxes then differ and q_1 uses each photon's own.
    pub aim_caustics: bool,
    /// Caustics seen directly by the camera (`L S+ D E`) also from the
    /// caustic photons connected to the camera as they are stored (the
    /// light tracer's strategy), a third technique beside the caustic map
    /// and the gather rays (`connect.rs`). Progressive mode with the seed's
    /// weights only; off in scenes with media.
    pub connect_caustics: bool,
    /// Render in iterations, each with fresh maps and shrinking radii (the
    /// default; `None`: one pair of maps for the whole render, the
    /// single-map baseline).
    pub progressive: Option<Progressive>,
}

/// The progressive mode's defaults (docs/integrators.md, "Choosing the
/// defaults", says how they were measured): per iteration, photons for the
/// global and the caustic map, and gather rays per camera sample.
pub const PROGRESSIVE_PHOTONS: (u64, u64) = (PROG_GLOBAL, PROG_CAUSTIC);
const PROG_GLOBAL: u64 = 40_000;
const PROG_CAUSTIC: u64 = 200_000;
const PROG_GATHER_RAYS: u32 = 4;
/// The Sobol sampler lowers the gather rays' caustic error per iteration
/// 3.4 times on `sphere-large-light` and the photons' 1.04 times, which the
/// seed's density-based weights cannot see; 3 there lowers the 120 s error
/// to 0.80 and leaves the other scenes of the caustic set and the default
/// scene within their noise (docs/integrators.md, "Why the large light
/// resists"). The single map keeps the seed's weights (1).
const PROG_GATHER_GAIN: f32 = 3.0;
/// Up to 4 times the gather rays where they carry the caustics: 0.88-0.90
/// of the error on `sphere-large-light` at 30 and 120 s, 0.91-1.03 on the
/// rest of the caustic set, the default scene's 16 iterations unchanged
/// (docs/integrators.md, "The gather boost").
const PROG_GATHER_BOOST: f32 = 4.0;
const PROG_SPECULAR_SPLITS: u32 = 4;

impl Default for PhotonSettings {
    /// The progressive mode's defaults.
    fn default() -> Self {
        PhotonSettings {
            global_photons: PROG_GLOBAL,
            caustic_photons: PROG_CAUSTIC,
            gather_rays: PROG_GATHER_RAYS,
            gather_gain: PROG_GATHER_GAIN,
            gather_boost: PROG_GATHER_BOOST,
            specular_splits: PROG_SPECULAR_SPLITS,
            connect_caustics: true,
            progressive: Some(Progressive::default()),
            ..PhotonSettings::single_map()
        }
    }
}

impl PhotonSettings {
    /// The single map's defaults (`progressive false`, the baseline; the
    /// defaults of every render before the progressive mode).
    pub fn single_map() -> PhotonSettings {
        PhotonSettings {
            global_photons: 200_000,
            caustic_photons: 1_000_000,
            nearest: 50,
            gather_rays: 16,
            gather_gain: 1.0,
            gather_boost: 1.0,
            specular_splits: 0,
            max_radius: 0.0,
            caustics: CausticMode::Mis,
            heuristic: Heuristic::Balance,
            alpha: AlphaMode::Footprint,
            max_depth: 8,
            kernel: Kernel::None,
            radiance_photons: true,
            aim_caustics: false,
            connect_caustics: false,
            progressive: None,
        }
    }
}

const fn spec(
    ty: &'static str,
    name: &'static str,
    words: &'static str,
    value: &'static str,
    help: &'static str,
) -> ParamSpec {
    ParamSpec {
        ty,
        name,
        words,
        value,
        help,
    }
}

/// The parameters of `Integrator "photon"` (besides `maxdepth`), declared
/// once: `load/photon.rs` reads them, front ends offer them.
pub const PARAMS: &[ParamSpec] = &[
    spec("integer", "photons", "photons", "N", "photons emitted for the global map"),
    spec("integer", "causticphotons", "caustic-photons", "N", "photons emitted for the caustic map"),
    spec("integer", "nearest", "nearest", "M1", "nearest photons per estimate (m_1)"),
    spec("integer", "gatherrays", "gather-rays", "M2", "final-gather rays per shading point (m_2)"),
    spec("integer", "specularsplits", "specular-splits", "K", "camera paths follow both the reflection and the refraction (each weighted by Fresnel) at the first K smooth dielectric interfaces they meet, instead of choosing one"),
    spec("float", "maxradius", "max-radius", "R", "largest photon search radius in scene units (0: 2% of the scene radius)"),
    spec("string", "caustics", "caustics", "mis|photons|gather", "caustics from `mis` (the seed's weights), `photons` only or `gather` rays only"),
    spec("string", "heuristic", "heuristic", "balance|power", "MIS heuristic for the caustic weights"),
    spec("string", "alpha", "alpha", "footprint|spp|1", "alpha in q_1 at the first camera hit: `footprint` (the default, also `auto`: samples per pixel discounted by the photon neighbourhoods a pixel reads), `spp` (the seed's: samples per pixel) or `1`"),
    spec("float", "gathergain", "gather-gain", "G", "caustics: alpha of q_1 at the first camera hit times G, trusting the gather rays G times more than their density says (with Sobol samples they can be: a large light seen through glass, 3; docs/integrators.md); 1: the seed's weights"),
    spec("float", "gatherboost", "gather-boost", "B", "progressive: up to B times the gather rays at a camera hit, in proportion to the share of the irradiance there that the gather rays carry of the caustics (measured on the first iteration's maps); 1: the same count everywhere"),
    spec("string", "kernel", "kernel", "none|cone", "caustic density-estimation kernel"),
    spec("bool", "radiancephotons", "radiance-photons", "true|false", "read the global map through precomputed radiance photons"),
    spec("bool", "aimcaustics", "aim-caustics", "true|false", "emit caustic photons only towards perfectly specular shapes"),
    spec("bool", "connectcaustics", "connect-caustics", "true|false", "progressive: caustics the camera sees directly are also estimated by connecting each caustic photon to the camera (the light tracer's strategy), weighed with the caustic map and the gather rays by the balance heuristic over the three"),
    spec("bool", "progressive", "progressive", "true|false", "render in iterations (the default), each tracing fresh photons (`photons` and `causticphotons` per iteration) with radii that shrink from one to the next; `false`: one photon map for the whole render"),
    spec("integer", "iterationspp", "iteration-spp", "S", "progressive: samples per pixel rendered with each iteration's maps"),
    spec("float", "shrink", "shrink", "A", "progressive: radius sequence r_{i+1}^2 = r_i^2 (i + A) / (i + 1), 0 < A <= 1"),
    spec("float", "initialradius", "initial-radius", "R", "progressive: caustic radius of the first iteration (0: the median k-NN radius of the first iteration's caustic photons)"),
    spec("integer", "iterations", "iterations", "N", "progressive: iterations to render (samples per pixel = N x iterationspp; 0: from the sample count)"),
    spec("float", "photonshare", "photon-share", "F", "progressive with a time budget: share of each iteration's time spent tracing photons, which sets the photon counts when they are not given, the global map then getting a fifth of its count (0: keep the counts)"),
];

/// Bytes per stored photon plus kd-tree overhead, and per global photon the
/// normal kept for radiance photons; used for the memory estimate.
pub const BYTES_PER_PHOTON_ESTIMATE: u64 = 24 + 16 + 12;

/// Estimated peak memory of the photon maps, in bytes (an upper bound: every
/// emitted photon stored up to `max_depth` times for the global map).
pub fn memory_estimate(s: &PhotonSettings) -> u64 {
    let global = s
        .global_photons
        .saturating_mul(s.max_depth.clamp(1, 4) as u64);
    (global.saturating_add(s.caustic_photons)).saturating_mul(BYTES_PER_PHOTON_ESTIMATE)
}

/// Memory available to this process, from /proc/meminfo (None if unknown).
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Refuses photon budgets that would not fit in memory, naming the parameter.
pub fn check_memory(s: &PhotonSettings) -> Result<(), String> {
    let need = memory_estimate(s);
    if let Some(avail) = available_memory() {
        if need > avail / 10 * 8 {
            let which = if s.caustic_photons > s.global_photons {
                "causticphotons"
            } else {
                "photons"
            };
            return Err(format!(
                "the photon maps would need about {:.1} GiB but only {:.1} GiB of memory is available; lower `{which}`",
                need as f64 / (1u64 << 30) as f64,
                avail as f64 / (1u64 << 30) as f64
            ));
        }
    }
    Ok(())
}
