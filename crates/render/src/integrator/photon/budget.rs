//! The progressive mode's time rule: under a time budget, when the photon
//! counts are not set, the renderer chooses them so that photon tracing
//! takes a fixed share of every iteration's time (`photonshare`, by default
//! a quarter), then traces a fifth of the global photons that share gives.
//! Photon tracing and camera samples attack different errors (the photon
//! maps' variance and bias; the gather rays', the direct light's and the
//! pixel's), and the balance that minimises the sum is a property of
//! the scene's cost, which only timing can see: a scene whose photons mostly
//! miss the specular objects gets many cheap ones, a scene of heavy camera
//! paths more photons per sample.
//!
//! The counts are chosen once, before iteration 0, from short probes (photon
//! passes at two small fractions of the counts, with a stream no iteration
//! uses, for the fixed and the per-photon cost; camera samples at one pixel
//! in 32 or more), each the fastest of up to three while they take at most
//! 3% of the budget, and kept for every iteration, so the render is an
//! ordinary fixed-count one: the counts and the iteration count it reached
//! reproduce it exactly without a time budget.

use super::aim::Aims;
use super::camera;
use super::gather::PhotonCtx;
use super::progressive::iteration_seed;
use super::{check_memory, PhotonMaps, PhotonSettings};
use crate::film::PixelBounds;
use crate::integrator::driver::Start;
use crate::integrator::RayCounts;
use crate::scene::Scene;
use lumis_math::{Sampler, SamplerKind, Vec2};
use rayon::prelude::*;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// A camera sample at one pixel in this many, at most, for the probe.
const PROBE_PIXELS: u64 = 32;
/// Probes are lengthened until they take this long (seconds), so fixed
/// costs and timer noise do not dominate them.
const PROBE_SECS: f64 = 0.04;
/// Each probe is taken up to this many times and its fastest kept: another
/// process taking the core for a few of a probe's milliseconds slows one
/// repeat, rarely all of them ...
const PROBE_REPEATS: usize = 3;
/// ... as long as the probes take at most this share of the time budget
/// (the first round is always taken).
const PROBE_SHARE: f64 = 0.03;
/// The counts stay within this factor of the settings'.
const MAX_SCALE: f64 = 1024.0;
/// The global map gets this fraction of the count the share gives it: its
/// radiance photons light what the gather rays hit, light that bounced at
/// least once more and smooth, and its time does more as camera samples.
/// Measured on the caustic set (explicit counts: a fifth of the rule's
/// global count at its caustic count): 0.88-1.01 of the error at 30 and
/// 120 s, the large light and the ring the most (docs/integrators.md,
/// "Fewer global photons").
const GLOBAL_FRACTION: f64 = 0.2;

/// The factor by which to scale the photon counts so that photon tracing,
/// `fixed + per_unit * k` seconds at `k` times the settings' counts, takes
/// `share` of an iteration whose camera samples take `camera_secs`; within
/// [1/1024, 1024].
pub fn photon_scale(share: f64, fixed: f64, per_unit: f64, camera_secs: f64) -> f64 {
    let known = per_unit > 0.0 && camera_secs > 0.0 && fixed >= 0.0;
    if !(share > 0.0 && share < 1.0 && known) {
        return 1.0;
    }
    let target = share / (1.0 - share) * camera_secs;
    ((target - fixed) / per_unit).clamp(1.0 / MAX_SCALE, MAX_SCALE)
}

/// `n` rounded to two significant digits (at least 1000 unless 0), so the
/// counts read well in a summary and on a command line.
pub fn round_count(n: f64) -> u64 {
    if !(n >= 1.0) {
        return 0;
    }
    let n = n.max(1000.0);
    let unit = 10f64.powi(n.log10().floor() as i32 - 1);
    ((n / unit).round() * unit) as u64
}

/// Per-iteration photon counts `(global, caustic)` for a time budget:
/// the settings' counts scaled by [`photon_scale`] from probes, then
/// lowered until the maps fit in memory. `None` if interrupted.
pub fn choose_counts(
    scene: &Scene,
    s: &PhotonSettings,
    share: f64,
    iteration_spp: u32,
    render: &Start,
    aims: &Aims,
    cancel: &AtomicBool,
) -> Option<(u64, u64)> {
    let (crop, seed) = (render.crop, render.seed);
    let budget = render.time_limit.map_or(0.0, |t| t.as_secs_f64());
    let start = Instant::now();
    // Photon passes (traces, trees, radiance photons) at fractions f and 4f
    // of the counts: a line through the two gives the fixed and per-photon
    // costs. A stream no iteration uses.
    let probe_seed = iteration_seed(seed, u64::MAX);
    let pass = |f: f64| -> Option<(f64, PhotonMaps)> {
        let mut probe = s.clone();
        probe.global_photons = (s.global_photons as f64 * f).ceil() as u64;
        probe.caustic_photons = (s.caustic_photons as f64 * f).ceil() as u64;
        let t = Instant::now();
        let maps = PhotonMaps::build(scene, &probe, probe_seed, None, aims, cancel)?;
        Some((t.elapsed().as_secs_f64(), maps))
    };
    let mut f = 1.0 / 256.0;
    let (mut t1, mut t4, maps) = loop {
        let (t1, _) = pass(f)?;
        let (t4, maps) = pass(4.0 * f)?;
        if t4 >= PROBE_SECS || f >= 0.25 {
            break (t1, t4, maps);
        }
        f *= 4.0;
    };
    let t_camera = Instant::now();
    let mut camera = camera_probe(scene, s, &maps, crop, seed);
    let round = t1 + t4 + t_camera.elapsed().as_secs_f64();
    for _ in 1..PROBE_REPEATS {
        if start.elapsed().as_secs_f64() + round > PROBE_SHARE * budget {
            break;
        }
        t1 = t1.min(pass(f)?.0);
        t4 = t4.min(pass(4.0 * f)?.0);
        camera = camera.min(camera_probe(scene, s, &maps, crop, seed));
    }
    let per_unit = ((t4 - t1) / (3.0 * f)).max(t4 / (4.0 * f) * 0.5);
    let fixed = (t1 - per_unit * f).max(0.0);
    let camera_secs = camera * iteration_spp as f64;
    let k = photon_scale(share, fixed, per_unit, camera_secs);
    let mut counts = (
        round_count(s.global_photons as f64 * k * GLOBAL_FRACTION),
        round_count(s.caustic_photons as f64 * k),
    );
    loop {
        let mut fit = s.clone();
        (fit.global_photons, fit.caustic_photons) = counts;
        if check_memory(&fit).is_ok() || counts.0 + counts.1 <= 2000 {
            return Some(counts);
        }
        counts = (
            round_count(counts.0 as f64 / 2.0),
            round_count(counts.1 as f64 / 2.0),
        );
    }
}

/// Seconds one sample per pixel over `crop` would take, from one sample at
/// every `d`-th pixel (random positions inside them), `d` halved from
/// [`PROBE_PIXELS`] until the probe takes [`PROBE_SECS`] or covers every
/// pixel.
fn camera_probe(
    scene: &Scene,
    s: &PhotonSettings,
    maps: &PhotonMaps,
    crop: PixelBounds,
    seed: u64,
) -> f64 {
    let w = (crop.x1 - crop.x0).max(1) as u64;
    let pixels = w * (crop.y1 - crop.y0).max(1) as u64;
    let ctx = PhotonCtx {
        scene,
        maps,
        s,
        alpha_first: 1.0,
        pixel_spread: 1.0,
        connect: None,
    };
    let mut d = PROBE_PIXELS;
    loop {
        let n = pixels.div_ceil(d);
        let t = Instant::now();
        (0..n).into_par_iter().for_each(|j| {
            let i = j * d;
            let (px, py) = (crop.x0 + (i % w) as u32, crop.y0 + (i / w) as u32);
            let mut sampler = Sampler::new(SamplerKind::Independent, seed ^ 0x9e0b);
            sampler.start_pixel_sample(px, py, 0);
            let p_film = Vec2::new(px as f32, py as f32) + sampler.get_2d();
            let ray = scene.camera.generate_ray(p_film, sampler.get_2d());
            let mut rays = RayCounts::default();
            std::hint::black_box(camera::li(&ctx, ray, &mut sampler, &mut rays));
        });
        let secs = t.elapsed().as_secs_f64();
        if secs >= PROBE_SECS || d == 1 {
            return secs * pixels as f64 / n as f64;
        }
        d = (d / 2).max(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_gives_photons_their_share_of_the_iteration() {
        // Photons 1 s per unit of the settings' counts, camera 3 s: for half
        // the time, 3x the photons; for a quarter, 1x; a fixed 1 s of it
        // leaves 2 s for photons at half the time.
        assert!((photon_scale(0.5, 0.0, 1.0, 3.0) - 3.0).abs() < 1e-12);
        assert!((photon_scale(0.25, 0.0, 1.0, 3.0) - 1.0).abs() < 1e-12);
        assert!((photon_scale(0.5, 1.0, 1.0, 3.0) - 2.0).abs() < 1e-12);
        // Clamped, and neutral when nothing is known.
        assert_eq!(photon_scale(0.5, 0.0, 1e-9, 1e3), 1024.0);
        assert_eq!(photon_scale(0.5, 0.0, 1e3, 1e-9), 1.0 / 1024.0);
        assert_eq!(photon_scale(0.5, 5.0, 1.0, 3.0), 1.0 / 1024.0);
        assert_eq!(photon_scale(0.0, 0.0, 1.0, 3.0), 1.0);
        assert_eq!(photon_scale(0.5, 0.0, 0.0, 3.0), 1.0);
    }

    #[test]
    fn counts_round_to_two_digits() {
        assert_eq!(round_count(123_456.0), 120_000);
        assert_eq!(round_count(1_560_000.0), 1_600_000);
        assert_eq!(round_count(10.0), 1000);
        assert_eq!(round_count(0.0), 0);
    }
}
