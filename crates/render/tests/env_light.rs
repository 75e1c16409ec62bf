//! Image environment lights (`LightSource "infinite" "string filename"`):
//! a constant map is the uniform infinite light (same radiance, power and
//! furnace), power is `pi r² ∫ L dω` checked against an independent
//! quadrature, and a diffuse plane under a lumpy map renders to its
//! analytic radiance `a/pi ∫ L cos dω` (importance sampling, MIS and the
//! light's transform together).

use crate::common;

use common::envmap::*;
use common::*;
use lumis_math::sampling::square_to_uniform_sphere;
use lumis_math::{Pcg32, Rgb, Vec2, Vec3, PI};
use lumis_render::light::Light;
use std::path::Path;

fn env_scene(light: &str, world: &str, camera: &str) -> String {
    format!(
        "{}\n{camera}\nCamera \"perspective\" \"float fov\" [ 30 ]\nWorldBegin\n{light}\n{world}\n",
        header(24)
    )
}

fn image_light(path: &Path, extra: &str) -> String {
    format!(
        "LightSource \"infinite\" \"string filename\" \"{}\" {extra}",
        path.display()
    )
}

/// `∫ L dω` of a loaded scene's light 0 by Monte Carlo over uniform directions.
fn radiance_integral(light: &Light, n: usize) -> Rgb {
    let mut rng = Pcg32::new(17, 3);
    let mut sum = [0f64; 3];
    for _ in 0..n {
        let d = square_to_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
        for (c, v) in light.le(d).to_array().into_iter().enumerate() {
            sum[c] += v as f64;
        }
    }
    let k = 4.0 * std::f64::consts::PI / n as f64;
    Rgb::new(
        (sum[0] * k) as f32,
        (sum[1] * k) as f32,
        (sum[2] * k) as f32,
    )
}

#[test]
fn constant_map_is_the_uniform_light() {
    let c = Rgb::new(0.3, 0.5, 0.7);
    let square = write_env("const.exr", 8, 8, |_, _| c);
    let wide = write_env("const-ll.pfm", 16, 8, |_, _| c);
    let world = "Shape \"sphere\" \"float radius\" [ 1 ]";
    let cam = "LookAt 0 0 5  0 0 0  0 1 0";
    let uniform = load(
        &env_scene(
            "LightSource \"infinite\" \"rgb L\" [ 0.3 0.5 0.7 ]",
            world,
            cam,
        ),
        &Default::default(),
    );
    let p_uniform = uniform.scene.lights[0].power(&uniform.scene.shapes);
    for (path, label) in [(&square, "equal-area"), (&wide, "lat-long")] {
        let l = load(
            &env_scene(&image_light(path, "\"float scale\" [ 1 ]"), world, cam),
            &Default::default(),
        );
        assert!(l.warnings.is_empty(), "{label}: {:?}", l.warnings);
        let light = &l.scene.lights[0];
        assert!(matches!(light, Light::Image(_)), "{label}");
        let p = light.power(&l.scene.shapes);
        for (a, b) in p.to_array().into_iter().zip(p_uniform.to_array()) {
            assert!(
                (a / b - 1.0).abs() < 1e-5,
                "{label}: power {p:?} vs {p_uniform:?}"
            );
        }
        let mut rng = Pcg32::new(1, 1);
        for _ in 0..1000 {
            let d = square_to_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            assert_eq!(light.le(d), c, "{label}");
        }
    }
    // Illuminance: both reach it on an upward patch (E = pi L for a constant map).
    let with_e = |light: String| {
        let l = load(&env_scene(&light, world, cam), &Default::default());
        l.scene.lights[0].le(Vec3::Z)
    };
    let e_uniform = with_e(
        "LightSource \"infinite\" \"rgb L\" [ 0.3 0.5 0.7 ] \"float illuminance\" [ 10 ]".into(),
    );
    let fine = write_env("const-fine.exr", 128, 128, |_, _| c);
    let e_image = with_e(image_light(&fine, "\"float illuminance\" [ 10 ]"));
    // pbrt-v4 sets `illuminance` for the unit-luminance spectrum: an `rgb L`
    // keeps its own luminance on top (a map's luminance is divided out).
    assert!((e_uniform.luminance() * PI - 10.0 * c.luminance()).abs() < 1e-3);
    // Texel centres stand in for the cosine over each texel, which is off
    // where texels straddle the horizon: 6.7% at 8x8, 0.4% at 128x128.
    assert!(
        (e_image.luminance() * c.luminance() / e_uniform.luminance() - 1.0).abs() < 0.01,
        "{e_image:?} vs {e_uniform:?}"
    );
}

/// White diffuse, mirror and glass spheres vanish in a constant image map,
/// as in the uniform furnace (`furnace.rs`).
#[test]
fn constant_map_furnace() {
    let path = write_env("white.exr", 16, 16, |_, _| Rgb::WHITE);
    for (material, spp) in [
        ("Material \"diffuse\" \"rgb reflectance\" [ 1 1 1 ]", 32),
        ("Material \"dielectric\" \"float eta\" [ 1.5 ]", 64),
    ] {
        let text = format!(
            "Integrator \"path\" \"integer maxdepth\" [ 300 ]\n{}",
            env_scene(
                &image_light(&path, ""),
                &format!("{material}\nShape \"sphere\" \"float radius\" [ 1 ]"),
                "LookAt 0 0 5  0 0 0  0 1 0"
            )
        );
        let l = load(&text, &Default::default());
        let out = render_loaded(&l, spp, 3, 0);
        let (mean, se) = mean_and_se(&out.film, None);
        let z = (mean - 1.0) / se.max(2.5e-5);
        eprintln!("{material}: mean {mean:.5} se {se:.2e} z {z:.2}");
        assert_eq!(out.bad_samples, 0);
        assert!(z.abs() < 4.5, "{material}: mean {mean}, z {z:.1}");
    }
}

#[test]
fn power_is_pi_r2_times_the_radiance_integral() {
    for (name, w, h) in [("lumpy.exr", 32, 32), ("lumpy-ll.exr", 64, 32)] {
        let path = write_env(name, w, h, lumpy(w, h));
        let l = load(
            &env_scene(
                &image_light(&path, "\"float scale\" [ 2 ]"),
                "Shape \"sphere\" \"float radius\" [ 1 ]",
                "LookAt 0 0 5  0 0 0  0 1 0",
            ),
            &Default::default(),
        );
        let light = &l.scene.lights[0];
        let Light::Image(img) = light else {
            panic!("image light expected")
        };
        let r = img.scene_radius;
        let expected = radiance_integral(light, 4_000_000) * (PI * r * r);
        let p = light.power(&l.scene.shapes);
        for (a, b) in p.to_array().into_iter().zip(expected.to_array()) {
            // Monte Carlo error of the quadrature: ~0.2% (the bright spot).
            assert!(
                (a / b - 1.0).abs() < 0.01,
                "{name}: power {p:?} vs {expected:?}"
            );
        }
    }
}

/// A large diffuse disk facing +z under a rotated lumpy map: every point
/// sees the whole upper hemisphere, so its radiance is `a/pi ∫ L cos dω`.
#[test]
fn diffuse_plane_under_a_map_matches_its_irradiance() {
    let albedo = 0.5f32;
    for (name, w, h) in [("plane.exr", 32, 32), ("plane-ll.exr", 64, 32)] {
        let path = write_env(name, w, h, lumpy(w, h));
        let text = format!(
            "Integrator \"path\" \"integer maxdepth\" [ 1 ]\n{}",
            env_scene(
                &format!("AttributeBegin\nRotate 70 1 0.3 0\n{}\nAttributeEnd", image_light(&path, "")),
                &format!("Material \"diffuse\" \"rgb reflectance\" [ {albedo} {albedo} {albedo} ]\nShape \"disk\" \"float radius\" [ 1000 ]"),
                "LookAt 0 0 1  0 0 0  0 1 0"
            )
        );
        let l = load(&text, &Default::default());
        let light = &l.scene.lights[0];
        // Irradiance by Monte Carlo over cosine-free uniform directions.
        let mut rng = Pcg32::new(5, 5);
        let n = 4_000_000;
        let mut e = 0.0f64;
        for _ in 0..n {
            let d = square_to_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            if d.z > 0.0 {
                e += (light.le(d).luminance() * d.z) as f64;
            }
        }
        let expected =
            albedo as f64 / std::f64::consts::PI * e * 4.0 * std::f64::consts::PI / n as f64;
        let out = render_loaded(&l, 64, 9, 0);
        let vals: Vec<f64> = out
            .film
            .pixels
            .iter()
            .map(|p| p.mean_rgb().luminance() as f64)
            .collect();
        let (m, se) = sample_mean_and_se(&vals);
        let z = (m - expected) / (se.powi(2) + (0.002 * expected).powi(2)).sqrt();
        eprintln!("{name}: mean {m:.5} expected {expected:.5} se {se:.2e} z {z:.2}");
        assert_eq!(out.bad_samples, 0);
        assert!(z.abs() < 4.5, "{name}: {m} vs {expected}");
        assert!(se < 0.01 * expected, "{name}: too noisy (se {se})");
    }
}

#[test]
fn bad_maps_are_located_errors() {
    let odd = write_env("odd.exr", 30, 20, |_, _| Rgb::WHITE);
    let nan = write_env("nan.pfm", 4, 4, |x, _| {
        Rgb::splat(if x == 1 { f32::NAN } else { 1.0 })
    });
    let ok = write_env("ok.exr", 4, 4, |_, _| Rgb::WHITE);
    for (light, what) in [
        (image_light(&odd, ""), "square"),
        (image_light(&nan, ""), "NaN"),
        (
            image_light(Path::new("/nonexistent/env.exr"), ""),
            "env.exr",
        ),
        (image_light(&ok, "\"rgb L\" [ 1 1 1 ]"), "not both"),
        (image_light(&ok, "\"string mapping\" \"cube\""), "latlong"),
    ] {
        let text = env_scene(&light, "", "");
        let err = match lumis_render::load::load_text(
            &text,
            "t.pbrt",
            Path::new("."),
            &Default::default(),
        ) {
            Ok(_) => panic!("{what}: loaded"),
            Err(e) => e.to_string(),
        };
        assert!(
            err.contains(what) && err.contains("t.pbrt:7"),
            "{what}: {err}"
        );
    }
    // pbrt-v3 style: explicit lat-long takes `L` as a multiplier, any shape.
    let l = load(
        &env_scene(
            &image_light(&odd, "\"string mapping\" \"latlong\" \"rgb L\" [ 2 2 2 ]"),
            "",
            "",
        ),
        &Default::default(),
    );
    assert_eq!(l.scene.lights[0].le(Vec3::X), Rgb::splat(2.0));
}

/// Goniometric light: the image's pole is the light's +y axis (pbrt-v4's
/// swap), intensity falls off as 1/d², `power` sets the luminous power.
#[test]
fn goniometric_light_orientation_and_power() {
    use lumis_math::sampling::equal_area_square_to_sphere;
    let n = 16;
    let path = write_env("gonio.exr", n, n, |x, y| {
        let d = equal_area_square_to_sphere(Vec2::new(
            (x as f32 + 0.5) / n as f32,
            (y as f32 + 0.5) / n as f32,
        ));
        Rgb::splat(if d.z > 0.8 { 3.0 } else { 0.5 })
    });
    let text = |extra: &str| {
        env_scene(
            &format!(
                "AttributeBegin\nTranslate 0 0 1\nLightSource \"goniometric\" \"string filename\" \"{}\" \"rgb I\" [ 2 2 2 ] {extra}\nAttributeEnd",
                path.display()
            ),
            "",
            "",
        )
    };
    let l = load(&text(""), &Default::default());
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let light = &l.scene.lights[0];
    assert!(light.is_delta());
    // Seen from +y of the light (the image's pole): 2 * 3 / d².
    let s = light
        .sample_li(&l.scene.shapes, Vec3::new(0.0, 2.0, 1.0), Vec2::ZERO)
        .unwrap();
    assert!((s.li.luminance() - 6.0 / 4.0).abs() < 1e-4, "{:?}", s.li);
    assert!((s.wi - Vec3::NEG_Y).length() < 1e-6);
    // Along +z of the light: off the pole.
    let s = light
        .sample_li(&l.scene.shapes, Vec3::new(0.0, 0.0, 3.0), Vec2::ZERO)
        .unwrap();
    assert!((s.li.luminance() - 1.0 / 4.0).abs() < 1e-4, "{:?}", s.li);
    // pbrt-v4: `power` is for a unit-luminance `I`; an `rgb I` of 2 doubles it.
    let l = load(&text("\"float power\" [ 10 ]"), &Default::default());
    let p = l.scene.lights[0].power(&l.scene.shapes).luminance();
    assert!((p - 20.0).abs() < 2e-3, "power {p}");
}

/// pbrt-v3 files: `mapname` maps are latitude-longitude whatever their shape
/// (the upgrade says so with `"string mapping" "latlong"`), and v3's `L`
/// multiplies the map: the top row is the light's +z pole.
#[test]
fn pbrt_v3_mapname_is_a_latlong_map() {
    for (name, w, h) in [("v3.exr", 64, 32), ("v3-square.exr", 32, 32)] {
        let path = write_env(name, w, h, |_, y| {
            Rgb::splat(if y == 0 { 5.0 } else { 1.0 })
        });
        let l = load(
            &env_scene(
                &format!(
                    "LightSource \"infinite\" \"string mapname\" \"{}\" \"color L\" [ 2 2 2 ]",
                    path.display()
                ),
                "",
                "",
            ),
            &Default::default(),
        );
        assert!(l.warnings.is_empty(), "{name}: {:?}", l.warnings);
        let light = &l.scene.lights[0];
        assert_eq!(light.le(Vec3::Z), Rgb::splat(10.0), "{name}");
        assert_eq!(light.le(Vec3::X), Rgb::splat(2.0), "{name}");
    }
}
