//! The `photon` integrator against `path` on caustic scenes (METHOD.md §5):
//! a glass sphere over a diffuse floor and over a glossy rough-aluminium floor,
//! lit by a small bright area light. In the caustic region, the mean radiance
//! of each caustic mode (mis, photons, gather) must agree with a committed
//! high-sample `path` reference within a bound that shrinks as the photon
//! count grows, and the three modes must agree with each other.
//!
//! Regenerate the references with:
//!   cargo test -p lumis-render --test integration -- --ignored photon_consistency::make_references

use crate::common;

use common::*;
use lumis_render::film::Film;
use lumis_render::image_io::{read_image, write_image, RgbImage};
use lumis_render::load::{load_path, Overrides};

const REF_SPP: u32 = 1_048_576;

/// The single photon map (these tests measure its estimates; the
/// progressive mode's are in `photon_progressive.rs`).
fn ov(integrator: &str) -> Overrides {
    let mut o = Overrides::default();
    o.crop_from(CAUSTIC_CROP, "test").integrator(integrator);
    if integrator == "photon" {
        o.integrator_param("bool progressive", "false");
    }
    o
}

#[test]
#[ignore = "writes the committed references; run by hand"]
fn make_references() {
    for name in ["caustic_sphere", "caustic_sphere_glossy"] {
        let l = load_path(&test_scene(name), &ov("path")).unwrap();
        let out = render_loaded(&l, REF_SPP, 2024, 0);
        let (w, h) = (out.film.width(), out.film.height());
        let cmd =
            "cargo test -p lumis-render --test integration -- --ignored photon_consistency::make_references";
        for (suffix, px) in [
            ("mean", out.film.mean_image()),
            ("var", out.film.variance_image()),
        ] {
            let mut img = RgbImage::new(w, h, px);
            img.metadata = vec![
                ("lumis:spp".into(), REF_SPP.to_string()),
                ("lumis:integrator".into(), "path".into()),
                ("lumis:command".into(), cmd.into()),
            ];
            write_image(&test_data(&format!("{name}_ref_{suffix}.exr")), &img, 0.0).unwrap();
        }
    }
}

fn photon_region(name: &str, mode: &str, caustic_photons: u64, spp: u32) -> (f64, f64) {
    let mut o = ov("photon");
    o.integrator_param("string caustics", &format!("\"{mode}\""));
    o.integrator_param("integer causticphotons", &caustic_photons.to_string());
    let l = load_path(&test_scene(name), &o).unwrap();
    region_mean_and_se(&render_loaded(&l, spp, 7, 0).film, None)
}

fn check_scene(name: &str, spp: u32) {
    let (r, r_se) = caustic_reference(name);
    eprintln!("{name}: path reference {r:.4} ± {r_se:.4}");
    let mut means = Vec::new();
    for mode in ["mis", "photons", "gather"] {
        let mut errs = Vec::new();
        for (n, bias_bound) in [(100_000u64, 0.04f64), (1_000_000, 0.025)] {
            let (m, se) = photon_region(name, mode, n, spp);
            let err = (m - r) / r;
            let noise = (se * se + r_se * r_se).sqrt() / r;
            eprintln!(
                "  {mode:8} {n:>8} caustic photons: {m:.4} ± {se:.4} ({:+.2}%, noise {:.2}%)",
                err * 100.0,
                noise * 100.0
            );
            // Photon-map bias (blur of the density estimate) plus 4 standard errors.
            assert!(
                err.abs() < bias_bound + 4.0 * noise,
                "{name} {mode} N={n}: {:+.2}% off the path reference",
                err * 100.0
            );
            errs.push((err, noise));
            means.push((mode, n, m, se));
        }
        if mode == "photons" {
            // The photon-only estimate's bias falls as the photon count grows.
            let ((e0, _), (e1, n1)) = (errs[0], errs[1]);
            assert!(
                e1.abs() < e0.abs() + 2.0 * n1,
                "{name}: error did not fall with more photons ({e0:+.4} -> {e1:+.4})"
            );
        }
    }
    // No mode double-counts or drops the caustic: at 1M photons all three agree.
    let at = |mode: &str| {
        means
            .iter()
            .find(|m| m.0 == mode && m.1 == 1_000_000)
            .map(|m| (m.2, m.3))
            .unwrap()
    };
    let (mis, mis_se) = at("mis");
    for other in ["photons", "gather"] {
        let (o, o_se) = at(other);
        let d = (mis - o) / mis;
        let noise = (mis_se * mis_se + o_se * o_se).sqrt() / mis;
        assert!(
            d.abs() < 0.05 + 4.0 * noise,
            "{name}: mis and {other} differ by {:+.2}%",
            d * 100.0
        );
    }
}

#[test]
fn diffuse_floor_caustic_matches_path() {
    check_scene("caustic_sphere", 64);
}

#[test]
fn glossy_floor_caustic_matches_path() {
    check_scene("caustic_sphere_glossy", 64);
}

/// Aimed caustic photons (`aimcaustics`): the same caustic with several times
/// more photons stored from the same emitted count; photon fluxes then vary
/// and q_1 uses each photon's own.
#[test]
fn aimed_caustic_photons_match_path() {
    let name = "caustic_sphere";
    let (r, r_se) = caustic_reference(name);
    let mut stored = Vec::new();
    for aim in [false, true] {
        for mode in ["photons", "mis"] {
            let mut o = ov("photon");
            o.integrator_param("string caustics", &format!("\"{mode}\""));
            o.integrator_param("integer causticphotons", "1000000");
            o.integrator_param("bool aimcaustics", &aim.to_string());
            let l = load_path(&test_scene(name), &o).unwrap();
            let out = render_loaded(&l, 64, 7, 0);
            let (m, se) = region_mean_and_se(&out.film, None);
            let err = (m - r) / r;
            let noise = (se * se + r_se * r_se).sqrt() / r;
            eprintln!("aim {aim} {mode}: {m:.4} ± {se:.4} ({:+.2}%)", err * 100.0);
            assert!(
                err.abs() < 0.025 + 4.0 * noise,
                "aim {aim} {mode}: {:+.2}% off the path reference",
                err * 100.0
            );
            stored.push(out.photon_stats.unwrap().caustic_stored);
        }
    }
    assert!(
        stored[2] > 3 * stored[0],
        "aiming should store several times more caustic photons: {stored:?}"
    );
}

/// Per-pixel squared error against the committed reference, less the
/// reference's own variance (an unbiased estimate of the image's MSE).
fn mse_against_reference(name: &str, film: &Film) -> f64 {
    let m = read_image(&test_data(&format!("{name}_ref_mean.exr"))).unwrap();
    let v = read_image(&test_data(&format!("{name}_ref_var.exr"))).unwrap();
    assert_eq!(m.data.len(), 3 * film.pixels.len());
    let mut sq = 0.0f64;
    for (i, p) in film.pixels.iter().enumerate() {
        for c in 0..3 {
            sq += (p.mean()[c] - m.data[3 * i + c] as f64).powi(2) - v.data[3 * i + c] as f64;
        }
    }
    sq / m.data.len() as f64
}

/// The method's claim at equal cost (METHOD.md §5), on the glossy floor:
/// `mis` has a lower error than either technique alone. All three modes do
/// the same work per sample (one caustic query and `m_2` gather rays), so
/// equal sample counts are equal times without timing anything; 1024 spp is
/// about what 4 s of the README's equal-time table gives. It also holds the
/// seed's `alpha = spp` to account: that `alpha` treats every sample of a
/// pixel as reading the same photons, while here a pixel's footprint covers
/// several query discs, and it gives the gather rays too much weight.
/// Measured over seeds 1-4 (CLI, 2M-spp reference): `mis` 0.63-0.93 of
/// `photons`' MSE, 0.25-0.63 of the seed's `alpha`, 0.12-0.23 of `gather`;
/// the bounds below are for the sum over seeds 1 and 2 (0.66, 0.31).
#[test]
fn mis_beats_both_baselines_at_equal_samples_on_the_glossy_floor() {
    let name = "caustic_sphere_glossy";
    let spp = 1024;
    let mse = |mode: &str, alpha: &str, seeds: &[u64]| {
        let mut o = ov("photon");
        o.integrator_param("string caustics", &format!("\"{mode}\""));
        o.integrator_param("string alpha", &format!("\"{alpha}\""));
        let l = load_path(&test_scene(name), &o).unwrap();
        let e: f64 = seeds
            .iter()
            .map(|&s| mse_against_reference(name, &render_loaded(&l, spp, s, 0).film))
            .sum::<f64>()
            / seeds.len() as f64;
        eprintln!("{mode:8} alpha {alpha:9}: MSE {e:.3e} (seeds {seeds:?})");
        e
    };
    let mis = mse("mis", "footprint", &[1, 2]);
    let mis_seed = mse("mis", "spp", &[1, 2]);
    let photons = mse("photons", "footprint", &[1, 2]);
    let gather = mse("gather", "footprint", &[1]);
    assert!(
        mis < 0.85 * photons,
        "mis {mis:.3e} vs photons {photons:.3e}"
    );
    assert!(mis < 0.5 * gather, "mis {mis:.3e} vs gather {gather:.3e}");
    assert!(
        mis < 0.7 * mis_seed,
        "footprint alpha {mis:.3e} vs spp {mis_seed:.3e}"
    );
}
