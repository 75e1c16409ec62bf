//! The `photon` integrator's orchestration: the photon pass before the first
//! camera pass (inside the time budget; a resumed render rebuilds the same
//! maps from the seed, since photon tracing is deterministic), and `alpha`,
//! the samples per pixel of the seed's `q_1`, known up front or, with only a
//! time budget, predicted after each pass from the passes so far.
//!
//! In the progressive mode (`progressive.rs`) a photon pass starts every
//! iteration: the previous maps are freed first, so memory stays at one
//! iteration's maps, and `alpha` is the iteration's samples per pixel.

use super::aim::Aims;
use super::budget::choose_counts;
use super::camera;
use super::connect;
use super::gather::PhotonCtx;
use super::progressive::{iteration_seed, stop_at_power_of_two, IterState};
use super::radius_field::RadiusFields;
use super::weights::CausticMode;
use super::{PhotonMaps, PhotonSettings, PhotonStats, Radii};
use crate::geometry::Ray;
use crate::integrator::driver::{PassReport, Start};
use crate::integrator::RayCounts;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler, SamplerKind, Vec2};
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

pub struct PhotonRun<'a> {
    scene: &'a Scene,
    settings: &'a PhotonSettings,
    start: Start,
    maps: Option<PhotonMaps>,
    /// `alpha` at the first camera hit for the next pass (seed, A.10).
    alpha: f32,
    /// The progressive mode's iteration (`None` without it).
    iter: Option<IterState>,
    /// Progressive: the photon passes' figures summed over iterations.
    totals: PhotonStats,
    /// Progressive: the latest photon pass's duration.
    photon_time: Duration,
    /// Progressive: every point's initial radii (from iteration 0).
    fields: Option<RadiusFields>,
    /// What the caustic photons of every pass aim at and are skipped by.
    aims: Aims,
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
                .unwrap_or_default()
        });
        PhotonRun {
            scene,
            settings,
            start: *start,
            maps: None,
            alpha,
            iter,
            totals: PhotonStats::default(),
            photon_time: Duration::ZERO,
            fields: None,
            aims: Aims::new(scene, settings.aim_caustics),
        }
    }

    /// Builds the maps before the first pass (progressive: before each
    /// iteration); `false` if interrupted.
    pub fn before_pass(&mut self, cancel: &AtomicBool) -> bool {
        if self.iter.is_some() {
            return self.begin_iteration(cancel);
        }
        if self.maps.is_none() {
            let (scene, s, seed) = (self.scene, self.settings, self.start.seed);
            self.maps = PhotonMaps::build(scene, s, seed, None, &self.aims, cancel);
        }
        self.maps.is_some()
    }

    /// `S`, the samples per pixel of one iteration.
    fn iteration_spp(&self) -> u32 {
        self.settings
            .progressive
            .map_or(1, |p| p.iteration_spp.max(1))
    }

    /// Progressive: moves on to the next iteration when this one has had its
    /// samples, and builds the iteration's maps if they are not there.
    fn begin_iteration(&mut self, cancel: &AtomicBool) -> bool {
        let p = self.settings.progressive.expect("progressive settings");
        let s_iter = self.iteration_spp();
        let mut it = self.iter.expect("progressive state");
        if it.next_if_done(s_iter, p.shrink as f64) {
            self.maps = None;
        }
        if self.maps.is_some() {
            return true;
        }
        let t0 = Instant::now();
        if it.global_photons == 0 && it.caustic_photons == 0 {
            let Some(c) = self.photon_counts(cancel) else {
                return false;
            };
            it.choose_counts(c);
        }
        let mut s = self.settings.clone();
        (s.global_photons, s.caustic_photons) = (it.global_photons, it.caustic_photons);
        let connect = self.connect();
        let trace = |i, connect| {
            let seed = iteration_seed(self.start.seed, i);
            PhotonMaps::trace(self.scene, &s, seed, connect, &self.aims, cancel)
        };
        let Some((mut maps, normals)) = trace(it.index, connect) else {
            return false;
        };
        if self.fields.is_none() {
            // The radii come from iteration 0's photons (traced again when
            // a checkpoint resumes a later iteration).
            let fields = match it.index {
                0 => RadiusFields::new(&maps, &normals, &s, &p),
                _ => match trace(0, None) {
                    Some((first, n)) => RadiusFields::new(&first, &n, &s, &p),
                    None => return false,
                },
            };
            self.fields = Some(fields);
        }
        let f = self.fields.as_ref().expect("radius fields");
        let radii = Radii {
            caustic: f.caustic.clone(),
            global: f.global.clone(),
            scale2: it.scale2 as f32,
            global_points: f.global_points.clone(),
        };
        maps.finish(&s, &normals, Some(radii));
        // The samples per pixel that will read these maps.
        self.alpha = match self.start.spp {
            0 => s_iter,
            t => s_iter.min(t.saturating_sub(it.start_spp)).max(1),
        } as f32;
        if let Some(margin) = self.connect() {
            let splats = connect::weigh(&self.ctx(&maps), &maps.connections, margin);
            maps.splats = splats;
            maps.connections = Vec::new();
        }
        self.totals.add_iteration(&maps.stats);
        self.totals.iteration_photons = (it.global_photons, it.caustic_photons);
        self.totals.render_iterations = it.index + 1;
        self.totals.counts_chosen = self.time_rule();
        self.maps = Some(maps);
        self.iter = Some(it);
        self.photon_time = t0.elapsed();
        true
    }

    /// The film margin for caustic photons connected to the camera, if
    /// they are: only in the progressive mode with the seed's weights (the
    /// connections' weights need the iteration's radii), and not in scenes
    /// with media (the connection would need the transmittance to the lens).
    fn connect(&self) -> Option<Vec2> {
        let s = self.settings;
        let on = s.connect_caustics
            && s.progressive.is_some()
            && s.caustics == CausticMode::Mis
            && !self.scene.has_media();
        on.then_some(self.start.filter_radius)
    }

    /// The caustic photons' camera connections of the current maps.
    pub fn pass_splats(&self) -> &[(Vec2, Rgb)] {
        self.maps.as_ref().map_or(&[], |m| m.splats.as_slice())
    }

    /// Whether the time rule chooses the photon counts: under a time
    /// budget, when the settings leave them open.
    fn time_rule(&self) -> bool {
        let share = self.settings.progressive.map_or(0.0, |p| p.photon_share);
        self.start.time_limit.is_some() && share > 0.0
    }

    /// Photon counts per iteration: the settings', or the time rule's
    /// (`budget.rs`).
    fn photon_counts(&self, cancel: &AtomicBool) -> Option<(u64, u64)> {
        let s = self.settings;
        if !self.time_rule() {
            return Some((s.global_photons, s.caustic_photons));
        }
        let st = &self.start;
        let share = s.progressive.map_or(0.0, |p| p.photon_share) as f64;
        let spp = self.iteration_spp();
        choose_counts(self.scene, s, share, spp, st, &self.aims, cancel)
    }

    #[inline]
    pub fn li(&self, ray: Ray, sampler: &mut Sampler, rays: &mut RayCounts) -> Rgb {
        let maps = self
            .maps
            .as_ref()
            .expect("photon maps are built before a pass");
        camera::li(&self.ctx(maps), ray, sampler, rays)
    }

    fn ctx<'m>(&'m self, maps: &'m PhotonMaps) -> PhotonCtx<'m> {
        PhotonCtx {
            scene: self.scene,
            maps,
            s: self.settings,
            alpha_first: self.alpha,
            pixel_spread: self.start.pixel_spread,
            connect: self.connect(),
        }
    }

    /// The time the render's next indivisible step would take after the
    /// pass `r` reports, for the driver's time budget: one pass, or in the
    /// progressive mode, at an iteration's end, the next whole iteration
    /// (its photon pass and its passes); `None` inside an iteration, which
    /// a time budget never cuts.
    pub fn next_cost(&self, r: &PassReport, pass_time: Duration) -> Option<Duration> {
        let Some(it) = &self.iter else {
            return Some(pass_time);
        };
        let s = self.iteration_spp();
        if r.spp_done < it.start_spp.saturating_add(s) {
            return None;
        }
        let per_pass = r.pass_time_sum / r.passes_here.max(1);
        let cost = self.photon_time + per_pass * s;
        if let (Some(t), 0, SamplerKind::Sobol) = (r.time_limit, r.spp_target, self.start.sampler) {
            let left = t.saturating_sub(r.elapsed).as_secs_f64();
            let more = (left / cost.as_secs_f64().max(1e-9)).floor() as u64;
            if stop_at_power_of_two(it.index + 1, it.index + 1 + more) {
                // More than the time left: the driver stops here.
                return Some(t);
            }
        }
        Some(cost)
    }

    /// With only a time budget, predicts the render's samples per pixel
    /// from the time per sample so far. Progressive: frees the maps of a
    /// finished iteration.
    pub fn after_pass(&mut self, r: &PassReport) {
        if let Some(it) = self.iter.as_mut() {
            it.spp_done = r.spp_done;
            let s = self
                .settings
                .progressive
                .map_or(1, |p| p.iteration_spp.max(1));
            if it.spp_done >= it.start_spp.saturating_add(s) {
                self.maps = None;
            }
            return;
        }
        if let (Some(t), false, 0) = (r.time_limit, r.stopping, r.spp_target) {
            let per_sample = r.pass_time_sum.as_secs_f64() / r.samples_here as f64;
            let left = (t.saturating_sub(r.elapsed)).as_secs_f64();
            self.alpha =
                (r.spp_done as f64 + (left / per_sample.max(1e-9)).floor()).max(1.0) as f32;
        }
    }

    /// [`Self::save`]'s output after `spp` samples per pixel of a render
    /// without a time budget (what a partial render starting there needs):
    /// single map, `alpha` is the sample count, as a fresh run sets it;
    /// progressive, the iteration replayed from the pass boundaries.
    pub fn state_at(settings: &PhotonSettings, start: &Start, spp: u32) -> Vec<u8> {
        let Some(p) = settings.progressive else {
            return Vec::new();
        };
        let counts = (settings.global_photons, settings.caustic_photons);
        let s_iter = p.iteration_spp.max(1);
        let it = IterState::replay(
            spp,
            start.spp_per_pass,
            start.spp,
            s_iter,
            p.shrink as f64,
            counts,
        );
        // `alpha` is set again when the iteration's maps are built.
        let mut b = 1f32.to_bits().to_le_bytes().to_vec();
        it.encode(&mut b);
        b
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
