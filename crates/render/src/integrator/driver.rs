//! The render driver: passes of samples over the film for any integrator.
//!
//! Each pass adds `spp_per_pass` samples to every pixel; a pixel's samples
//! are always added in index order by one thread, every sample's random
//! numbers depend only on (seed, pixel, index), and splats to other pixels
//! are applied after the pass in row order, so the image is bit-identical
//! whatever the thread count. The driver owns sample indexing, camera rays,
//! clamping, bad-sample accounting, the time budget, cancellation and the
//! progress and per-pass hooks; what an integrator does between passes and
//! per sample is behind [`Pass`] (see `run.rs`).

use super::run::Run;
use super::{Integrator, RayCounts};
use crate::film::{Film, Filter, PixelBounds};
use crate::geometry::Ray;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler, SamplerKind, Vec2};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

#[derive(Clone, Debug)]
pub struct RenderSettings {
    /// Samples per pixel; with a time limit, the most to take (0 = unbounded).
    pub spp: u32,
    pub seed: u64,
    /// Worker threads (0 = all cores).
    pub threads: usize,
    /// Stop after the last whole pass that fits in this wall-clock budget.
    pub time_limit: Option<Duration>,
    pub sampler: SamplerKind,
    pub filter: Filter,
    pub crop: PixelBounds,
    pub spp_per_pass: u32,
    /// If set, each sample is scaled down so its largest component is at most
    /// this (pbrt's `maxcomponentvalue`): biased, off by default.
    pub clamp: Option<f32>,
    /// Test hook: the sample at (x, y, index) becomes NaN, to prove bad
    /// samples are dropped and reported (`None` outside tests).
    pub inject_nan: Option<(u32, u32, u32)>,
    /// A partial render: only these passes of the render `spp` describes
    /// (see [`RenderSettings::pass_count`]). The film starts empty and the
    /// integrator in its state at the first of them, so the parts' films
    /// merge ([`Film::merge`]) to the bits of the whole render. `None`: all.
    pub passes: Option<std::ops::Range<u32>>,
}

impl RenderSettings {
    /// The passes of the whole render (`None` without a sample count: a
    /// time budget alone sets no pass count).
    pub fn pass_count(&self) -> Option<u32> {
        (self.spp > 0).then(|| self.spp.div_ceil(self.spp_per_pass.max(1)))
    }

    /// Samples per pixel before pass `pass` (all passes but the last are whole).
    pub fn spp_before(&self, pass: u32) -> u32 {
        let n = pass.saturating_mul(self.spp_per_pass.max(1));
        match self.spp {
            0 => n,
            t => n.min(t),
        }
    }

    /// Refuses a pass range the render does not have.
    pub fn check_passes(&self) -> Result<(), String> {
        let Some(r) = &self.passes else {
            return Ok(());
        };
        let Some(total) = self.pass_count() else {
            return Err(
                "a partial render (a pass range) needs a sample count, not a time budget alone"
                    .into(),
            );
        };
        if self.time_limit.is_some() {
            return Err("a partial render (a pass range) cannot have a time budget: where a budget stops depends on the machine".into());
        }
        if r.start >= r.end || r.end > total {
            return Err(format!(
                "pass range {}..{} is not inside this render's passes 0..{total} (start < end <= {total})",
                r.start, r.end
            ));
        }
        Ok(())
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Progress {
    pub spp_done: u32,
    /// Fraction of the work (samples or time budget) done, in [0, 1].
    pub fraction: f64,
    pub elapsed: Duration,
}

/// Where the first dropped (NaN or infinite) sample was: the lowest sample
/// index, then row, then column, so it does not depend on thread timing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct BadSample {
    pub sample: u32,
    pub y: u32,
    pub x: u32,
}

/// Everything a render has accumulated: enough to continue it exactly
/// (checkpoints) or to show it (previews).
#[derive(Clone, Debug)]
pub struct RenderState {
    pub film: Film,
    /// Samples per pixel done (whole passes).
    pub spp_done: u32,
    /// The integrator's own state (see [`Pass::save`]), opaque here.
    pub integrator: Vec<u8>,
    /// Samples dropped because they were NaN or infinite.
    pub bad_samples: u64,
    pub first_bad: Option<BadSample>,
    pub rays: u64,
    /// Wall time spent on this render so far, over all runs.
    pub elapsed: Duration,
}

impl RenderState {
    /// A render that has not started, on `film`.
    pub fn new(film: Film) -> RenderState {
        RenderState {
            film,
            spp_done: 0,
            integrator: Vec::new(),
            bad_samples: 0,
            first_bad: None,
            rays: 0,
            elapsed: Duration::ZERO,
        }
    }
}

/// Optional callbacks and a saved state to continue from.
pub struct RenderHooks<'a> {
    pub progress: &'a (dyn Fn(&Progress) + Sync),
    /// Set (e.g. by SIGINT) to start no further pass.
    pub cancel: &'a AtomicBool,
    /// Called after every pass with the state so far (checkpoints, previews).
    pub after_pass: Option<&'a mut (dyn FnMut(&RenderState) + Send)>,
    /// Continue this state instead of starting from an empty film.
    pub resume: Option<RenderState>,
}

#[derive(Clone, Debug)]
pub struct RenderOutcome {
    pub film: Film,
    /// Samples per pixel done (over all runs of a resumed render).
    pub spp: u32,
    /// Wall time of this run (not counting earlier runs of a resumed render).
    pub elapsed: Duration,
    /// Rays traced by this run.
    pub rays: u64,
    /// The same by kind (camera, indirect, shadow, gather; photons are counted
    /// in the scene's counters).
    pub ray_counts: RayCounts,
    /// Samples dropped because they were NaN or infinite (over all runs).
    pub bad_samples: u64,
    pub first_bad: Option<BadSample>,
    pub interrupted: bool,
    /// Photon pass figures, for the `photon` integrator.
    pub photon_stats: Option<super::photon::PhotonStats>,
    /// The integrator's own state for a further run (see [`Pass::save`]).
    pub integrator: Vec<u8>,
    /// Rays and wall time over all runs (for the state).
    pub total_rays: u64,
    pub total_elapsed: Duration,
}

impl RenderOutcome {
    /// The state to continue from (what a checkpoint saves).
    pub fn state(&self) -> RenderState {
        RenderState {
            film: self.film.clone(),
            spp_done: self.spp,
            integrator: self.integrator.clone(),
            bad_samples: self.bad_samples,
            first_bad: self.first_bad,
            rays: self.total_rays,
            elapsed: self.total_elapsed,
        }
    }
}

/// What an integrator is told when a render starts.
#[derive(Clone, Copy, Debug)]
pub struct Start {
    /// Samples per pixel aimed at (0: until the time budget ends).
    pub spp: u32,
    pub seed: u64,
    /// The area, in pixels, a pixel's samples spread over (the filter's).
    pub pixel_spread: f32,
    /// The filter's radius in pixels: how far outside the film a point
    /// connected to the camera may still land.
    pub filter_radius: Vec2,
    /// The pixels rendered, and the render's wall-clock budget.
    pub crop: PixelBounds,
    pub time_limit: Option<Duration>,
    pub sampler: SamplerKind,
    /// Samples per pixel in each pass.
    pub spp_per_pass: u32,
}

/// What an integrator is told after each pass.
#[derive(Clone, Copy, Debug)]
pub struct PassReport {
    pub spp_done: u32,
    /// Samples per pixel and passes taken by this run, and the time its
    /// passes took.
    pub samples_here: u32,
    pub passes_here: u32,
    pub pass_time_sum: Duration,
    /// Wall time of this run so far, and its budget.
    pub elapsed: Duration,
    pub time_limit: Option<Duration>,
    pub spp_target: u32,
    /// No further pass follows.
    pub stopping: bool,
}

/// A contribution to another pixel than the sample's own (light tracing,
/// bidirectional connections), in full-film raster coordinates.
#[derive(Clone, Copy, Debug)]
pub struct Splat {
    pub x: u32,
    pub y: u32,
    pub l: Rgb,
}

/// Per-sample context: the sample's pixel and index, ray counters, the
/// splat list of the row and the pixel filter.
pub struct SampleCx<'a> {
    pub pixel: (u32, u32),
    pub index: u32,
    pub rays: &'a mut RayCounts,
    pub splats: &'a mut Vec<Splat>,
    pub filter: &'a Filter,
}

impl SampleCx<'_> {
    /// Splats `l` arriving at raster position `p` (full film, pixels, y
    /// down) into every pixel whose filter reaches it, weighted by the
    /// filter's density there: the same pixel estimate as the filter's
    /// importance-sampled camera samples.
    pub fn splat_at(&mut self, p: Vec2, l: Rgb) {
        filter_splats(self.filter, p, l, self.splats);
    }
}

/// `l` arriving at raster position `p` (full film, pixels, y down) as
/// splats into every pixel whose filter reaches it, weighted by the
/// filter's density there.
pub fn filter_splats(filter: &Filter, p: Vec2, l: Rgb, out: &mut Vec<Splat>) {
    let r = filter.radius;
    let (x0, x1) = ((p.x - 0.5 - r.x).ceil(), (p.x - 0.5 + r.x).floor());
    let (y0, y1) = ((p.y - 0.5 - r.y).ceil(), (p.y - 0.5 + r.y).floor());
    let mut y = y0.max(0.0);
    while y <= y1 {
        let mut x = x0.max(0.0);
        while x <= x1 {
            let w = filter.pdf(p - Vec2::new(x + 0.5, y + 0.5));
            if w > 0.0 {
                out.push(Splat {
                    x: x as u32,
                    y: y as u32,
                    l: l * w,
                });
            }
            x += 1.0;
        }
        y += 1.0;
    }
}

/// The integrator side of a render, driven pass by pass.
pub trait Pass: Sync {
    /// Work before a pass (e.g. photon tracing); `false` if `cancel` stopped it.
    fn before_pass(&mut self, cancel: &AtomicBool) -> bool;
    /// Radiance arriving along a camera ray, for the sample's own pixel.
    fn li(&self, ray: Ray, sampler: &mut Sampler, cx: &mut SampleCx) -> Rgb;
    /// Contributions made outside the camera samples (e.g. photons
    /// connected to the camera when they were traced): raster position and
    /// radiance, each an estimate for one sample per pixel, added to the
    /// splats once per sample of every pass.
    fn pass_splats(&self) -> &[(Vec2, Rgb)] {
        &[]
    }
    /// The time the render's next step would take after the pass `report`
    /// tells of, which took `pass_time`: the driver stops under a time
    /// budget when it would not fit. The default, one more pass; `None`:
    /// the render cannot stop here (a budget never cuts the step short).
    fn next_cost(&self, report: &PassReport, pass_time: Duration) -> Option<Duration> {
        let _ = report;
        Some(pass_time)
    }
    /// Bookkeeping after a pass.
    fn after_pass(&mut self, report: &PassReport);
    /// The integrator's own state, for checkpoints (empty if it has none).
    fn save(&self) -> Vec<u8>;
}

/// Renders until the sample count or time budget is reached, or `cancel` is set.
pub fn render(
    scene: &Scene,
    integrator: &Integrator,
    settings: &RenderSettings,
    progress: &(dyn Fn(&Progress) + Sync),
    cancel: &AtomicBool,
) -> RenderOutcome {
    render_with(
        scene,
        integrator,
        settings,
        RenderHooks {
            progress,
            cancel,
            after_pass: None,
            resume: None,
        },
    )
}

/// [`render`] with per-pass callbacks and, optionally, a state to continue.
/// A resumed render is bit-identical to an uninterrupted one with the same
/// settings: samples are indexed from the state's `spp_done` and added to
/// the saved per-pixel statistics in the same order.
pub fn render_with(
    scene: &Scene,
    integrator: &Integrator,
    settings: &RenderSettings,
    mut hooks: RenderHooks,
) -> RenderOutcome {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()
        .expect("thread pool");
    pool.install(|| {
        let start = Start {
            spp: settings.spp,
            seed: settings.seed,
            pixel_spread: settings.filter.sample_spread(),
            filter_radius: settings.filter.radius,
            crop: settings.crop,
            time_limit: settings.time_limit,
            sampler: settings.sampler,
            spp_per_pass: settings.spp_per_pass.max(1),
        };
        if hooks.resume.is_none() {
            if let Some(r) = &settings.passes {
                // A part starts where the whole render would be at its first pass.
                let mut st = RenderState::new(Film::new(scene.camera.resolution, settings.crop));
                st.spp_done = settings.spp_before(r.start);
                st.integrator = Run::state_at(integrator, &start, r.start, st.spp_done);
                hooks.resume = Some(st);
            }
        }
        let saved = hooks.resume.as_ref().map(|s| s.integrator.as_slice());
        let mut run = Run::new(integrator, scene, &start, saved);
        let mut out = match settings.inject_nan {
            None => drive(scene, &mut run, settings, hooks),
            Some(at) => drive(scene, &mut InjectNan(&mut run, at), settings, hooks),
        };
        out.photon_stats = run.photon_stats();
        out
    })
}

/// The pass loop, for any [`Pass`] (inside the caller's thread pool).
pub fn drive<P: Pass>(
    scene: &Scene,
    pass: &mut P,
    settings: &RenderSettings,
    mut hooks: RenderHooks,
) -> RenderOutcome {
    let start = Instant::now();
    let mut state = hooks
        .resume
        .take()
        .unwrap_or_else(|| RenderState::new(Film::new(scene.camera.resolution, settings.crop)));
    let elapsed_before = state.elapsed;
    let per_pass = settings.spp_per_pass.max(1);
    let limit = match (settings.spp, &settings.passes) {
        (0, _) => u32::MAX,
        (_, Some(r)) => settings.spp_before(r.end),
        (n, None) => n,
    };
    // Progress counts a part's own passes.
    let base = settings
        .passes
        .as_ref()
        .map_or(0, |r| settings.spp_before(r.start));
    let share = |done: u32| (done - base) as f64 / (limit - base).max(1) as f64;
    let mut interrupted = false;
    let mut pass_time_sum = Duration::ZERO;
    let mut samples_here = 0u32;
    let mut passes_here = 0u32;
    let mut rays_here = RayCounts::default();
    while state.spp_done < limit {
        if hooks.cancel.load(Ordering::Relaxed) || !pass.before_pass(hooks.cancel) {
            interrupted = true;
            break;
        }
        let done = state.spp_done;
        let n = per_pass.min(limit - done);
        let pass_start = Instant::now();
        let tally = render_pass(scene, &*pass, settings, &mut state.film, done..done + n);
        state.spp_done += n;
        // A part's splats are its own samples' (they merge by adding).
        state.film.splat_samples += n;
        samples_here += n;
        passes_here += 1;
        rays_here.add(&tally.rays);
        state.rays += tally.rays.total();
        state.bad_samples += tally.bad;
        state.first_bad = min_bad(state.first_bad, tally.first_bad);
        let elapsed = start.elapsed();
        state.elapsed = elapsed_before + elapsed;
        let done = state.spp_done;
        let fraction = match settings.time_limit {
            Some(t) if settings.spp == 0 => (elapsed.as_secs_f64() / t.as_secs_f64()).min(1.0),
            Some(t) => (elapsed.as_secs_f64() / t.as_secs_f64())
                .max(share(done))
                .min(1.0),
            None => share(done),
        };
        let pass_time = pass_start.elapsed();
        pass_time_sum += pass_time;
        let mut report = PassReport {
            spp_done: done,
            samples_here,
            passes_here,
            pass_time_sum,
            elapsed,
            time_limit: settings.time_limit,
            spp_target: settings.spp,
            stopping: false,
        };
        // Stop when the next step (another pass of the same length, or what
        // the integrator says) would overrun the budget.
        report.stopping = match (settings.time_limit, pass.next_cost(&report, pass_time)) {
            (Some(t), Some(cost)) => elapsed + cost > t,
            _ => false,
        };
        let stop = report.stopping;
        pass.after_pass(&report);
        state.integrator = pass.save();
        (hooks.progress)(&Progress {
            spp_done: done,
            fraction,
            elapsed,
        });
        if let Some(f) = hooks.after_pass.as_mut() {
            f(&state);
        }
        if stop {
            break;
        }
    }
    scene.count_rays(rays_here.total());
    RenderOutcome {
        spp: state.spp_done,
        elapsed: start.elapsed(),
        rays: rays_here.total(),
        ray_counts: rays_here,
        bad_samples: state.bad_samples,
        first_bad: state.first_bad,
        interrupted,
        photon_stats: None,
        integrator: pass.save(),
        total_rays: state.rays,
        total_elapsed: elapsed_before + start.elapsed(),
        film: state.film,
    }
}

/// What one pass added besides the pixels.
#[derive(Default)]
pub(super) struct Tally {
    rays: RayCounts,
    bad: u64,
    first_bad: Option<BadSample>,
}

impl Tally {
    /// Counts `o`'s rays as this tally's.
    pub(super) fn add_rays(&mut self, o: &Tally) {
        self.rays.add(&o.rays);
    }
}

/// The earlier of two first bad samples.
pub(crate) fn min_bad(a: Option<BadSample>, b: Option<BadSample>) -> Option<BadSample> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// Samples `indices` of every pixel, rows in parallel; then the rows'
/// splats, in row order. A filter that splats has a pass of its own
/// (`splatted.rs`).
fn render_pass<P: Pass>(
    scene: &Scene,
    pass: &P,
    settings: &RenderSettings,
    film: &mut Film,
    indices: std::ops::Range<u32>,
) -> Tally {
    if settings.filter.splat {
        return super::splatted::render_pass(scene, pass, settings, film, indices);
    }
    let width = film.width() as usize;
    let rows: Vec<(Tally, Vec<Splat>)> = film
        .pixels
        .par_chunks_mut(width.max(1))
        .enumerate()
        .map(|(row, pixels)| {
            let py = settings.crop.y0 + row as u32;
            let mut sampler = Sampler::new(settings.sampler, settings.seed);
            let mut t = Tally::default();
            let mut splats = Vec::new();
            for (col, pixel) in pixels.iter_mut().enumerate() {
                let px = settings.crop.x0 + col as u32;
                for s in indices.clone() {
                    sampler.start_pixel_sample(px, py, s);
                    let off = settings.filter.sample(sampler.get_2d());
                    let p_film = Vec2::new(px as f32 + 0.5, py as f32 + 0.5) + off;
                    let at = (px, py, s);
                    let (t, sp) = (&mut t, &mut splats);
                    if let Some(l) =
                        take_sample(scene, pass, settings, &mut sampler, at, p_film, t, sp)
                    {
                        pixel.add(l);
                    }
                }
            }
            (t, splats)
        })
        .collect();
    let mut tally = Tally::default();
    add_rows(&mut tally, film, rows, settings.clamp);
    add_pass_splats(pass, settings, film, indices.len() as f32);
    tally
}

/// Sample `at = (x, y, index)` through film position `p_film` (raster,
/// full film), its camera ray drawn from `sampler`'s next pair; its rays
/// counted and splats kept in the row's `t` and `splats`. Returns its
/// radiance as the film takes it, or `None` for a dropped sample (not
/// finite), which is counted and never reaches a pixel.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(super) fn take_sample<P: Pass>(
    scene: &Scene,
    pass: &P,
    settings: &RenderSettings,
    sampler: &mut Sampler,
    at: (u32, u32, u32),
    p_film: Vec2,
    t: &mut Tally,
    splats: &mut Vec<Splat>,
) -> Option<Rgb> {
    let ray = scene.camera.generate_ray(p_film, sampler.get_2d());
    let mut cx = SampleCx {
        pixel: (at.0, at.1),
        index: at.2,
        rays: &mut t.rays,
        splats,
        filter: &settings.filter,
    };
    let l = accept(pass.li(ray, sampler, &mut cx), settings.clamp);
    if l.is_none() {
        t.bad += 1;
        let (x, y, sample) = at;
        t.first_bad = min_bad(t.first_bad, Some(BadSample { sample, y, x }));
    }
    l
}

/// The rows' tallies into `tally` and their splats into the film, in row order.
pub(super) fn add_rows(
    tally: &mut Tally,
    film: &mut Film,
    rows: Vec<(Tally, Vec<Splat>)>,
    clamp: Option<f32>,
) {
    for (t, splats) in rows {
        tally.add_rays(&t);
        tally.bad += t.bad;
        tally.first_bad = min_bad(tally.first_bad, t.first_bad);
        for s in splats {
            if let Some(l) = accept(s.l, clamp) {
                film.add_splat(s.x, s.y, l);
            }
        }
    }
}

/// The integrator's own splats of the pass (`Pass::pass_splats`), `n`
/// samples per pixel's worth.
pub(super) fn add_pass_splats<P: Pass>(
    pass: &P,
    settings: &RenderSettings,
    film: &mut Film,
    n: f32,
) {
    let own = pass.pass_splats();
    if !own.is_empty() {
        let mut splats = Vec::new();
        for &(p, l) in own {
            filter_splats(&settings.filter, p, l * n, &mut splats);
        }
        for s in splats {
            if let Some(l) = accept(s.l, settings.clamp) {
                film.add_splat(s.x, s.y, l);
            }
        }
    }
}

/// The sample as the film takes it: clamped if asked, `None` if not finite.
#[inline]
fn accept(mut l: Rgb, clamp: Option<f32>) -> Option<Rgb> {
    if let Some(c) = clamp {
        let m = l.max_component();
        if m > c {
            l *= c / m;
        }
    }
    l.is_finite().then_some(l)
}

/// Test hook: makes the sample at (x, y, index) a NaN, to prove bad samples
/// are dropped and reported; wraps the integrator only when asked, so the
/// hook costs ordinary renders nothing.
struct InjectNan<'p, P>(&'p mut P, (u32, u32, u32));

impl<P: Pass> Pass for InjectNan<'_, P> {
    fn before_pass(&mut self, cancel: &AtomicBool) -> bool {
        self.0.before_pass(cancel)
    }
    fn li(&self, ray: Ray, sampler: &mut Sampler, cx: &mut SampleCx) -> Rgb {
        let mut l = self.0.li(ray, sampler, cx);
        if (cx.pixel.0, cx.pixel.1, cx.index) == self.1 {
            l.r = f32::NAN;
        }
        l
    }
    fn pass_splats(&self) -> &[(Vec2, Rgb)] {
        self.0.pass_splats()
    }
    fn next_cost(&self, report: &PassReport, pass_time: Duration) -> Option<Duration> {
        self.0.next_cost(report, pass_time)
    }
    fn after_pass(&mut self, report: &PassReport) {
        self.0.after_pass(report)
    }
    fn save(&self) -> Vec<u8> {
        self.0.save()
    }
}
