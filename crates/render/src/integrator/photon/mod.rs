//! The `photon` integrator: photon mapping with final gathering, where the
//! caustic part is estimated twice (caustic photon map and final-gather rays)
//! and combined per sample with the seed's weights (`../shared/METHOD.md`).
//!
//! Orchestration is in `run.rs` (the photon pass before the camera passes,
//! `alpha` between them) and [`PhotonMaps::build`]; per-path tracing in
//! `trace.rs` (photons) and `gather.rs` (camera paths); settings here;
//! weights in `weights.rs`; the progressive mode's iteration schedule and
//! shrinking radius in `progressive.rs`.

pub mod aim;
pub mod budget;
pub mod gather;
pub mod map;
pub mod photon;
pub mod progressive;
pub mod radiance;
pub mod radius_field;
pub mod run;
pub mod trace;
pub mod weights;

use crate::scene::Scene;
use lumis_math::Vec3;
use lumis_scene::ParamSpec;
use map::PhotonMap;
pub use progressive::Progressive;
use radiance::RadiancePhotons;
use radius_field::RadiusField;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::{Duration, Instant};
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
    /// Render in iterations, each with fresh maps and shrinking radii (the
    /// default; `None`: one pair of maps for the whole render, the
    /// single-map baseline).
    pub progressive: Option<Progressive>,
}

impl Default for PhotonSettings {
    fn default() -> Self {
        PhotonSettings {
            global_photons: 200_000,
            caustic_photons: 1_000_000,
            nearest: 50,
            gather_rays: 16,
            max_radius: 0.0,
            caustics: CausticMode::Mis,
            heuristic: Heuristic::Balance,
            alpha: AlphaMode::Footprint,
            max_depth: 8,
            kernel: Kernel::None,
            radiance_photons: true,
            aim_caustics: false,
            progressive: Some(Progressive::default()),
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
    spec("float", "maxradius", "max-radius", "R", "largest photon search radius in scene units (0: 2% of the scene radius)"),
    spec("string", "caustics", "caustics", "mis|photons|gather", "caustics from `mis` (the seed's weights), `photons` only or `gather` rays only"),
    spec("string", "heuristic", "heuristic", "balance|power", "MIS heuristic for the caustic weights"),
    spec("string", "alpha", "alpha", "footprint|spp|1", "alpha in q_1 at the first camera hit: `footprint` (the default, also `auto`: samples per pixel discounted by the photon neighbourhoods a pixel reads), `spp` (the seed's: samples per pixel) or `1`"),
    spec("string", "kernel", "kernel", "none|cone", "caustic density-estimation kernel"),
    spec("bool", "radiancephotons", "radiance-photons", "true|false", "read the global map through precomputed radiance photons"),
    spec("bool", "aimcaustics", "aim-caustics", "true|false", "emit caustic photons only towards perfectly specular shapes"),
    spec("bool", "progressive", "progressive", "true|false", "render in iterations (the default), each tracing fresh photons (`photons` and `causticphotons` per iteration) with radii that shrink from one to the next; `false`: one photon map for the whole render"),
    spec("integer", "iterationspp", "iteration-spp", "S", "progressive: samples per pixel rendered with each iteration's maps"),
    spec("float", "shrink", "shrink", "A", "progressive: radius sequence r_{i+1}^2 = r_i^2 (i + A) / (i + 1), 0 < A <= 1"),
    spec("float", "initialradius", "initial-radius", "R", "progressive: caustic radius of the first iteration (0: the median k-NN radius of the first iteration's caustic photons)"),
    spec("integer", "iterations", "iterations", "N", "progressive: iterations to render (samples per pixel = N x iterationspp; 0: from the sample count)"),
    spec("float", "photonshare", "photon-share", "F", "progressive with a time budget: share of each iteration's time spent tracing photons, which sets the photon counts when they are not given (0: keep the counts)"),
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

/// Timing and counts of the photon passes, for the summary and benchmarks.
#[derive(Clone, Debug, Default)]
pub struct PhotonStats {
    pub global_stored: usize,
    pub caustic_stored: usize,
    pub trace_time: Duration,
    pub build_time: Duration,
    pub radiance_time: Duration,
    pub memory_bytes: usize,
    /// Progressive iterations begun (0 without the progressive mode); the
    /// counts and times are then sums over them and the memory their peak.
    pub iterations: u32,
    /// Progressive: the caustic radius of the latest iteration.
    pub caustic_radius: f32,
    /// Progressive: photons emitted per iteration (global, caustic).
    pub iteration_photons: (u64, u64),
    /// Progressive: iterations of the whole render (over all runs of a
    /// resumed one) begun so far; `iterations` counts this run's photon
    /// passes.
    pub render_iterations: u64,
}

impl PhotonStats {
    /// Adds one progressive iteration's photon pass: counts and times
    /// summed, memory the peak, the radius the latest.
    pub fn add_iteration(&mut self, st: &PhotonStats) {
        self.global_stored += st.global_stored;
        self.caustic_stored += st.caustic_stored;
        self.trace_time += st.trace_time;
        self.build_time += st.build_time;
        self.radiance_time += st.radiance_time;
        self.memory_bytes = self.memory_bytes.max(st.memory_bytes);
        self.iterations += 1;
        self.caustic_radius = st.caustic_radius;
    }
}

/// Everything the camera pass needs from the photon pass.
pub struct PhotonMaps {
    pub global: PhotonMap,
    pub caustic: PhotonMap,
    pub radiance: Option<RadiancePhotons>,
    /// Total emitted power `Phi` (luminance) of all lights.
    pub phi: f32,
    pub max_radius: f32,
    /// Set when caustic photons were aimed: q_1 then uses per-photon fluxes.
    pub targets: Option<aim::Targets>,
    /// The fixed radii of the caustic and global estimates (progressive
    /// iterations); `None`: the `nearest` photons within a largest radius.
    pub radii: Option<Radii>,
    pub stats: PhotonStats,
}

/// The query radii of one progressive iteration: each point's `r_0`
/// scaled by the iteration's `scale2` (fixed before the iteration).
#[derive(Clone, Debug)]
pub struct Radii {
    pub caustic: Arc<RadiusField>,
    pub global: Arc<RadiusField>,
    pub scale2: f32,
    /// Where the global estimate is precomputed (radiance photons).
    pub global_points: Arc<radiance::Points>,
}

impl Radii {
    /// Squared radius of the caustic estimate at `p`.
    #[inline]
    pub fn caustic_r2(&self, p: Vec3) -> f32 {
        self.caustic.r2_at(p) * self.scale2
    }

    /// Squared radius of the global estimate at `p`.
    #[inline]
    pub fn global_r2(&self, p: Vec3) -> f32 {
        self.global.r2_at(p) * self.scale2
    }

    /// The largest global radius of this iteration.
    pub fn global_max(&self) -> f32 {
        self.global.max_radius() * self.scale2.sqrt()
    }
}

/// One global photon in this many becomes a radiance photon.
pub const RADIANCE_STRIDE: usize = 4;

/// The global map's largest radius relative to the caustic map's.
pub const GLOBAL_RADIUS_SCALE: f32 = 5.0;

impl PhotonMaps {
    /// Traces and builds the maps, radiance photons from the `nearest`
    /// photons; gives up (`None`) soon after `cancel` is set, so an
    /// interrupt during a long photon pass ends the render at once.
    pub fn build(
        scene: &Scene,
        s: &PhotonSettings,
        seed: u64,
        cancel: &AtomicBool,
    ) -> Option<PhotonMaps> {
        let (mut maps, normals) = Self::trace(scene, s, seed, cancel)?;
        maps.finish(s, &normals, None);
        Some(maps)
    }

    /// Traces the photons and builds the maps' trees; [`PhotonMaps::finish`]
    /// then builds the radiance photons (`normals`: the global photons'
    /// surface normals).
    pub fn trace(
        scene: &Scene,
        s: &PhotonSettings,
        seed: u64,
        cancel: &AtomicBool,
    ) -> Option<(PhotonMaps, Vec<Vec3>)> {
        let phi: f32 = scene
            .lights
            .iter()
            .map(|l| l.power(&scene.shapes).luminance())
            .sum();
        let max_radius = if s.max_radius > 0.0 {
            s.max_radius
        } else {
            0.02 * scene.bounds.bounding_sphere().1.max(1e-6)
        };
        let t0 = Instant::now();
        let g = trace::trace_photons(
            scene,
            s.global_photons,
            trace::MapKind::Global,
            seed,
            s.max_depth,
            None,
            cancel,
        )?;
        let targets =
            Some(aim::Targets::from_scene(scene)).filter(|t| s.aim_caustics && !t.is_empty());
        let c = trace::trace_photons(
            scene,
            s.caustic_photons,
            trace::MapKind::Caustic,
            seed ^ 0x5eed,
            s.max_depth,
            targets.as_ref(),
            cancel,
        )?;
        let trace_time = t0.elapsed();
        let t1 = Instant::now();
        let global = PhotonMap::build(g.photons, s.global_photons);
        let caustic = PhotonMap::build(c.photons, s.caustic_photons);
        let stats = PhotonStats {
            global_stored: global.len(),
            caustic_stored: caustic.len(),
            trace_time,
            build_time: t1.elapsed(),
            ..PhotonStats::default()
        };
        let maps = PhotonMaps {
            global,
            caustic,
            radiance: None,
            phi,
            max_radius,
            targets,
            radii: None,
            stats,
        };
        Some((maps, g.normals))
    }

    /// Sets the query radii (`None`: nearest photons) and builds the
    /// radiance photons accordingly, if the settings ask for them.
    pub fn finish(&mut self, s: &PhotonSettings, normals: &[Vec3], radii: Option<Radii>) {
        let t2 = Instant::now();
        self.radiance = match &radii {
            _ if !s.radiance_photons || self.global.is_empty() => None,
            Some(r) => Some(RadiancePhotons::fixed(
                &self.global,
                r.global_points.clone(),
                r,
            )),
            None => Some(RadiancePhotons::build(
                &self.global,
                normals,
                RADIANCE_STRIDE,
                s.nearest,
                self.max_radius * 2.0,
            )),
        };
        let st = &mut self.stats;
        st.radiance_time = t2.elapsed();
        st.memory_bytes = self.global.memory_bytes()
            + self.caustic.memory_bytes()
            + self.radiance.as_ref().map_or(0, |r| r.memory_bytes());
        st.caustic_radius = radii
            .as_ref()
            .map_or(0.0, |r| (r.caustic.median_r2() * r.scale2).sqrt());
        self.radii = radii;
    }
}
