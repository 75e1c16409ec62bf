//! `bdpt` (bidirectional path tracing with MIS over every connection
//! strategy) against what is known: the furnace's `Le sum a^k` with pbrt's
//! `maxdepth`, `path`'s committed references and images where `path` is
//! exact (area lights, an environment light), and the light tracer's
//! references on a spot light's and a point light's caustics, which `path`
//! cannot render (these checks are shared with `vcm.rs`: `common/bidir.rs`). Its
//! MIS: every strategy rendered alone (weighted) sums to the full image,
//! and strategies of one depth rendered alone and unweighted estimate the
//! same light. Same bits on any thread count.

use crate::common;

use common::*;

#[test]
fn furnace_converges_to_le_sum_of_albedo_powers_with_pbrts_maxdepth() {
    bidir::emitting_furnace_sums("bdpt", &[]);
}

#[test]
fn caustic_regions_agree_with_path() {
    bidir::caustic_regions_agree_with_path("bdpt", 512);
}

/// The environment is reached by light samples and escaped rays only.
#[test]
fn white_furnace_is_one_under_an_environment_light() {
    bidir::white_furnace_is_one("bdpt");
}

#[test]
fn cornell_box_agrees_with_path() {
    bidir::cornell_box_agrees_with_path("bdpt");
}

#[test]
fn delta_light_caustics_agree_with_the_light_tracer() {
    bidir::delta_light_caustics_agree_with_the_light_tracer("bdpt", 1024);
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
