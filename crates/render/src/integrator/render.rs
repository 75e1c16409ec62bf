//! Orchestration: passes of samples over the film, rows in parallel.
//!
//! Each pass adds `spp_per_pass` samples to every pixel; a pixel's samples
//! are always added in index order by one thread, and every sample's random
//! numbers depend only on (seed, pixel, index), so the image is bit-identical
//! whatever the thread count.

use super::photon::gather::PhotonCtx;
use super::photon::PhotonMaps;
use super::{Integrator, IntegratorKind};
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

#[derive(Clone, Debug)]
pub struct RenderOutcome {
    pub film: Film,
    pub spp: u32,
    pub elapsed: Duration,
    pub rays: u64,
    /// Samples dropped because they were NaN or infinite.
    pub bad_samples: u64,
    pub first_bad_pixel: Option<(u32, u32)>,
    pub interrupted: bool,
    /// Photon pass figures, for the `photon` integrator.
    pub photon_stats: Option<super::photon::PhotonStats>,
}

/// Renders until the sample count or time budget is reached, or `cancel` is set.
pub fn render(
    scene: &Scene,
    integrator: &Integrator,
    settings: &RenderSettings,
    progress: &(dyn Fn(&Progress) + Sync),
    cancel: &AtomicBool,
) -> RenderOutcome {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()
        .expect("thread pool");
    pool.install(|| render_in_pool(scene, integrator, settings, progress, cancel))
}

fn render_in_pool(
    scene: &Scene,
    integrator: &Integrator,
    settings: &RenderSettings,
    progress: &(dyn Fn(&Progress) + Sync),
    cancel: &AtomicBool,
) -> RenderOutcome {
    let start = Instant::now();
    let cam = &scene.camera;
    let mut film = Film::new(cam.resolution, settings.crop);
    let width = film.width() as usize;
    let bad = AtomicU64::new(0);
    let first_bad = Mutex::new(None);
    let rays = AtomicU64::new(0);
    let per_pass = settings.spp_per_pass.max(1);
    let mut done = 0u32;
    let mut interrupted = false;
    let limit = if settings.spp == 0 {
        u32::MAX
    } else {
        settings.spp
    };
    // The photon pass runs once, inside the time budget.
    let maps = (integrator.kind == IntegratorKind::Photon)
        .then(|| PhotonMaps::build(scene, &integrator.photon, settings.seed));
    // alpha (seed, A.10) is the number of samples per pixel: known up front, or
    // with only a time budget, predicted from the passes so far (1 for the first).
    let mut alpha = if settings.spp > 0 {
        settings.spp as f32
    } else {
        1.0
    };
    let mut pass_time_sum = Duration::ZERO;
    while done < limit {
        let ctx = maps.as_ref().map(|m| PhotonCtx {
            scene,
            maps: m,
            s: &integrator.photon,
            alpha_first: alpha,
        });
        if cancel.load(Ordering::Relaxed) {
            interrupted = true;
            break;
        }
        let n = per_pass.min(limit - done);
        let pass_start = Instant::now();
        film.pixels
            .par_chunks_mut(width.max(1))
            .enumerate()
            .for_each(|(row, pixels)| {
                let py = settings.crop.y0 + row as u32;
                let mut sampler = Sampler::new(settings.sampler, settings.seed);
                let mut local_rays = 0u64;
                for (col, pixel) in pixels.iter_mut().enumerate() {
                    let px = settings.crop.x0 + col as u32;
                    for s in done..done + n {
                        sampler.start_pixel_sample(px, py, s);
                        let off = settings.filter.sample(sampler.get_2d());
                        let p_film = Vec2::new(px as f32 + 0.5, py as f32 + 0.5) + off;
                        let ray = cam.generate_ray(p_film, sampler.get_2d());
                        let mut l =
                            integrator.li(scene, ctx.as_ref(), ray, &mut sampler, &mut local_rays);
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
                            if bad.fetch_add(1, Ordering::Relaxed) == 0 {
                                *first_bad.lock().unwrap() = Some((px, py));
                            }
                        }
                    }
                }
                rays.fetch_add(local_rays, Ordering::Relaxed);
            });
        done += n;
        let elapsed = start.elapsed();
        let fraction = match settings.time_limit {
            Some(t) if settings.spp == 0 => (elapsed.as_secs_f64() / t.as_secs_f64()).min(1.0),
            Some(t) => (elapsed.as_secs_f64() / t.as_secs_f64())
                .max(done as f64 / limit as f64)
                .min(1.0),
            None => done as f64 / limit as f64,
        };
        progress(&Progress {
            spp_done: done,
            fraction,
            elapsed,
        });
        let pass_time = pass_start.elapsed();
        pass_time_sum += pass_time;
        if let Some(t) = settings.time_limit {
            // Stop when another pass of the same length would overrun the budget.
            if elapsed + pass_time > t {
                break;
            }
            if settings.spp == 0 {
                let per_pass = pass_time_sum.as_secs_f64() / done as f64;
                let left = (t.saturating_sub(elapsed)).as_secs_f64();
                alpha = (done as f64 + (left / per_pass.max(1e-9)).floor()).max(1.0) as f32;
            }
        }
    }
    scene.count_rays(rays.load(Ordering::Relaxed));
    let first_bad_pixel = *first_bad.lock().unwrap();
    RenderOutcome {
        film,
        spp: done,
        elapsed: start.elapsed(),
        rays: rays.load(Ordering::Relaxed),
        bad_samples: bad.load(Ordering::Relaxed),
        first_bad_pixel,
        interrupted,
        photon_stats: maps.map(|m| m.stats),
    }
}
