//! The `photon` integrator's orchestration: the photon pass before the first
//! camera pass (inside the time budget; a resumed render rebuilds the same
//! maps from the seed, since photon tracing is deterministic), and `alpha`,
//! the samples per pixel of the seed's `q_1`, known up front or, with only a
//! time budget, predicted after each pass from the passes so far.
//!
//! In the progressive mode (`progressive.rs`) a photon pass starts every
//! iteration: the previous maps are freed first, so memory stays at one
//! iteration's maps, and `alpha` is the iteration's samples per pixel.

use super::gather::{self, PhotonCtx};
use super::progressive::{initial_radius2, iteration_seed, next_radius2, IterState};
use super::{PhotonMaps, PhotonSettings, PhotonStats};
use crate::geometry::Ray;
use crate::integrator::driver::{PassReport, Start};
use crate::integrator::RayCounts;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler};
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

pub struct PhotonRun<'a> {
    scene: &'a Scene,
    settings: &'a PhotonSettings,
    seed: u64,
    pixel_spread: f32,
    /// Samples per pixel aimed at (0: until the time budget ends).
    spp_target: u32,
    maps: Option<PhotonMaps>,
    /// `alpha` at the first camera hit for the next pass (seed, A.10).
    alpha: f32,
    /// The progressive mode's iteration (`None` without it).
    iter: Option<IterState>,
    /// Under a time budget: the current iteration runs to the end, since a
    /// fresh photon pass would not fit in the time left.
    last: bool,
    /// Progressive: the photon passes' figures summed over iterations.
    totals: PhotonStats,
    /// Progressive: the latest photon pass's duration.
    photon_time: Duration,
}

impl<'a> PhotonRun<'a> {
    /// `saved` is [`PhotonRun::save`]'s output from an earlier run.
    pub fn new(
        scene: &'a Scene,
        settings: &'a PhotonSettings,
        start: &Start,
        saved: Option<&[u8]>,
    ) -> PhotonRun<'a> {
        let fresh = if start.spp > 0 { start.spp as f32 } else { 1.0 };
        let alpha = saved
            .and_then(|b| b.get(..4)?.try_into().ok())
            .map_or(fresh, |b: [u8; 4]| f32::from_bits(u32::from_le_bytes(b)));
        let iter = settings.progressive.map(|_| {
            saved
                .and_then(|b| IterState::decode(b.get(4..)?))
                .unwrap_or(IterState {
                    index: 0,
                    start_spp: 0,
                    spp_done: 0,
                    r2: 0.0,
                })
        });
        PhotonRun {
            scene,
            settings,
            seed: start.seed,
            pixel_spread: start.pixel_spread,
            spp_target: start.spp,
            maps: None,
            alpha,
            iter,
            last: false,
            totals: PhotonStats::default(),
            photon_time: Duration::ZERO,
        }
    }

    /// Builds the maps before the first pass (progressive: before each
    /// iteration); `false` if interrupted.
    pub fn before_pass(&mut self, cancel: &AtomicBool) -> bool {
        if self.iter.is_some() {
            return self.begin_iteration(cancel);
        }
        if self.maps.is_none() {
            self.maps = PhotonMaps::build(self.scene, self.settings, self.seed, cancel);
        }
        self.maps.is_some()
    }

    /// Progressive: moves on to the next iteration when this one has had its
    /// samples, and builds the iteration's maps if they are not there.
    fn begin_iteration(&mut self, cancel: &AtomicBool) -> bool {
        let p = self.settings.progressive.expect("progressive settings");
        let it = self.iter.as_mut().expect("progressive state");
        if !self.last && it.spp_done >= it.start_spp.saturating_add(p.iteration_spp.max(1)) {
            self.maps = None;
            it.r2 = next_radius2(it.r2, it.index, p.shrink as f64);
            it.index += 1;
            it.start_spp = it.spp_done;
        }
        if self.maps.is_some() {
            return true;
        }
        let t0 = Instant::now();
        let seed = iteration_seed(self.seed, it.index);
        let Some(mut maps) = PhotonMaps::build(self.scene, self.settings, seed, cancel) else {
            return false;
        };
        if it.r2 <= 0.0 {
            it.r2 = if p.initial_radius > 0.0 {
                (p.initial_radius as f64).powi(2)
            } else {
                initial_radius2(&maps.caustic, self.settings.nearest, maps.max_radius)
            };
        }
        maps.caustic_radius = Some(it.r2.sqrt() as f32);
        // The samples per pixel that will read these maps.
        let s = p.iteration_spp.max(1);
        self.alpha = match self.spp_target {
            0 => s,
            t => s.min(t.saturating_sub(it.start_spp)).max(1),
        } as f32;
        let st = &maps.stats;
        let tot = &mut self.totals;
        tot.global_stored += st.global_stored;
        tot.caustic_stored += st.caustic_stored;
        tot.trace_time += st.trace_time;
        tot.build_time += st.build_time;
        tot.radiance_time += st.radiance_time;
        tot.memory_bytes = tot.memory_bytes.max(st.memory_bytes);
        tot.iterations += 1;
        tot.caustic_radius = it.r2.sqrt() as f32;
        self.maps = Some(maps);
        self.photon_time = t0.elapsed();
        true
    }

    #[inline]
    pub fn li(&self, ray: Ray, sampler: &mut Sampler, rays: &mut RayCounts) -> Rgb {
        let maps = self
            .maps
            .as_ref()
            .expect("photon maps are built before a pass");
        let ctx = PhotonCtx {
            scene: self.scene,
            maps,
            s: self.settings,
            alpha_first: self.alpha,
            pixel_spread: self.pixel_spread,
        };
        gather::li(&ctx, ray, sampler, rays)
    }

    /// With only a time budget, predicts the render's samples per pixel
    /// from the time per sample so far. Progressive: frees the maps of a
    /// finished iteration, unless under a time budget the next photon pass
    /// and a camera pass would not fit in the time left; then the current
    /// maps serve the passes to the end.
    pub fn after_pass(&mut self, r: &PassReport) {
        if let Some(it) = self.iter.as_mut() {
            it.spp_done = r.spp_done;
            let s = self
                .settings
                .progressive
                .map_or(1, |p| p.iteration_spp.max(1));
            if self.last || r.stopping || it.spp_done < it.start_spp.saturating_add(s) {
                return;
            }
            if let Some(t) = r.time_limit {
                let per_pass = r.pass_time_sum / r.passes_here;
                if r.elapsed + self.photon_time + per_pass > t {
                    self.last = true;
                    return;
                }
            }
            self.maps = None;
            return;
        }
        if let (Some(t), false, 0) = (r.time_limit, r.stopping, r.spp_target) {
            let per_sample = r.pass_time_sum.as_secs_f64() / r.samples_here as f64;
            let left = (t.saturating_sub(r.elapsed)).as_secs_f64();
            self.alpha =
                (r.spp_done as f64 + (left / per_sample.max(1e-9)).floor()).max(1.0) as f32;
        }
    }

    /// The state a resumed render needs: `alpha` (4 bytes), then in the
    /// progressive mode the iteration ([`IterState`]).
    pub fn save(&self) -> Vec<u8> {
        let mut b = self.alpha.to_bits().to_le_bytes().to_vec();
        if let Some(it) = &self.iter {
            it.encode(&mut b);
        }
        b
    }

    pub fn stats(&self) -> Option<PhotonStats> {
        if self.iter.is_some() {
            return (self.totals.iterations > 0).then(|| self.totals.clone());
        }
        self.maps.as_ref().map(|m| m.stats.clone())
    }
}
