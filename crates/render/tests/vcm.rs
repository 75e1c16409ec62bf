//! `vcm` (vertex connection and merging) against what is known: the
//! furnace's `Le sum a^k` with pbrt's `maxdepth`, `path`'s committed
//! references and images where `path` is exact (area lights, an
//! environment light, Bitterli's Cornell box), and the light tracer's
//! references on a spot light's and a point light's caustics, which `path`
//! cannot render. Merging is biased by its radius and consistent: with a
//! radius too large on purpose, the caustic's error falls as the passes
//! shrink it. Same bits on any thread count. (That the MIS weights of all
//! techniques sum to one is a unit test: `src/integrator/vcm/mis_test.rs`.)

mod common;

use common::*;
use lumis_render::load::{load_path, Overrides};

/// The furnace with a radius so small (0.01 in a sphere of radius 3) that
/// merges have no share in it: the connections and their weights balance
/// energy. (At the automatic radius, merges evaluate their weights at the
/// camera vertex rather than at the light vertex they merge with: measured
/// at maxdepth 1, 64 passes, 8 seeds, 0.749950 +- 0.000007 for 0.75, a
/// bias of 7e-5 that the radius's shrinking removes; the merges are
/// checked where they matter, on caustics, below.)
#[test]
fn furnace_converges_to_le_sum_of_albedo_powers_with_pbrts_maxdepth() {
    for (a, le, d) in [
        (0.5f32, 0.5f32, 0u32),
        (0.5, 0.5, 1),
        (0.5, 0.5, 2),
        (0.5, 0.5, 12),
        (0.8, 0.2, 16),
    ] {
        let expected: f64 = (0..=d).map(|k| le as f64 * (a as f64).powi(k as i32)).sum();
        let mut ov = Overrides::default();
        ov.integrator_param("float initialradius", "0.01");
        let l = load(&emitting_furnace(a, le, "vcm", d), &ov);
        assert_close(
            &format!("albedo {a}, maxdepth {d}"),
            over_seeds(&l, 16, 0..8),
            expected,
            0.0,
        );
    }
}

/// The caustic regions of the glass sphere over a diffuse and over a rough
/// aluminium floor (small area light) against `path`'s committed
/// million-sample references.
#[test]
fn caustic_regions_agree_with_path() {
    for name in ["caustic_sphere", "caustic_sphere_glossy"] {
        let mut ov = Overrides::default();
        ov.crop_from(CAUSTIC_CROP, "test").integrator("vcm");
        let l = load_path(&test_scene(name), &ov).unwrap();
        let (r, r_se) = caustic_reference(name);
        assert_close(name, over_seeds(&l, 1024, 0..8), r, r_se);
    }
}

/// The white furnace: a white diffuse sphere under a uniform environment
/// of radiance 1 is radiance 1 everywhere.
#[test]
fn white_furnace_is_one_under_an_environment_light() {
    let l = load(
        &white_furnace("vcm", r#"Material "diffuse" "rgb reflectance" [ 1 1 1 ]"#).replace(
            r#""integer maxdepth" [ 300 ]"#,
            r#""integer maxdepth" [ 40 ]"#,
        ),
        &Default::default(),
    );
    assert_close("white furnace", over_seeds(&l, 16, 0..8), 1.0, 0.0);
}

/// Bitterli's Cornell box: the whole image and its channels against `path`.
#[test]
fn cornell_box_agrees_with_path() {
    let (Some(v), Some(p)) = (cornell_box("vcm", 256, 32), cornell_box("path", 1024, 32)) else {
        return;
    };
    for (c, r) in channel_ratios(&v, &p).into_iter().enumerate() {
        eprintln!("channel {c}: vcm / path {r:.4}");
        assert!((r - 1.0).abs() < 0.01, "channel {c}: {r:.4}");
    }
}

/// Delta lights' caustics, which `path` cannot see, against the light
/// tracer's committed 262k-spp references (`lighttracer.rs`): the spot
/// light's focused through the glass sphere (its region), and the point
/// light's off the silver ring (the whole image where the light tracer
/// sees: not where the ring shows the camera).
#[test]
fn delta_light_caustics_agree_with_the_light_tracer() {
    let mut ov = Overrides::default();
    ov.crop_from(SPOT_CROP, "test").integrator("vcm");
    let l = load_path(&caustic_scene("spot-glass"), &ov).unwrap();
    assert_close(
        "spot-glass",
        over_seeds(&l, 256, 0..8),
        reference_mean("spot_glass_lt_mean.exr"),
        0.0,
    );
    let (m, r) = ring_lit_means("vcm", &[], 64, 0..8);
    assert_close("ring-point, lit pixels", m, r, 0.0);
}

/// Consistency: with a first radius 20 times the automatic one, the spot
/// light's caustic is blurred; as the passes shrink the radius, the error
/// against the light tracer's reference falls (MSE over the region's
/// pixels, two seeds).
#[test]
fn error_falls_as_the_radius_shrinks() {
    let reference = lumis_render::image_io::read_image(&test_data("spot_glass_lt_mean.exr"))
        .expect("committed reference");
    let mut mse = Vec::new();
    for spp in [4u32, 32, 256] {
        let mut ov = Overrides::default();
        ov.crop_from(SPOT_CROP, "test")
            .integrator("vcm")
            .integrator_param("float initialradius", "0.1")
            .integrator_param("float shrink", "0.5");
        let l = load_path(&caustic_scene("spot-glass"), &ov).unwrap();
        let mut e = 0.0;
        for seed in [1, 2] {
            let img = render_loaded(&l, spp, seed, 0).film.mean_image();
            let d: f64 = img
                .iter()
                .zip(&reference.data)
                .map(|(&a, &b)| (a as f64 - b as f64).powi(2))
                .sum();
            e += d / img.len() as f64 / 2.0;
        }
        eprintln!("{spp} passes: MSE {e:.3e}");
        mse.push(e);
    }
    assert!(mse[1] < 0.5 * mse[0], "4 -> 32 passes: {mse:?}");
    assert!(mse[2] < 0.5 * mse[1], "32 -> 256 passes: {mse:?}");
}

#[test]
fn same_bits_on_any_thread_count() {
    assert_same_bits_on_one_and_two_threads("vcm");
}
