//! `bdpt` (bidirectional path tracing with MIS over every connection
//! strategy) against what is known: the furnace's `Le sum a^k` with pbrt's
//! `maxdepth`, `path`'s committed references and images where `path` is
//! exact (area lights, an environment light), and the light tracer's
//! reference on a spot light's caustic, which `path` cannot render. Its
//! MIS: every strategy rendered alone (weighted) sums to the full image,
//! and strategies of one depth rendered alone and unweighted estimate the
//! same light. Same bits on any thread count.

mod common;

use common::*;
use lumis_render::load::{load_path, Overrides};

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
        let l = load(&emitting_furnace(a, le, "bdpt", d), &Default::default());
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
        ov.crop_from(CAUSTIC_CROP, "test").integrator("bdpt");
        let l = load_path(&test_scene(name), &ov).unwrap();
        let (r, r_se) = caustic_reference(name);
        assert_close(name, over_seeds(&l, 512, 0..8), r, r_se);
    }
}

/// The white furnace: a white diffuse sphere under a uniform environment
/// of radiance 1 is radiance 1 everywhere (the environment reached by light
/// samples and escaped rays).
#[test]
fn white_furnace_is_one_under_an_environment_light() {
    let l = load(
        &white_furnace("bdpt", r#"Material "diffuse" "rgb reflectance" [ 1 1 1 ]"#).replace(
            r#""integer maxdepth" [ 300 ]"#,
            r#""integer maxdepth" [ 40 ]"#,
        ),
        &Default::default(),
    );
    // 40 bounces of albedo 1: what is left beyond them is nil for a convex
    // sphere (light leaves it after one bounce).
    assert_close("white furnace", over_seeds(&l, 16, 0..8), 1.0, 0.0);
}

/// Bitterli's Cornell box: the whole image and its channels against `path`.
#[test]
fn cornell_box_agrees_with_path() {
    let (Some(b), Some(p)) = (cornell_box("bdpt", 256, 32), cornell_box("path", 1024, 32)) else {
        return;
    };
    for (c, r) in channel_ratios(&b, &p).into_iter().enumerate() {
        eprintln!("channel {c}: bdpt / path {r:.4}");
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
    ov.crop_from(SPOT_CROP, "test").integrator("bdpt");
    let l = load_path(&caustic_scene("spot-glass"), &ov).unwrap();
    assert_close(
        "spot-glass",
        over_seeds(&l, 1024, 0..8),
        reference_mean("spot_glass_lt_mean.exr"),
        0.0,
    );
    let (m, r) = ring_lit_means("bdpt", &[], 64, 0..8);
    assert_close("ring-point, lit pixels", m, r, 0.0);
}

/// A small all-diffuse room (so that every strategy can make every path)
/// lit by a small area light, for the MIS tests.
fn diffuse_room(extra: &str, maxdepth: u32) -> String {
    format!(
        r#"Integrator "bdpt" "integer maxdepth" [ {maxdepth} ] {extra}
{}
LookAt 0 1 3.5  0 0.8 0  0 1 0
Camera "perspective" "float fov" [ 45 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 5 5 5 ] "bool twosided" true
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  Shape "trianglemesh" "point3 P" [ -0.5 1.8 -0.5  0.5 1.8 -0.5  0.5 1.8 0.5  -0.5 1.8 0.5 ] "integer indices" [ 0 2 1 0 3 2 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.7 0.6 0.5 ]
Shape "trianglemesh" "point3 P" [ -2 0 -2  2 0 -2  2 0 2  -2 0 2  -2 2.01 -2  2 2.01 -2  2 2.01 2  -2 2.01 2 ]
  "integer indices" [ 0 1 2 0 2 3  4 6 5 4 7 6  0 4 5 0 5 1  0 3 7 0 7 4  1 5 6 1 6 2 ]
Material "diffuse" "rgb reflectance" [ 0.3 0.5 0.8 ]
AttributeBegin
  Translate 0.3 0.4 -0.2
  Shape "sphere" "float radius" [ 0.4 ]
AttributeEnd
"#,
        header(16)
    )
}

/// Every strategy `(s, t)` rendered alone, with its MIS weight, from the
/// same seed: their images add up to the full render's.
#[test]
fn weighted_strategies_sum_to_the_full_image() {
    let maxdepth = 3u32;
    let full = render_loaded(
        &load(&diffuse_room("", maxdepth), &Default::default()),
        4,
        7,
        1,
    )
    .film
    .mean_image();
    let mut sum = vec![0.0f64; full.len()];
    for t in 1..=maxdepth + 2 {
        for s in 0..=maxdepth + 2 - t {
            if s == 1 && t == 1 {
                continue;
            }
            let extra = format!(r#""integer strategy" [ {s} {t} ]"#);
            let img = render_loaded(
                &load(&diffuse_room(&extra, maxdepth), &Default::default()),
                4,
                7,
                1,
            )
            .film
            .mean_image();
            for (a, &b) in sum.iter_mut().zip(&img) {
                *a += b as f64;
            }
        }
    }
    let total: f64 = full.iter().map(|&v| v as f64).sum();
    assert!(total > 0.0);
    let worst = full
        .iter()
        .zip(&sum)
        .map(|(&f, &s)| (f as f64 - s).abs() / (f as f64).abs().max(1e-3))
        .fold(0.0, f64::max);
    eprintln!("largest relative difference {worst:.2e}");
    assert!(worst < 1e-4, "strategies do not add up: {worst:.2e}");
}

/// Strategies of one depth rendered alone without weights each estimate
/// the light over paths of that depth: their image means agree.
#[test]
fn unweighted_strategies_of_one_depth_agree() {
    for depth in [1u32, 2] {
        let mut means = Vec::new();
        for s in 0..=depth + 2 {
            let t = depth + 2 - s;
            if t == 0 || (s == 1 && t == 1) {
                continue;
            }
            let extra = format!(r#""integer strategy" [ {s} {t} ] "bool mis" false"#);
            let l = load(&diffuse_room(&extra, depth), &Default::default());
            // Hitting the light (s = 0) is the noisiest way to find it.
            let spp = if s == 0 { 2048 } else { 1024 };
            let m = over_seeds(&l, spp, 0..8);
            eprintln!("depth {depth}, ({s}, {t}): {:.5} ± {:.5}", m.0, m.1);
            means.push(((s, t), m));
        }
        // Against the most precise of them.
        let (_, base) = *means
            .iter()
            .min_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
            .unwrap();
        for ((s, t), m) in &means {
            assert_close(&format!("depth {depth} ({s}, {t})"), *m, base.0, base.1);
        }
    }
}

#[test]
fn same_bits_on_any_thread_count() {
    assert_same_bits_on_one_and_two_threads("bdpt");
}
