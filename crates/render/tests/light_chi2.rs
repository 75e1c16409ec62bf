//! Chi-square tests of every light with a sampling density: the directions
//! `sample_li` returns from a reference point against `pdf_li`, and the
//! emitted directions of `sample_le` against their density.

use crate::common;

use common::chi2::{self, sidak_alpha, Chi2Config};
use common::envmap::{lumpy, write_env};
use common::*;
use lumis_math::{Frame, Vec3};
use lumis_render::geometry::Ray;
use lumis_render::light::Light;
use lumis_render::load::LoadedScene;

const TESTS: usize = 23;

fn scene(shape: &str, two_sided: bool) -> LoadedScene {
    let text = format!(
        r#"Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
Camera "perspective"
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 1 2 3 ] "bool twosided" {two_sided}
{shape}
AttributeEnd
"#
    );
    load(&text, &Default::default())
}

/// Density of `sample_li` for direction `wi` from `p`: found by tracing to the light.
fn pdf_li(l: &LoadedScene, light: u32, p: Vec3, wi: Vec3) -> f32 {
    let Some(hit) = l.scene.intersect(&Ray::new(p, wi)) else {
        return 0.0;
    };
    if hit.light != Some(light) {
        return 0.0;
    }
    l.scene.lights[light as usize].pdf_li(&l.scene.shapes, p, wi, hit.geom.p, hit.geom.ng)
}

fn check_li(l: &LoadedScene, p: Vec3, label: &str) {
    check_li_breaks(l, p, label, Vec::new())
}

/// [`check_li`] with outline curves along constant `cos theta` declared.
fn check_li_breaks(l: &LoadedScene, p: Vec3, label: &str, z_breaks: Vec<f64>) {
    // Light outlines are curves across the bins: 30x30 quadrature points per bin
    // keep the integration error of edge bins below the test's resolution.
    let cfg = Chi2Config {
        samples: 400_000,
        quad_points: 30,
        z_breaks,
        ..Default::default()
    };
    for (i, light) in l.scene.lights.iter().enumerate() {
        let out = chi2::run(
            &cfg,
            |u, _| light.sample_li(&l.scene.shapes, p, u).map(|s| s.wi),
            |wi| pdf_li(l, i as u32, p, wi),
        );
        assert!(
            out.passes(sidak_alpha(0.01, TESTS)),
            "{label} light {i}: {}",
            out.report()
        );
        assert!(
            out.sampled_fraction > 0.999,
            "{label}: samples failed: {}",
            out.report()
        );
    }
}

#[test]
fn triangle_lights() {
    let l = scene(
        r#"Shape "trianglemesh" "point3 P" [ -1 -1 2  1 -1 2.5  1 1 2  -1 1 1.5 ] "integer indices" [ 0 1 2 0 2 3 ]"#,
        true,
    );
    assert_eq!(l.scene.lights.len(), 2);
    check_li(&l, Vec3::new(0.2, -0.1, 0.0), "triangle");
}

#[test]
fn disk_light() {
    let l = scene(
        r#"Translate 0.3 0 2 Rotate 30 1 0 0 Shape "disk" "float radius" [ 1.5 ] "float innerradius" [ 0.4 ]"#,
        true,
    );
    check_li(&l, Vec3::new(0.0, 0.0, 0.0), "disk");
}

#[test]
fn sphere_light_from_outside_and_inside() {
    let l = scene(
        r#"Translate 0 0 3 Shape "sphere" "float radius" [ 1.2 ]"#,
        false,
    );
    check_li(&l, Vec3::new(0.1, 0.2, 0.0), "sphere outside (cone)");
    let l = scene(r#"Shape "sphere" "float radius" [ 2 ]"#, true);
    check_li(&l, Vec3::new(0.3, -0.4, 0.5), "sphere inside (area)");
}

#[test]
fn partial_sphere_and_cylinder_lights() {
    // Reference points from which every direction meets the surface at most
    // once (the chi-square compares against the density at the first hit).
    let l = scene(
        r#"Translate 0 0 1 Shape "sphere" "float radius" [ 1.5 ] "float zmin" [ -0.5 ] "float zmax" [ 1.2 ] "float phimax" [ 250 ]"#,
        true,
    );
    check_li(&l, Vec3::new(0.1, 0.2, 1.1), "partial sphere, inside");
    let l = scene(
        r#"Shape "sphere" "float radius" [ 1 ] "float zmin" [ 0.6 ]"#,
        false,
    );
    // Seen from the axis, the cap's rim (z = 0.6) is a circle of constant
    // cos theta = -2.4 / |(0.8, 0, -2.4)|.
    let rim = -2.4 / (0.64f64 + 5.76).sqrt();
    check_li_breaks(
        &l,
        Vec3::new(0.0, 0.0, 3.0),
        "spherical cap, outside",
        vec![rim],
    );
    let l = scene(
        r#"Rotate 20 1 0 0 Shape "cylinder" "float radius" [ 0.8 ] "float zmin" [ -1 ] "float zmax" [ 2 ] "float phimax" [ 300 ]"#,
        true,
    );
    check_li(&l, Vec3::new(0.1, -0.2, 0.3), "cylinder, inside");
}

#[test]
fn uniform_infinite_light() {
    let l = load(
        "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\nShape \"sphere\" \"float radius\" [ 0.01 ]\n",
        &Default::default(),
    );
    let light = &l.scene.lights[0];
    let p = Vec3::new(5.0, 0.0, 0.0);
    let out = chi2::run(
        &Chi2Config {
            samples: 400_000,
            ..Default::default()
        },
        |u, _| light.sample_li(&l.scene.shapes, p, u).map(|s| s.wi),
        |wi| light.pdf_li(&l.scene.shapes, p, wi, Vec3::ZERO, Vec3::ZERO),
    );
    assert!(out.passes(sidak_alpha(0.01, TESTS)), "{}", out.report());
}

/// Emitted directions: cosine-weighted about the normal (doubled for two-sided lights).
#[test]
fn area_emission_directions() {
    for two_sided in [false, true] {
        let l = scene(
            r#"Shape "trianglemesh" "point3 P" [ -1 -1 2  1 -1 2  0 1 2 ] "integer indices" [ 0 1 2 ]"#,
            two_sided,
        );
        let Light::Area(a) = &l.scene.lights[0] else {
            panic!("area light expected")
        };
        let n = lumis_render::geometry::sample::sample_area(
            &l.scene.shapes,
            a.prim,
            lumis_math::Vec2::splat(0.3),
        )
        .n;
        let out = chi2::run(
            &Chi2Config {
                samples: 400_000,
                ..Default::default()
            },
            |u, uc| {
                l.scene.lights[0]
                    .sample_le(&l.scene.shapes, lumis_math::Vec2::new(uc, 0.5), u)
                    .map(|s| s.ray.d)
            },
            |d| {
                let c = d.dot(n);
                if two_sided {
                    c.abs() / (2.0 * lumis_math::PI)
                } else {
                    c.max(0.0) / lumis_math::PI
                }
            },
        );
        assert!(
            out.passes(sidak_alpha(0.01, TESTS)),
            "two-sided {two_sided}: {}",
            out.report()
        );
        // Densities reported by sample_le agree with the distribution tested.
        let s = l.scene.lights[0]
            .sample_le(
                &l.scene.shapes,
                lumis_math::Vec2::new(0.2, 0.7),
                lumis_math::Vec2::new(0.4, 0.1),
            )
            .unwrap();
        let expected = s.ray.d.dot(s.n).abs() / lumis_math::PI / if two_sided { 2.0 } else { 1.0 };
        assert!((s.pdf_dir - expected).abs() < 1e-4 * expected.max(1.0));
        assert!(
            (s.pdf_pos - 1.0 / 2.0).abs() < 1e-5,
            "triangle area 2: pdf_pos {}",
            s.pdf_pos
        );
    }
}

/// Spot light photons: uniform in the outer cone.
#[test]
fn spot_emission_directions() {
    let l = load(
        "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\nLightSource \"spot\" \"point3 from\" [ 0 0 0 ] \"point3 to\" [ 1 1 0 ] \"float coneangle\" [ 35 ] \"float conedeltaangle\" [ 10 ]\n",
        &Default::default(),
    );
    let axis = Vec3::new(1.0, 1.0, 0.0).normalize();
    let cos_max = 35f32.to_radians().cos();
    let frame = Frame::from_normal(axis);
    let mut cfg = Chi2Config {
        samples: 400_000,
        ..Default::default()
    };
    cfg.z_breaks = vec![cos_max as f64];
    let out = chi2::run(
        &cfg,
        |u, _| {
            l.scene.lights[0]
                .sample_le(&l.scene.shapes, u, u)
                .map(|s| frame.to_local(s.ray.d))
        },
        |d| {
            if d.z >= cos_max {
                lumis_math::sampling::uniform_cone_pdf(cos_max)
            } else {
                0.0
            }
        },
    );
    assert!(out.passes(sidak_alpha(0.01, TESTS)), "{}", out.report());
}

/// Lights are chosen in proportion to their power.
#[test]
fn light_choice_is_proportional_to_power() {
    let l = load(
        r#"Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
Camera "perspective"
WorldBegin
LightSource "point" "rgb I" [ 1 1 1 ]
LightSource "point" "rgb I" [ 3 3 3 ] "point3 from" [ 1 0 0 ]
AreaLightSource "diffuse" "rgb L" [ 2 2 2 ]
Shape "sphere" "float radius" [ 0.5 ]
"#,
        &Default::default(),
    );
    let powers: Vec<f64> = l
        .scene
        .lights
        .iter()
        .map(|x| x.power(&l.scene.shapes).luminance() as f64)
        .collect();
    let total: f64 = powers.iter().sum();
    let n = 300_000;
    let mut counts = vec![0f64; powers.len()];
    let mut rng = lumis_math::Pcg32::new(4, 4);
    for _ in 0..n {
        let (i, pmf) = l.scene.light_sampler.sample(rng.next_f32()).unwrap();
        assert!((pmf as f64 - powers[i as usize] / total).abs() < 1e-5);
        counts[i as usize] += 1.0;
    }
    let expected: Vec<f64> = powers.iter().map(|p| p / total * n as f64).collect();
    let (c2, dof) = chi2::pearson(&counts, &expected, 5.0);
    let p = chi2::chi2_sf(c2, dof);
    assert!(p > sidak_alpha(0.01, TESTS), "chi2 {c2} dof {dof} p {p}");
}

/// Image environment lights: `sample_li` against `pdf_li` (importance by
/// luminance through the equal-area and lat-long Jacobians, under a rotation
/// and a reflection), and photon emission directions against the same density.
#[test]
fn image_infinite_lights() {
    let square = write_env("chi2-ea.exr", 24, 24, lumpy(24, 24));
    let wide = write_env("chi2-ll.exr", 48, 24, lumpy(48, 24));
    for (path, xf, label) in [
        (&square, "Rotate 40 1 2 0", "equal-area"),
        (&wide, "Scale -1 1 1 Rotate 20 0 1 1", "lat-long"),
    ] {
        let l = load(
            &format!(
                "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\n{xf}\nLightSource \"infinite\" \"string filename\" \"{}\"\n",
                path.display()
            ),
            &Default::default(),
        );
        let light = &l.scene.lights[0];
        assert!(matches!(light, Light::Image(_)));
        let p = Vec3::new(0.3, 0.1, -0.2);
        // Texel outlines are curves across the bins, as for area lights.
        let cfg = Chi2Config {
            samples: 400_000,
            quad_points: 30,
            ..Default::default()
        };
        let pdf = |wi: Vec3| light.pdf_li(&l.scene.shapes, p, wi, Vec3::ZERO, Vec3::ZERO);
        let out = chi2::run(
            &cfg,
            |u, _| light.sample_li(&l.scene.shapes, p, u).map(|s| s.wi),
            pdf,
        );
        assert!(
            out.passes(sidak_alpha(0.01, TESTS)),
            "{label} li: {}",
            out.report()
        );
        assert!(out.sampled_fraction > 0.999, "{label}: {}", out.report());
        // Emission: the direction of travel is the reverse of an incident one.
        let out = chi2::run(
            &cfg,
            |u, uc| {
                light
                    .sample_le(&l.scene.shapes, u, lumis_math::Vec2::new(uc, 0.5))
                    .map(|s| s.ray.d)
            },
            |d| pdf(-d),
        );
        assert!(
            out.passes(sidak_alpha(0.01, TESTS)),
            "{label} le: {}",
            out.report()
        );
        let s = light
            .sample_le(
                &l.scene.shapes,
                lumis_math::Vec2::new(0.2, 0.7),
                lumis_math::Vec2::new(0.4, 0.1),
            )
            .unwrap();
        assert!((s.pdf_dir / pdf(-s.ray.d) - 1.0).abs() < 1e-3, "{label}");
    }
}

/// Goniometric light photons: directions by importance over its image.
#[test]
fn goniometric_emission_directions() {
    let img = write_env("chi2-gonio.exr", 16, 16, lumpy(16, 16));
    let l = load(
        &format!(
            "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\nTranslate 1 2 3 Rotate 30 1 0 1\nLightSource \"goniometric\" \"string filename\" \"{}\"\n",
            img.display()
        ),
        &Default::default(),
    );
    let Light::Goniometric(g) = &l.scene.lights[0] else {
        panic!("goniometric light expected")
    };
    let out = chi2::run(
        &Chi2Config {
            samples: 400_000,
            quad_points: 30,
            ..Default::default()
        },
        |u, _| {
            l.scene.lights[0]
                .sample_le(&l.scene.shapes, u, u)
                .map(|s| s.ray.d)
        },
        |d| g.pdf_dir(d),
    );
    assert!(out.passes(sidak_alpha(0.01, TESTS)), "{}", out.report());
}

/// A 4x2 test image for textured emitters: strong contrast, no exact zeros.
fn emitter_image(name: &str) -> std::path::PathBuf {
    write_env(name, 4, 2, |x, y| {
        let v = [[0.2, 3.0, 0.5, 8.0], [1.0, 0.1, 6.0, 0.3]][y as usize][x as usize];
        lumis_math::Rgb::new(v, 0.5 * v + 0.1, 0.2)
    })
}

/// Textured area lights: `sample_li` (points by the image's luminance over
/// each primitive's area-preserving square) against `pdf_li` (the density
/// at the hit point, found through the inverse map), on every shape type.
#[test]
fn textured_area_lights() {
    let img = emitter_image("chi2-emit.exr");
    let f = img.display();
    let cases = [
        (
            r#"Shape "trianglemesh" "point3 P" [ -1 -1 2  1 -1 2.5  1 1 2  -1 1 1.5 ] "integer indices" [ 0 1 2 0 2 3 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]"#.to_string(),
            Vec3::new(0.2, -0.1, 0.0),
            "quad with uv",
        ),
        (
            r#"Shape "trianglemesh" "point3 P" [ -1 -1 2  1 -1 2.5  0 1 2 ] "integer indices" [ 0 1 2 ]"#.to_string(),
            Vec3::new(0.2, -0.1, 0.0),
            "triangle without uv",
        ),
        (
            r#"Translate 0.3 0 2 Rotate 30 1 0 0 Shape "disk" "float radius" [ 1.5 ] "float innerradius" [ 0.4 ]"#.to_string(),
            Vec3::ZERO,
            "disk",
        ),
        (
            r#"Rotate 30 1 1 0 Shape "sphere" "float radius" [ 2 ]"#.to_string(),
            Vec3::new(0.3, -0.4, 0.5),
            "sphere, inside",
        ),
        (
            r#"Rotate 20 1 0 0 Shape "cylinder" "float radius" [ 0.8 ] "float zmin" [ -1 ] "float zmax" [ 2 ] "float phimax" [ 300 ]"#.to_string(),
            Vec3::new(0.1, -0.2, 0.3),
            "cylinder, inside",
        ),
    ];
    for (shape, p, label) in cases {
        let text = format!(
            r#"Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
Camera "perspective"
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "string filename" "{f}" "bool twosided" true
{shape}
AttributeEnd
"#
        );
        let l = load(&text, &Default::default());
        assert!(l.warnings.is_empty(), "{label}: {:?}", l.warnings);
        assert!(l
            .scene
            .lights
            .iter()
            .all(|x| matches!(x, Light::Area(a) if a.texture.is_some())));
        check_li(&l, p, label);
    }
}

/// Photon origins of a textured light: `sample_le`'s position density is
/// the one `pdf_li` uses (the same sampler), and its radiance is the image's.
#[test]
fn textured_area_emission_densities() {
    let img = emitter_image("chi2-emit-le.exr");
    let l = load(
        &format!(
            r#"Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
Camera "perspective"
WorldBegin
AreaLightSource "diffuse" "string filename" "{}" "float scale" [ 3 ] "bool twosided" true
Shape "trianglemesh" "point3 P" [ -1 -1 2  1 -1 2  1 1 2  -1 1 2 ] "integer indices" [ 0 1 2 0 2 3 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]
"#,
            img.display()
        ),
        &Default::default(),
    );
    let mut rng = lumis_math::Pcg32::new(2, 9);
    for light in &l.scene.lights {
        let Light::Area(a) = light else {
            panic!("area light expected")
        };
        for _ in 0..1000 {
            let u1 = lumis_math::Vec2::new(rng.next_f32(), rng.next_f32());
            let u2 = lumis_math::Vec2::new(rng.next_f32(), rng.next_f32());
            let s = light.sample_le(&l.scene.shapes, u1, u2).unwrap();
            let p = s.ray.o;
            let pdf = a.pdf_pos(&l.scene.shapes, p);
            assert!(
                (s.pdf_pos / pdf - 1.0).abs() < 1e-3,
                "{} vs {pdf}",
                s.pdf_pos
            );
            // The radiance of the sampled point, seen from below, is the image's.
            let hit = l
                .scene
                .intersect(&Ray::new(Vec3::new(p.x, p.y, 0.0), Vec3::Z))
                .unwrap();
            let le = light.l(hit.geom.ng, hit.geom.uv, -Vec3::Z);
            assert!((le - s.le).map(f32::abs).max_component() < 1e-3 * le.max_component());
        }
    }
}
