//! A textured area emitter rendered by `path`, `photon`, `lighttracer`, `bdpt` and `vcm`, against analytic
//! and numeric integrals: a quad at z = 1 facing down, emitting a two-colour
//! 2x1 image (bilinear: colour `A` up to u = 1/4, `B` from u = 3/4, linear
//! between), seen directly from below and lighting a diffuse floor at z = 0.
//! Each pixel's expected value is integrated over its footprint (the camera
//! looks straight at planes parallel to the film); the left and right halves
//! of the image are compared separately (Z-tests against the pixels' own
//! variance), so a mirrored or colour-swapped image fails.

use crate::common;

use common::*;
use lumis_math::{Vec2, Vec3, PI};
use lumis_render::film::Film;
use lumis_render::load::LoadedScene;

const A: [f32; 3] = [0.2, 0.4, 1.0];
const B: [f32; 3] = [3.0, 2.0, 0.5];
const RES: u32 = 16;
const ALBEDO: f64 = 0.5;

/// The emitter's radiance (channel `c`) at `x` on the quad [-1, 1]^2.
fn l_emit(c: usize, x: f64) -> f64 {
    let u = (x + 1.0) / 2.0;
    let (a, b) = (A[c] as f64, B[c] as f64);
    a + (b - a) * ((u - 0.25) / 0.5).clamp(0.0, 1.0)
}

/// Irradiance (channel `c`) on the floor at (x, y) from the emitter one unit
/// above: `∫ L cos cos / r^2 dA = ∫ L / r^4 dA`, by a 64x64 midpoint rule
/// (the ramp's kinks at x = ±1/2 fall on cell edges).
fn irradiance(c: usize, x: f64, y: f64) -> f64 {
    let n = 64;
    let h = 2.0 / n as f64;
    let mut e = 0.0;
    for i in 0..n {
        let xe = -1.0 + (i as f64 + 0.5) * h;
        let l = l_emit(c, xe);
        for j in 0..n {
            let ye = -1.0 + (j as f64 + 0.5) * h;
            let r2 = (x - xe).powi(2) + (y - ye).powi(2) + 1.0;
            e += l / (r2 * r2) * h * h;
        }
    }
    e
}

fn scene(integrator: &str, spp: u32, camera: &str, floor: bool) -> LoadedScene {
    let img = common::envmap::write_env("textured-emitter.exr", 2, 1, |x, _| {
        let t = if x == 0 { A } else { B };
        lumis_math::Rgb::new(t[0], t[1], t[2])
    });
    let floor = if floor {
        "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\nShape \"trianglemesh\" \"point3 P\" [ -10 -10 0  10 -10 0  10 10 0  -10 10 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]"
    } else {
        ""
    };
    let photon = if integrator == "photon" {
        "\"integer photons\" [ 20000 ] \"integer causticphotons\" [ 1000 ]"
    } else {
        ""
    };
    let text = format!(
        r#"Integrator "{integrator}" "integer maxdepth" [ 5 ] {photon}
Sampler "independent" "integer pixelsamples" [ {spp} ]
PixelFilter "box"
Film "rgb" "integer xresolution" [ {RES} ] "integer yresolution" [ {RES} ]
{camera}
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "string filename" "{}"
Material "diffuse" "rgb reflectance" [ 0 0 0 ]
Shape "trianglemesh" "point3 P" [ -1 -1 1  1 -1 1  1 1 1  -1 1 1 ] "integer indices" [ 0 2 1 0 3 2 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]
AttributeEnd
{floor}
"#,
        img.display()
    );
    let l = load(&text, &Default::default());
    assert!(l.warnings.is_empty(), "warnings: {:?}", l.warnings);
    l
}

/// Z-scores of the left and right image halves against `expected(c, x, y)`
/// averaged over each pixel's footprint on the plane `z = plane`.
/// Each pixel's expected value (channel-interleaved), integrated over its
/// footprint on the plane `z = plane`.
fn expected_image(
    l: &LoadedScene,
    plane: f32,
    expected: impl Fn(usize, f64, f64) -> f64,
) -> Vec<f64> {
    let cam = &l.scene.camera;
    let k = 4;
    let mut out = vec![0.0; (3 * RES * RES) as usize];
    for py in 0..RES {
        for px in 0..RES {
            for c in 0..3 {
                let mut e = 0.0;
                for a in 0..k {
                    for b in 0..k {
                        let pf = Vec2::new(
                            px as f32 + (a as f32 + 0.5) / k as f32,
                            py as f32 + (b as f32 + 0.5) / k as f32,
                        );
                        let r = cam.generate_ray(pf, Vec2::splat(0.5));
                        let t = (plane - r.o.z) / r.d.z;
                        let p: Vec3 = r.o + r.d * t;
                        e += expected(c, p.x as f64, p.y as f64) / (k * k) as f64;
                    }
                }
                out[3 * (py * RES + px) as usize + c] = e;
            }
        }
    }
    out
}

/// Whether pixel index `i` (channel-interleaved) is in image half `half`.
fn in_half(i: usize, half: u32) -> bool {
    let px = (i / 3) as u32 % RES;
    px / (RES / 2) == half
}

/// Z-test of each image half's sum against its expected sum, `diff` and
/// `var` the half's rendered-minus-expected sum and its variance.
fn z_test(half: u32, diff: f64, var: f64, sum_exp: f64) {
    let se = var.sqrt().max(1e-5 * sum_exp);
    let z = diff / se;
    eprintln!(
        "half {half}: rendered / expected {:.5}, z {z:+.2} (relative se {:.2e})",
        (sum_exp + diff) / sum_exp,
        se / sum_exp
    );
    assert!(z.abs() < 4.5, "half {half}: off by {z:.1} standard errors");
    assert!(se < 0.005 * sum_exp, "half {half}: too noisy to see 1%");
}

/// The halves against the pixels' own variance (integrators whose samples
/// stay in their pixel).
fn halves(l: &LoadedScene, film: &Film, plane: f32, expected: impl Fn(usize, f64, f64) -> f64) {
    let e = expected_image(l, plane, expected);
    for half in 0..2 {
        let (mut diff, mut var, mut sum_exp) = (0.0, 0.0, 0.0);
        for (i, &ei) in e.iter().enumerate().filter(|(i, _)| in_half(*i, half)) {
            let pixel = &film.pixels[i / 3];
            diff += pixel.mean()[i % 3] - ei;
            var += pixel.variance_of_mean()[i % 3] as f64;
            sum_exp += ei;
        }
        z_test(half, diff, var, sum_exp);
    }
}

/// The halves over independent seeds (integrators that splat: their
/// pixels share light paths), `spp` each.
fn halves_over_seeds(
    l: &LoadedScene,
    spp: u32,
    seeds: std::ops::Range<u64>,
    plane: f32,
    expected: impl Fn(usize, f64, f64) -> f64,
) {
    let e = expected_image(l, plane, expected);
    let images: Vec<Vec<f32>> = seeds
        .map(|s| render_loaded(l, spp, s, 0).film.mean_image())
        .collect();
    for half in 0..2 {
        let sums: Vec<f64> = images
            .iter()
            .map(|img| {
                img.iter()
                    .enumerate()
                    .filter(|(i, _)| in_half(*i, half))
                    .map(|(i, &v)| v as f64 - e[i])
                    .sum()
            })
            .collect();
        let (diff, se) = sample_mean_and_se(&sums);
        let sum_exp: f64 = e
            .iter()
            .enumerate()
            .filter(|(i, _)| in_half(*i, half))
            .map(|(_, &v)| v)
            .sum();
        z_test(half, diff, se * se, sum_exp);
    }
}

#[test]
fn textured_emitter_seen_directly() {
    for (integrator, spp) in [("path", 16), ("photon", 4)] {
        eprintln!("{integrator}:");
        let l = scene(
            integrator,
            spp,
            "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]",
            false,
        );
        let out = render_loaded(&l, spp, 3, 0);
        assert_eq!(out.bad_samples, 0);
        halves(&l, &out.film, 1.0, |c, x, _| l_emit(c, x));
    }
}

/// The diffuse floor under the emitter, seen from above.
fn floor_scene(integrator: &str, spp: u32) -> LoadedScene {
    scene(
        integrator,
        spp,
        "LookAt 0 0 0.5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 60 ]",
        true,
    )
}

/// The floor's radiance (channel `c`) at (x, y): one diffuse bounce.
fn floor_radiance(c: usize, x: f64, y: f64) -> f64 {
    ALBEDO / PI as f64 * irradiance(c, x, y)
}

#[test]
fn textured_emitter_lights_a_diffuse_floor() {
    for (integrator, spp) in [("path", 64), ("photon", 16)] {
        eprintln!("{integrator}:");
        let l = floor_scene(integrator, spp);
        let out = render_loaded(&l, spp, 5, 0);
        assert_eq!(out.bad_samples, 0);
        halves(&l, &out.film, 0.0, floor_radiance);
    }
}

/// The bidirectional integrators: the floor lit by the textured emitter
/// through camera connections of light paths (splatted), light samples
/// (`bdpt`, `vcm`) and merges (`vcm`); 8 seeds.
#[test]
fn textured_emitter_lights_a_diffuse_floor_bidirectionally() {
    for (integrator, spp) in [("lighttracer", 2048), ("bdpt", 16), ("vcm", 16)] {
        eprintln!("{integrator}:");
        let l = floor_scene(integrator, spp);
        halves_over_seeds(&l, spp, 0..8, 0.0, floor_radiance);
    }
}

/// pbrt-v4 refuses `L` together with `filename`; an unreadable image is a
/// located error too.
#[test]
fn textured_emitter_input_errors() {
    let img = common::envmap::write_env("textured-emitter-err.exr", 2, 1, |_, _| {
        lumis_math::Rgb::WHITE
    });
    for (light, needle) in [
        (
            format!(
                "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"string filename\" \"{}\"",
                img.display()
            ),
            "either `L` or `filename`",
        ),
        (
            "AreaLightSource \"diffuse\" \"string filename\" \"missing.exr\"".to_string(),
            "cannot read area light image",
        ),
    ] {
        let text = format!("Camera \"perspective\"\nWorldBegin\n{light}\nShape \"sphere\"\n");
        let err = lumis_render::load::load_text(
            &text,
            "t.pbrt",
            std::path::Path::new("."),
            &Default::default(),
        )
        .err()
        .expect("an error");
        let msg = err.to_string();
        assert!(msg.contains(needle), "{msg}");
        assert!(msg.contains("t.pbrt:3:"), "located: {msg}");
    }
}
