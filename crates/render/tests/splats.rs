//! The render driver with an integrator that writes to other pixels than
//! its sample's own (as light tracing and BDPT will): splats reach the
//! film, enter the image divided by the samples per pixel, and give the
//! same bits whatever the thread count.

use lumis_math::{Rgb, Sampler};
use lumis_render::geometry::Ray;
use lumis_render::integrator::driver::{drive, Pass, PassReport, SampleCx, Splat};
use lumis_render::integrator::{RenderHooks, RenderOutcome};
use lumis_render::load::{load_text, LoadedScene, Overrides, DEFAULT_SCENE};
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// Each sample sends a random amount to a pixel chosen from its own, and
/// one splat off the film (which must be dropped).
struct Scatter {
    width: u32,
    height: u32,
    passes: u32,
}

impl Pass for Scatter {
    fn before_pass(&mut self, _: &AtomicBool) -> bool {
        true
    }
    fn li(&self, _: Ray, sampler: &mut Sampler, cx: &mut SampleCx) -> Rgb {
        let (x, y) = cx.pixel;
        let u = sampler.get_1d();
        cx.splats.push(Splat {
            x: (x * 7 + y + cx.index) % self.width,
            y: (y * 3 + x) % self.height,
            l: Rgb::new(u, 1.0, 2.0 * u),
        });
        cx.splats.push(Splat {
            x: self.width + 5,
            y,
            l: Rgb::splat(1e6),
        });
        Rgb::new(0.0, 0.0, 0.5)
    }
    fn after_pass(&mut self, _: &PassReport) {
        self.passes += 1;
    }
    fn save(&self) -> Vec<u8> {
        self.passes.to_le_bytes().to_vec()
    }
}

fn scene() -> LoadedScene {
    let mut ov = Overrides::default();
    ov.resolution(24, 16).integrator("path");
    load_text(DEFAULT_SCENE, "default", Path::new("."), &ov).unwrap()
}

fn render(l: &LoadedScene, threads: usize) -> RenderOutcome {
    let settings = l.options.render_settings(6, 9, threads);
    let mut pass = Scatter {
        width: 24,
        height: 16,
        passes: 0,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let never = AtomicBool::new(false);
    pool.install(|| {
        drive(
            &l.scene,
            &mut pass,
            &settings,
            RenderHooks {
                progress: &|_| {},
                cancel: &never,
                after_pass: None,
                resume: None,
            },
        )
    })
}

#[test]
fn splats_are_deterministic_and_scaled_by_the_sample_count() {
    let l = scene();
    let one = render(&l, 1);
    let two = render(&l, 2);
    let bits = |o: &RenderOutcome| -> Vec<u32> {
        o.film.mean_image().iter().map(|v| v.to_bits()).collect()
    };
    assert_eq!(bits(&one), bits(&two), "1 vs 2 threads");
    assert_eq!(one.spp, 6);
    assert_eq!(
        one.integrator,
        6u32.to_le_bytes().to_vec(),
        "its own state, saved"
    );
    // Every sample splats exactly 1 in green and its own pixel gets 0.5 in
    // blue: over the image, green sums to the pixel count (splats / spp)
    // and nothing of the off-film splats arrives.
    let img = one.film.mean_image();
    let green: f64 = img.chunks_exact(3).map(|p| p[1] as f64).sum();
    assert!((green - 24.0 * 16.0).abs() < 1e-3, "green {green}");
    let blue_minus_red: f64 = img
        .chunks_exact(3)
        .map(|p| (p[2] - 2.0 * p[0]) as f64)
        .sum();
    assert!(
        (blue_minus_red - 0.5 * 24.0 * 16.0).abs() < 1e-3,
        "{blue_minus_red}"
    );
}
