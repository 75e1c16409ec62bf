//! A render stopped after some passes and continued from its saved state
//! (through the checkpoint file format) equals an uninterrupted render, bit
//! for bit, for `path` and for `photon` (whose maps are rebuilt from the seed).
//! Also: an injected NaN sample is dropped, counted and located.

use crate::common;

use common::{load, render_until};
use lumis_render::checkpoint::Checkpoint;
use lumis_render::film::Film;
use lumis_render::integrator::{BadSample, RenderOutcome, RenderSettings};
use lumis_render::load::{LoadedScene, Overrides, DEFAULT_SCENE};

fn scene(integrator: &str) -> LoadedScene {
    scene_with(integrator, Overrides::default())
}

fn scene_with(integrator: &str, mut ov: Overrides) -> LoadedScene {
    ov.resolution(20, 14)
        .integrator(integrator)
        .integrator_param("integer photons", "20000")
        .integrator_param("integer causticphotons", "20000")
        .integrator_param("integer gatherrays", "4");
    load(DEFAULT_SCENE, &ov)
}

fn assert_same_bits(a: &Film, b: &Film) {
    assert_eq!(a.pixels.len(), b.pixels.len());
    for (i, (p, q)) in a.pixels.iter().zip(&b.pixels).enumerate() {
        assert_eq!(p, q, "pixel {i}");
    }
    assert_eq!(a.splats, b.splats, "splats");
    assert_eq!(a.splat_samples, b.splat_samples);
    assert_eq!(a.weights, b.weights, "weights");
}

fn resume_equals_uninterrupted(integrator: &str, spp: u32, stop: u32) {
    resume_of(&scene(integrator), spp, stop);
}

fn resume_of(l: &LoadedScene, spp: u32, stop: u32) {
    let s = common::settings(l, spp, 11, 2);
    let full = render_until(l, &s, None, None);
    assert_eq!(full.spp, spp);
    let part = render_until(l, &s, Some(stop), None);
    assert!(part.interrupted);
    assert_eq!(part.spp, stop);
    // Through the file format, as `--checkpoint` / `--resume` do.
    let ck = Checkpoint {
        lumis_version: env!("CARGO_PKG_VERSION").into(),
        scene_hash: 1,
        job: format!("{{\"seed\": 11, \"budget\": {{\"spp\": {spp}}}}}"),
        state: part.state(),
    };
    let back = Checkpoint::decode(&ck.encode(), "test").unwrap();
    // Resumed on another thread count: still identical.
    let s1 = RenderSettings { threads: 1, ..s };
    let resumed = render_until(l, &s1, None, Some(back.state));
    assert_eq!(resumed.spp, spp);
    assert!(!resumed.interrupted);
    assert_same_bits(&resumed.film, &full.film);
    // A broken resume would differ: the partial film is not the full one.
    assert!(part.film.pixels.iter().any(|p| p.n != spp as u64));
}

#[test]
fn path_resume_is_bit_identical() {
    resume_equals_uninterrupted("path", 6, 2);
}

#[test]
fn photon_resume_is_bit_identical() {
    resume_equals_uninterrupted("photon", 4, 1);
}

/// A splatting filter's film (its weights) resumes too, with the photon
/// pass's own camera splats beside it.
#[test]
fn splatted_photon_resume_is_bit_identical() {
    let mut ov = Overrides::default();
    ov.filter_splat(true);
    let l = scene_with("photon", ov);
    assert!(l.options.filter.splat);
    resume_of(&l, 4, 1);
}

#[test]
fn lighttracer_resume_is_bit_identical() {
    resume_equals_uninterrupted("lighttracer", 6, 2);
}

#[test]
fn bdpt_resume_is_bit_identical() {
    resume_equals_uninterrupted("bdpt", 6, 2);
}

/// `vcm`'s state is its pass count (the radius and the light subpaths'
/// streams follow from it).
#[test]
fn vcm_resume_is_bit_identical() {
    resume_equals_uninterrupted("vcm", 6, 2);
}

/// The default scene with `path`, its filter sampled (`splat` false) or
/// splatting, rendered at 3 spp with sample 1 of pixel (5, 3) made a NaN:
/// the NaN is dropped, counted and located, and the image finite.
fn with_a_nan(splat: bool) -> RenderOutcome {
    let mut ov = Overrides::default();
    ov.filter_splat(splat);
    let l = scene_with("path", ov);
    let s = RenderSettings {
        inject_nan: Some((5, 3, 1)),
        ..common::settings(&l, 3, 0, 2)
    };
    let out = render_until(&l, &s, None, None);
    assert_eq!(out.bad_samples, 1);
    let (x, y, sample) = (5, 3, 1);
    assert_eq!(out.first_bad, Some(BadSample { x, y, sample }));
    assert!(out.film.mean_image().iter().all(|v| v.is_finite()));
    out
}

#[test]
fn injected_nan_is_dropped_counted_and_located() {
    let out = with_a_nan(false);
    // Its pixel has one sample fewer.
    let w = out.film.width() as usize;
    assert_eq!(out.film.pixels[3 * w + 5].n, 2);
    assert!(out
        .film
        .pixels
        .iter()
        .enumerate()
        .all(|(i, p)| p.n == 3 || i == 3 * w + 5));
}

/// Splatting, a dropped sample is black in the pixels it reaches (each
/// pixel still adds one weighted sum per sample index).
#[test]
fn injected_nan_is_dropped_counted_and_located_when_splatting() {
    let out = with_a_nan(true);
    assert!(out.film.pixels.iter().all(|p| p.n == 3));
}
