//! The checks `bdpt` and `vcm` share (`bdpt.rs`, `vcm.rs`): each renders
//! with `integrator` and the integrator parameters `params` (declaration,
//! value), and asserts what is known.

use super::*;
use lumis_render::load::{load_path, Overrides};

fn overrides(integrator: &str, params: &[(&str, &str)]) -> Overrides {
    let mut ov = Overrides::default();
    ov.integrator(integrator);
    for (decl, value) in params {
        ov.integrator_param(decl, value);
    }
    ov
}

/// The emitting furnace converges to `Le sum a^k` with pbrt's `maxdepth`
/// (0, 1, 2 and 12 at albedo 0.5; 16 at 0.8), 16 spp over 8 seeds.
pub fn emitting_furnace_sums(integrator: &str, params: &[(&str, &str)]) {
    for (a, le, d) in [
        (0.5f32, 0.5f32, 0u32),
        (0.5, 0.5, 1),
        (0.5, 0.5, 2),
        (0.5, 0.5, 12),
        (0.8, 0.2, 16),
    ] {
        let expected: f64 = (0..=d).map(|k| le as f64 * (a as f64).powi(k as i32)).sum();
        let l = load(
            &emitting_furnace(a, le, integrator, d),
            &overrides(integrator, params),
        );
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
/// million-sample references, `spp` over 8 seeds.
pub fn caustic_regions_agree_with_path(integrator: &str, spp: u32) {
    for name in ["caustic_sphere", "caustic_sphere_glossy"] {
        let mut ov = overrides(integrator, &[]);
        ov.crop_from(CAUSTIC_CROP, "test");
        let l = load_path(&test_scene(name), &ov).unwrap();
        let (r, r_se) = caustic_reference(name);
        assert_close(name, over_seeds(&l, spp, 0..8), r, r_se);
    }
}

/// A white diffuse sphere under a uniform environment of radiance 1 is
/// radiance 1 everywhere (40 bounces: what is left beyond them is nil for
/// a convex sphere, which light leaves after one bounce).
pub fn white_furnace_is_one(integrator: &str) {
    let l = load(
        &white_furnace(
            integrator,
            r#"Material "diffuse" "rgb reflectance" [ 1 1 1 ]"#,
        )
        .replace(
            r#""integer maxdepth" [ 300 ]"#,
            r#""integer maxdepth" [ 40 ]"#,
        ),
        &Default::default(),
    );
    assert_close("white furnace", over_seeds(&l, 16, 0..8), 1.0, 0.0);
}

/// Bitterli's Cornell box at 32 x 32: channel means within 1% of `path`'s.
pub fn cornell_box_agrees_with_path(integrator: &str) {
    let (Some(v), Some(p)) = (
        cornell_box(integrator, 256, 32),
        cornell_box("path", 1024, 32),
    ) else {
        return;
    };
    for (c, r) in channel_ratios(&v, &p).into_iter().enumerate() {
        eprintln!("channel {c}: {integrator} / path {r:.4}");
        assert!((r - 1.0).abs() < 0.01, "channel {c}: {r:.4}");
    }
}

/// Delta lights' caustics, which `path` cannot see, against the light
/// tracer's committed references (`lighttracer.rs`): the spot light's
/// focused through the glass sphere (its region, 262k spp; `spot_spp`
/// over 8 seeds), and the point light's off the silver ring (every pixel
/// the 32k-spp reference sees, not where the ring shows the camera; 64 spp
/// over 8 seeds).
pub fn delta_light_caustics_agree_with_the_light_tracer(integrator: &str, spot_spp: u32) {
    let mut ov = overrides(integrator, &[]);
    ov.crop_from(SPOT_CROP, "test");
    let l = load_path(&caustic_scene("spot-glass"), &ov).unwrap();
    assert_close(
        "spot-glass",
        over_seeds(&l, spot_spp, 0..8),
        reference_mean("spot_glass_lt_mean.exr"),
        0.0,
    );
    let (m, r) = ring_lit_means(integrator, 64, 0..8);
    assert_close("ring-point, lit pixels", m, r, 0.0);
}
