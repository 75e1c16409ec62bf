//! The `photon` integrator's orchestration: the photon pass before the first
//! camera pass (inside the time budget; a resumed render rebuilds the same
//! maps from the seed, since photon tracing is deterministic), and `alpha`,
//! the samples per pixel of the seed's `q_1`, known up front or, with only a
//! time budget, predicted after each pass from the passes so far.

use super::gather::{self, PhotonCtx};
use super::{PhotonMaps, PhotonSettings, PhotonStats};
use crate::geometry::Ray;
use crate::integrator::driver::{PassReport, Start};
use crate::integrator::RayCounts;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler};
use std::sync::atomic::AtomicBool;

pub struct PhotonRun<'a> {
    scene: &'a Scene,
    settings: &'a PhotonSettings,
    seed: u64,
    pixel_spread: f32,
    maps: Option<PhotonMaps>,
    /// `alpha` at the first camera hit for the next pass (seed, A.10).
    alpha: f32,
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
            .and_then(|b| b.try_into().ok())
            .map_or(fresh, |b: [u8; 4]| f32::from_bits(u32::from_le_bytes(b)));
        PhotonRun {
            scene,
            settings,
            seed: start.seed,
            pixel_spread: start.pixel_spread,
            maps: None,
            alpha,
        }
    }

    /// Builds the maps before the first pass; `false` if interrupted.
    pub fn before_pass(&mut self, cancel: &AtomicBool) -> bool {
        if self.maps.is_none() {
            self.maps = PhotonMaps::build(self.scene, self.settings, self.seed, cancel);
        }
        self.maps.is_some()
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
    /// from the time per sample so far.
    pub fn after_pass(&mut self, r: &PassReport) {
        if let (Some(t), false, 0) = (r.time_limit, r.stopping, r.spp_target) {
            let per_sample = r.pass_time_sum.as_secs_f64() / r.samples_here as f64;
            let left = (t.saturating_sub(r.elapsed)).as_secs_f64();
            self.alpha =
                (r.spp_done as f64 + (left / per_sample.max(1e-9)).floor()).max(1.0) as f32;
        }
    }

    /// The state a resumed render needs: `alpha` (4 bytes).
    pub fn save(&self) -> Vec<u8> {
        self.alpha.to_bits().to_le_bytes().to_vec()
    }

    pub fn stats(&self) -> Option<PhotonStats> {
        self.maps.as_ref().map(|m| m.stats.clone())
    }
}
