//! Orchestration: passes of samples over the film, rows in parallel.
//!
//! Each pass adds `spp_per_pass` samples to every pixel; a pixel's samples
//! are always added in index order by one thread, and every sample's random
//! numbers depend only on (seed, pixel, index), so the image is bit-identical
//! whatever the thread count.

use super::photon::gather::PhotonCtx;
use super::photon::PhotonMaps;
use super::{Integrator, IntegratorKind, RayCounts};
use crate::film::{Film, Filter, PixelBounds};
use crate::scene::Scene;
use lumis_math::{Sampler, SamplerKind, Vec2};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;
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
}

impl RenderSettings {
    /// Settings from a scene's options: `spp` samples per pixel (0 with a time
    /// limit: unbounded), one sample per pass, no clamp.
    pub fn from_options(
        o: &crate::load::RenderOptions,
        spp: u32,
        seed: u64,
        threads: usize,
    ) -> RenderSettings {
        RenderSettings {
            spp,
            seed,
            threads,
            time_limit: None,
            sampler: o.sampler,
            filter: o.filter.clone(),
            crop: o.crop,
            spp_per_pass: 1,
            clamp: None,
            inject_nan: None,
        }
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
    /// `alpha` at the first camera hit for the next pass (`photon`).
    pub alpha: f32,
    /// Samples dropped because they were NaN or infinite.
    pub bad_samples: u64,
    pub first_bad: Option<BadSample>,
    pub rays: u64,
    /// Wall time spent on this render so far, over all runs.
    pub elapsed: Duration,
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
    /// `alpha` for a further pass and the wall time over all runs (for the state).
    pub alpha: f32,
    pub total_rays: u64,
    pub total_elapsed: Duration,
}

impl RenderOutcome {
    pub fn state(&self) -> RenderState {
        RenderState {
            film: self.film.clone(),
            spp_done: self.spp,
            alpha: self.alpha,
            bad_samples: self.bad_samples,
            first_bad: self.first_bad,
            rays: self.total_rays,
            elapsed: self.total_elapsed,
        }
    }
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
    hooks: RenderHooks,
) -> RenderOutcome {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()
        .expect("thread pool");
    pool.install(|| render_in_pool(scene, integrator, settings, hooks))
}

fn render_in_pool(
    scene: &Scene,
    integrator: &Integrator,
    settings: &RenderSettings,
    mut hooks: RenderHooks,
) -> RenderOutcome {
    let start = Instant::now();
    let cam = &scene.camera;
    // alpha (seed, A.10) is the number of samples per pixel: known up front, or
    // with only a time budget, predicted from the passes so far (1 for the first).
    let mut state = hooks.resume.take().unwrap_or_else(|| RenderState {
        film: Film::new(cam.resolution, settings.crop),
        spp_done: 0,
        alpha: if settings.spp > 0 {
            settings.spp as f32
        } else {
            1.0
        },
        bad_samples: 0,
        first_bad: None,
        rays: 0,
        elapsed: Duration::ZERO,
    });
    let elapsed_before = state.elapsed;
    let width = state.film.width() as usize;
    let bad = AtomicU64::new(0);
    let first_bad = Mutex::new(state.first_bad);
    let rays = Mutex::new(RayCounts::default());
    let per_pass = settings.spp_per_pass.max(1);
    let mut interrupted = false;
    let limit = if settings.spp == 0 {
        u32::MAX
    } else {
        settings.spp
    };
    // The photon pass runs once, inside the time budget (a resumed render
    // rebuilds the same maps from the seed: photon tracing is deterministic).
    // An interrupt during it leaves no maps; the loop below then stops
    // before its first pass.
    let maps = (integrator.kind == IntegratorKind::Photon)
        .then(|| PhotonMaps::build(scene, &integrator.photon, settings.seed, hooks.cancel))
        .flatten();
    let pixel_spread = settings.filter.sample_spread();
    let mut pass_time_sum = Duration::ZERO;
    let mut samples_here = 0u32;
    let mut rays_here = RayCounts::default();
    while state.spp_done < limit {
        let ctx = maps.as_ref().map(|m| PhotonCtx {
            scene,
            maps: m,
            s: &integrator.photon,
            alpha_first: state.alpha,
            pixel_spread,
        });
        if hooks.cancel.load(Ordering::Relaxed) {
            interrupted = true;
            break;
        }
        let done = state.spp_done;
        let n = per_pass.min(limit - done);
        let pass_start = Instant::now();
        state
            .film
            .pixels
            .par_chunks_mut(width.max(1))
            .enumerate()
            .for_each(|(row, pixels)| {
                let py = settings.crop.y0 + row as u32;
                let mut sampler = Sampler::new(settings.sampler, settings.seed);
                let mut local_rays = RayCounts::default();
                let mut local_bad = 0u64;
                let mut local_first: Option<BadSample> = None;
                for (col, pixel) in pixels.iter_mut().enumerate() {
                    let px = settings.crop.x0 + col as u32;
                    for s in done..done + n {
                        sampler.start_pixel_sample(px, py, s);
                        let off = settings.filter.sample(sampler.get_2d());
                        let p_film = Vec2::new(px as f32 + 0.5, py as f32 + 0.5) + off;
                        let ray = cam.generate_ray(p_film, sampler.get_2d());
                        let mut l =
                            integrator.li(scene, ctx.as_ref(), ray, &mut sampler, &mut local_rays);
                        if settings.inject_nan == Some((px, py, s)) {
                            l.r = f32::NAN;
                        }
                        if let Some(c) = settings.clamp {
                            let m = l.max_component();
                            if m > c {
                                l *= c / m;
                            }
                        }
                        if l.is_finite() {
                            pixel.add(l);
                        } else {
                            // Dropped, counted, and never allowed into the pixel.
                            local_bad += 1;
                            let b = BadSample {
                                sample: s,
                                y: py,
                                x: px,
                            };
                            local_first = Some(local_first.map_or(b, |f| f.min(b)));
                        }
                    }
                }
                rays.lock().unwrap().add(&local_rays);
                if local_bad > 0 {
                    bad.fetch_add(local_bad, Ordering::Relaxed);
                    let mut f = first_bad.lock().unwrap();
                    *f = match (*f, local_first) {
                        (Some(a), Some(b)) => Some(a.min(b)),
                        (a, b) => a.or(b),
                    };
                }
            });
        state.spp_done += n;
        samples_here += n;
        let pass_rays = std::mem::take(&mut *rays.lock().unwrap());
        rays_here.add(&pass_rays);
        state.rays += pass_rays.total();
        state.bad_samples += bad.swap(0, Ordering::Relaxed);
        state.first_bad = *first_bad.lock().unwrap();
        let elapsed = start.elapsed();
        state.elapsed = elapsed_before + elapsed;
        let done = state.spp_done;
        let fraction = match settings.time_limit {
            Some(t) if settings.spp == 0 => (elapsed.as_secs_f64() / t.as_secs_f64()).min(1.0),
            Some(t) => (elapsed.as_secs_f64() / t.as_secs_f64())
                .max(done as f64 / limit as f64)
                .min(1.0),
            None => done as f64 / limit as f64,
        };
        let pass_time = pass_start.elapsed();
        pass_time_sum += pass_time;
        let mut stop = false;
        if let Some(t) = settings.time_limit {
            // Stop when another pass of the same length would overrun the budget.
            if elapsed + pass_time > t {
                stop = true;
            } else if settings.spp == 0 {
                let per_sample = pass_time_sum.as_secs_f64() / samples_here as f64;
                let left = (t.saturating_sub(elapsed)).as_secs_f64();
                state.alpha = (done as f64 + (left / per_sample.max(1e-9)).floor()).max(1.0) as f32;
            }
        }
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
        photon_stats: maps.map(|m| m.stats),
        alpha: state.alpha,
        total_rays: state.rays,
        total_elapsed: elapsed_before + start.elapsed(),
        film: state.film,
    }
}
