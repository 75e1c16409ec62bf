//! The built-in default scene against a committed reference rendered by
//! `path` at high sample count, compared statistically per block.
//!
//! Regenerate the reference (after changing scenes/default.pbrt) with:
//!   cargo test --release -p lumis-render --test integration -- --ignored default_scene::make_reference

use crate::common;

use common::*;
use lumis_render::image_io::{read_image, write_image, RgbImage};
use lumis_render::load::{Overrides, DEFAULT_SCENE};
use std::path::PathBuf;

const RES: u32 = 48;
const BLOCK: u32 = 8;
const REF_SPP: u32 = 16384;
/// Both the reference and the test clamp each sample's largest component at
/// this value. Both then estimate the same quantity, E[min-scaled L], with a
/// bounded distribution, so the block means are close to normal and the Z-test
/// is valid; unclamped, the caustic paths' rare huge samples (a floor point
/// whose BSDF sample refracts through a sphere onto the small light) make a
/// 1024-spp block occasionally 5 standard errors high with no bias at all.
/// Any error in materials, lights, camera or caustic paths still changes the
/// clamped mean.
const CLAMP: f32 = 10.0;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn overrides() -> Overrides {
    let mut o = Overrides::default();
    o.resolution(RES, RES).integrator("path");
    o
}

/// A render whose samples are clamped at [`CLAMP`], as the reference's.
fn render_clamped(
    l: &lumis_render::load::LoadedScene,
    spp: u32,
    seed: u64,
) -> lumis_render::integrator::RenderOutcome {
    let mut st = settings(l, spp, seed, 0);
    st.clamp = Some(CLAMP);
    lumis_render::integrator::render(
        &l.scene,
        &l.options.integrator,
        &st,
        &|_| {},
        &Default::default(),
    )
}

#[test]
#[ignore = "writes the committed reference; run by hand"]
fn make_reference() {
    // With the filter sampled, whatever the scene's says: independent
    // pixels, whose variances the test adds up per block.
    let mut ov = overrides();
    ov.filter_splat_from(false, "reference");
    let l = load(DEFAULT_SCENE, &ov);
    let out = render_clamped(&l, REF_SPP, 12345);
    let cmd =
        "cargo test --release -p lumis-render --test integration -- --ignored default_scene::make_reference";
    for (name, pixels) in [
        ("default_ref_mean.exr", out.film.mean_image()),
        ("default_ref_var.exr", out.film.variance_image()),
    ] {
        let mut img = RgbImage::new(RES, RES, pixels);
        img.metadata = vec![
            ("lumis:spp".into(), REF_SPP.to_string()),
            ("lumis:integrator".into(), "path".into()),
            ("lumis:clamp".into(), CLAMP.to_string()),
            ("lumis:command".into(), cmd.into()),
        ];
        write_image(&data(name), &img, 0.0).unwrap();
    }
}

#[test]
fn default_scene_matches_reference() {
    let mean = read_image(&data("default_ref_mean.exr")).expect("committed reference");
    let var = read_image(&data("default_ref_var.exr")).expect("committed reference variance");
    assert_eq!(mean.meta("lumis:spp"), Some(REF_SPP.to_string().as_str()));
    let l = load(DEFAULT_SCENE, &overrides());
    let spp = 1024;
    let out = render_clamped(&l, spp, 99);
    // The pixels' values: the default scene's filter splats (a pixel's
    // sums are weighted, its value their ratio to its weights). The
    // reference was rendered with the filter sampled: the same expectation.
    let img = out.film.mean_image();
    // The test's variance comes from the reference's per-sample variance scaled to
    // `spp`: at 256 spp the caustic paths' heavy tail makes a render's own variance
    // estimate too small exactly where it matters (no firefly sampled yet).
    let scale = REF_SPP as f64 / spp as f64;
    // Block sums of (test - reference) and their variances (independent renders).
    let nb = RES / BLOCK;
    let mut worst = 0.0f64;
    let mut z2_sum = 0.0f64;
    let mut tests = 0;
    let mut failures = Vec::new();
    for by in 0..nb {
        for bx in 0..nb {
            for c in 0..3 {
                let (mut d, mut v, mut m) = (0.0f64, 0.0f64, 0.0f64);
                for y in by * BLOCK..(by + 1) * BLOCK {
                    for x in bx * BLOCK..(bx + 1) * BLOCK {
                        let i = (y * RES + x) as usize;
                        d += img[3 * i + c] as f64 - mean.data[3 * i + c] as f64;
                        m += mean.data[3 * i + c] as f64;
                        v += var.data[3 * i + c] as f64 * (1.0 + scale);
                    }
                }
                if v <= 0.0 {
                    assert!(d.abs() < 1e-6, "block {bx},{by} differs with zero variance");
                    continue;
                }
                let z = d / v.sqrt();
                // Significant AND material: a block fails only if it is both
                // statistically off (|z| beyond the Sidak threshold) and more than 3%
                // off. Rare clamped caustic samples can still push a dark block a
                // few standard errors high by 1-2%; a real bug moves blocks by more.
                let material = (d / m.max(1e-9)).abs() > 0.03;
                if z.abs() >= 3.75 && material {
                    failures.push(format!(
                        "block ({bx},{by}) channel {c}: z {z:.2}, relative {:+.3}",
                        d / m
                    ));
                }
                if z.abs() > 3.0 {
                    eprintln!(
                        "block ({bx},{by}) channel {c}: z {z:.2} relative {:+.4}",
                        d / m
                    );
                }
                worst = worst.max(z.abs());
                z2_sum += z * z;
                tests += 1;
            }
        }
    }
    eprintln!(
        "{tests} block tests, worst |z| {worst:.2}, mean z^2 {:.2}",
        z2_sum / tests as f64
    );
    // Sidak-corrected two-sided threshold for 108 tests at alpha = 0.01: |z| < 3.75
    // (applied above, together with the 3% materiality floor).
    // A systematic error of a few percent in any block (a wrong material, light
    // or camera) exceeds this by far.
    assert!(
        failures.is_empty(),
        "blocks differ from the reference: {failures:#?}"
    );
    // Overall calibration: mean z^2 near 1 when both agree.
    assert!(
        z2_sum / (tests as f64) < 2.0,
        "blocks disagree more than their noise allows"
    );
}
