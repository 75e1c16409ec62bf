//! `vcm` (vertex connection and merging) against what is known: the
//! furnace's `Le sum a^k` with pbrt's `maxdepth`, `path`'s committed
//! references and images where `path` is exact (area lights, an
//! environment light, Bitterli's Cornell box), and the light tracer's
//! references on a spot light's and a point light's caustics, which `path`
//! cannot render. Merging is biased by its radius and consistent: with a
//! radius too large on purpose, the caustic's error falls as the passes
//! shrink it. Same bits on any thread count. (That the MIS weights of all
//! techniques sum to one is `mis_weights.rs`.)

use crate::common;

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
    bidir::emitting_furnace_sums("vcm", &[("float initialradius", "0.01")]);
}

#[test]
fn caustic_regions_agree_with_path() {
    bidir::caustic_regions_agree_with_path("vcm", 1024);
}

#[test]
fn white_furnace_is_one_under_an_environment_light() {
    bidir::white_furnace_is_one("vcm");
}

#[test]
fn cornell_box_agrees_with_path() {
    bidir::cornell_box_agrees_with_path("vcm");
}

#[test]
fn delta_light_caustics_agree_with_the_light_tracer() {
    bidir::delta_light_caustics_agree_with_the_light_tracer("vcm", 256);
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
            e += image_mse(&img, &reference.data, None) / 2.0;
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
