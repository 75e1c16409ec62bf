//! Two-sided transmissive materials (`thindielectric`, `diffusetransmission`)
//! through every integrator: white furnaces, analytic sheets, a caustic through
//! a thin sheet, and `photon` against `path` where light reaches a floor only
//! by diffuse transmission.

use crate::common;

use common::*;
use lumis_render::bsdf::ThinDielectric;

/// A horizontal square of half-size `h` at height `z` (normal +z).
fn quad(z: f32, h: f32) -> String {
    format!(
        r#"Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ]
  "point3 P" [ -{h} -{h} {z}  {h} -{h} {z}  {h} {h} {z}  -{h} {h} {z} ]"#
    )
}

fn check_z(label: &str, mean: f64, se: f64, expected: f64, bias: f64) {
    let z = (mean - expected).abs() / se.max(2.5e-5 * expected);
    eprintln!("{label}: mean {mean:.5} expected {expected:.5} se {se:.2e}");
    assert!(
        (mean - expected).abs() < bias * expected + 4.5 * se.max(2.5e-5 * expected),
        "{label}: mean {mean} vs {expected} ({z:.1} standard errors)"
    );
}

/// A closed lossless object in a uniform environment of radiance 1 looks
/// like the environment, whichever integrator renders it.
fn furnace(material: &str, integrator: &str, spp: u32, bias: f64, label: &str) {
    let text = white_furnace(integrator, material);
    let l = load(&text, &Default::default());
    assert!(l.warnings.is_empty(), "{label}: {:?}", l.warnings);
    let out = render_loaded(&l, spp, 7, 0);
    assert_eq!(out.bad_samples, 0, "{label}");
    let (mean, se) = mean_and_se(&out.film, None);
    check_z(label, mean, se, 1.0, bias);
    assert!(se < 0.01, "{label}: too noisy (se {se})");
}

#[test]
fn thin_dielectric_sphere_in_white_furnace() {
    let m = r#"Material "thindielectric" "float eta" [ 1.5 ]"#;
    furnace(m, "path", 16, 0.0, "thindielectric path");
    // Camera paths follow it as a delta surface: nothing else is seen.
    furnace(m, "photon", 4, 0.0, "thindielectric photon");
}

#[test]
fn diffuse_transmission_sphere_in_white_furnace() {
    let m = r#"Material "diffusetransmission" "rgb reflectance" [ 0.3 0.5 0.7 ]
  "rgb transmittance" [ 0.7 0.5 0.3 ]"#;
    furnace(m, "path", 32, 0.0, "diffusetransmission path");
    // The global map holds photons that arrived from outside and from inside
    // (the sphere's inside is lit only through it): the estimate at a point
    // must add both sides' photons, weighted by R and T. One map for the
    // whole image: a photon-map bound as in furnace.rs.
    furnace(m, "photon", 4, 0.015, "diffusetransmission photon");
}

/// A horizontal sheet lit from above by a distant light: seen from below it
/// is a Lambertian emitter of `T E / pi`, seen from above `R E / pi`, the
/// radiance of a diffuse surface of albedo `T` (or `R`) under the same light.
/// Every integrator finds it by light sampling on the sheet's back side.
#[test]
fn diffuse_transmission_sheet_seen_from_both_sides() {
    let scene = |material: &str, eye_z: f32, integrator: &str| {
        format!(
            r#"Integrator "{integrator}" "integer maxdepth" [ 5 ]
{}
LookAt 0.2 0.1 {eye_z}  0 0 0  0 1 0
Camera "perspective" "float fov" [ 20 ]
WorldBegin
LightSource "distant" "point3 from" [ 0.3 0.2 1 ] "point3 to" [ 0 0 0 ] "rgb L" [ 2 2 2 ]
{material}
{}
"#,
            header(8),
            quad(0.0, 5.0)
        )
    };
    let sheet = r#"Material "diffusetransmission" "rgb reflectance" [ 0.2 0.2 0.2 ]
  "rgb transmittance" [ 0.6 0.6 0.6 ] "float scale" [ 1.25 ]"#;
    for integrator in ["direct", "path", "photon"] {
        let mean = |text: String| {
            let l = load(&text, &Default::default());
            assert!(l.warnings.is_empty(), "{:?}", l.warnings);
            mean_and_se(&render_loaded(&l, 4, 1, 0).film, None).0
        };
        let below = mean(scene(sheet, -3.0, integrator));
        let above = mean(scene(sheet, 3.0, integrator));
        let ref_t = mean(scene(
            r#"Material "diffuse" "rgb reflectance" [ 0.75 0.75 0.75 ]"#,
            3.0,
            integrator,
        ));
        let ref_r = mean(scene(
            r#"Material "diffuse" "rgb reflectance" [ 0.25 0.25 0.25 ]"#,
            3.0,
            integrator,
        ));
        eprintln!("{integrator}: below {below:.5} (diffuse T {ref_t:.5}), above {above:.5} (diffuse R {ref_r:.5})");
        assert!(ref_t > 0.1, "{integrator}: the reference is lit");
        assert!(
            (below - ref_t).abs() < 1e-4 * ref_t,
            "{integrator}: below {below} vs {ref_t}"
        );
        assert!(
            (above - ref_r).abs() < 1e-4 * ref_r,
            "{integrator}: above {above} vs {ref_r}"
        );
    }
}

/// A spot light shines straight down through a thin glass sheet onto a
/// diffuse floor; the camera sits between sheet and floor. The floor is lit
/// only through the sheet (shadow rays stop at it), so every bit of its
/// radiance is a caustic `L S D`: `a / pi * T'(0) * I / d^2` below the light,
/// `T'(0) = 1 - 2R/(1+R)`. With no global photons, `photon` renders exactly
/// that caustic (delta light: photons only).
#[test]
fn thin_dielectric_caustic_under_a_spot_light() {
    let (i, d, a) = (3.0f64, 2.0f64, 0.5f64);
    let text = format!(
        r#"Integrator "photon" "integer maxdepth" [ 5 ] "integer photons" [ 0 ]
  "integer causticphotons" [ 1000000 ] "integer nearest" [ 200 ] "float maxradius" [ 0.05 ]
  "bool progressive" false
{}
LookAt 0 0 0.5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 4 ]
WorldBegin
LightSource "spot" "point3 from" [ 0 0 {d} ] "point3 to" [ 0 0 0 ] "rgb I" [ {i} {i} {i} ]
  "float coneangle" [ 2 ] "float conedeltaangle" [ 0.5 ]
AttributeBegin
Material "thindielectric" "float eta" [ 1.5 ]
{}
AttributeEnd
Material "diffuse" "rgb reflectance" [ {a} {a} {a} ]
{}
"#,
        header(16),
        quad(1.0, 5.0),
        quad(0.0, 5.0)
    );
    let l = load(&text, &Default::default());
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let out = render_loaded(&l, 8, 3, 0);
    let stats = out.photon_stats.expect("photon stats");
    assert!(stats.caustic_stored > 100_000, "{stats:?}");
    let (mean, se) = mean_and_se(&out.film, None);
    let t = ThinDielectric::new(1.5).split(1.0).1 as f64;
    assert!((t - (1.0 - 0.08 / 1.04)).abs() < 1e-6);
    let expected = a / std::f64::consts::PI * t * i / (d * d);
    // The camera sees a disc of radius 0.018 around the axis (inside the
    // spot's flat 1.5 degrees), where cos^3 falls by 0.01%; each estimate
    // (200 photons, radius ~1e-3) has ~7% noise, spread over the pixels.
    check_z("thin sheet caustic", mean, se, expected, 0.002);
}

/// Light reaches the floor only through a diffusely transmitting sheet, so
/// the floor's radiance is all indirect: gather rays from the floor go up
/// into the sheet's lower side, whose radiance comes from photons that
/// arrived on its upper side (and floor photons that came back up). The
/// `photon` image matches `path`.
#[test]
fn photon_matches_path_under_a_diffuse_transmission_sheet() {
    let scene = |integrator: &str| {
        format!(
            r#"Integrator "{integrator}" "integer maxdepth" [ 5 ]
{}
LookAt 0 0 1  0 0 0  0 1 0
Camera "perspective" "float fov" [ 60 ]
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
Shape "trianglemesh" "integer indices" [ 0 2 1 0 3 2 ]
  "point3 P" [ -0.5 -0.5 3  0.5 -0.5 3  0.5 0.5 3  -0.5 0.5 3 ]
AttributeEnd
AttributeBegin
Material "diffusetransmission" "rgb reflectance" [ 0.3 0.3 0.3 ]
  "rgb transmittance" [ 0.6 0.5 0.4 ]
{}
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
{}
"#,
            header(12),
            quad(2.0, 3.0),
            quad(0.0, 3.0)
        )
    };
    let render = |integrator: &str, spp: u32| {
        let l = load(&scene(integrator), &Default::default());
        assert!(l.warnings.is_empty(), "{:?}", l.warnings);
        let out = render_loaded(&l, spp, 5, 0);
        assert_eq!(out.bad_samples, 0);
        mean_and_se(&out.film, None)
    };
    let (p, p_se) = render("path", 1024);
    let (m, m_se) = render("photon", 16);
    let noise = (p_se * p_se + m_se * m_se).sqrt();
    eprintln!("path {p:.5} ± {p_se:.5}, photon {m:.5} ± {m_se:.5}");
    assert!(p > 0.01, "the floor is lit: {p}");
    assert!(
        (m - p).abs() < 0.03 * p + 4.0 * noise,
        "photon {m} vs path {p}: {:+.2}%",
        (m - p) / p * 100.0
    );
}

/// The loader: textured diffuse transmission with `scale`, a named glass
/// spectrum for `eta`, unknown parameters reported at their location, and a
/// negative `scale` refused.
#[test]
fn materials_load_with_parameters_checked() {
    use lumis_math::{Rgb, Vec3};
    use lumis_render::bsdf::{Bsdf, TransportMode};
    use lumis_render::geometry::Ray;
    use lumis_render::load::load_text;
    use std::path::Path;
    let scene = |mat: &str| {
        format!(
            r#"LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 4 "integer yresolution" 4
WorldBegin
LightSource "distant"
Texture "c" "spectrum" "scale" "rgb tex" [0.1 0.2 0.4]
  "float scale" 2
{mat}
{}
"#,
            quad(0.0, 1.0)
        )
    };
    let load = |t: &str| load_text(t, "m.pbrt", Path::new("."), &Default::default());
    let l = load(&scene(
        r#"Material "diffusetransmission" "texture transmittance" "c" "float scale" 0.5"#,
    ))
    .unwrap();
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let h = l
        .scene
        .intersect(&Ray::new(Vec3::new(-0.9, -0.9, 1.0), -Vec3::Z))
        .unwrap();
    let b = l.scene.bsdf(&h, Vec3::Z);
    let pi = lumis_math::PI;
    let t = b.eval(Vec3::Z, -Vec3::Z, TransportMode::Radiance) * pi;
    let r = b.eval(Vec3::Z, Vec3::Z, TransportMode::Radiance) * pi;
    let close = |a: Rgb, b: Rgb| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-6);
    assert!(close(t, Rgb::new(0.1, 0.2, 0.4)), "{t:?}");
    assert!(close(r, Rgb::splat(0.125)), "{r:?}");

    let l = load(&scene(
        r#"Material "thindielectric" "spectrum eta" "glass-BK7" "float roughness" 0.1"#,
    ))
    .unwrap();
    assert!(matches!(
        l.scene.bsdf(&h, Vec3::Z).bsdf,
        Bsdf::ThinDielectric(b) if (b.eta - 1.5168).abs() < 0.01
    ));
    // A named glass disperses in pbrt-v4: one index here, with a warning.
    assert_eq!(l.warnings.len(), 2, "{:?}", l.warnings);
    assert!(l.warnings[0].message.contains("dispersion is not rendered"));
    let w = &l.warnings[1];
    assert!(w.message.contains("roughness"), "{}", w.message);
    assert_eq!(w.loc.as_ref().map(|l| l.line), Some(8));

    let e = load(&scene(r#"Material "diffusetransmission" "float scale" -1"#))
        .err()
        .expect("negative scale is an error");
    assert!(e.message.contains("scale") && e.loc.is_some(), "{e:?}");
}

/// An area light above a thin glass sheet above a diffuse floor; the camera
/// sits under the sheet. The floor's light all comes through the sheet:
/// caustics `L S D` (and `L S D S D` through the sheet's reflection). Each
/// caustic mode of `photon` (the seed's MIS, photons only, gather rays
/// only) matches `path` (which finds the light by BSDF sampling through the
/// delta sheet), with one photon map and in the progressive mode.
#[test]
fn thin_sheet_caustic_modes_match_path() {
    let scene = |integrator: &str, caustics: &str| {
        format!(
            r#"Integrator "{integrator}" "integer maxdepth" [ 6 ] "string caustics" "{caustics}"
  "integer causticphotons" [ 400000 ] "bool progressive" false
{}
LookAt 0 0 1  0 0 0  0 1 0
Camera "perspective" "float fov" [ 50 ]
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]
Shape "trianglemesh" "integer indices" [ 0 2 1 0 3 2 ]
  "point3 P" [ -0.75 -0.75 3  0.75 -0.75 3  0.75 0.75 3  -0.75 0.75 3 ]
AttributeEnd
AttributeBegin
Material "thindielectric" "float eta" [ 1.5 ]
{}
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
{}
"#,
            header(12),
            quad(2.0, 3.0),
            quad(0.0, 3.0)
        )
    };
    let render = |integrator: &str, caustics: &str, spp: u32| {
        let text = scene(integrator, caustics);
        let text = if integrator == "path" {
            text.replace(r#""string caustics" "mis""#, "").replace(
                r#""integer causticphotons" [ 400000 ] "bool progressive" false"#,
                "",
            )
        } else {
            text
        };
        let l = load(&text, &Default::default());
        assert!(l.warnings.is_empty(), "{:?}", l.warnings);
        let out = render_loaded(&l, spp, 11, 0);
        assert_eq!(out.bad_samples, 0);
        mean_and_se(&out.film, None)
    };
    let (p, p_se) = render("path", "mis", 8192);
    eprintln!("path {p:.5} ± {p_se:.5}");
    assert!(p > 0.01, "the floor is lit: {p}");
    // The single map, and the progressive mode (4 iterations of 100k
    // caustic photons, each with its own maps and a shrinking radius).
    let progressive = r#""integer causticphotons" [ 400000 ] "bool progressive" false"#;
    let iterations = r#""integer causticphotons" [ 100000 ] "bool progressive" true "integer iterationspp" [ 4 ]"#;
    for (mode, prog) in ["mis", "photons", "gather"]
        .into_iter()
        .flat_map(|m| [(m, false), (m, true)])
    {
        let (m, m_se) = if prog {
            let text = scene("photon", mode).replace(progressive, iterations);
            let l = load(&text, &Default::default());
            assert!(l.warnings.is_empty(), "{:?}", l.warnings);
            let out = render_loaded(&l, 16, 11, 0);
            assert_eq!(out.bad_samples, 0);
            mean_and_se(&out.film, None)
        } else {
            render("photon", mode, 16)
        };
        let mode = if prog {
            format!("{mode} progressive")
        } else {
            mode.to_string()
        };
        let noise = (p_se * p_se + m_se * m_se).sqrt();
        eprintln!(
            "photon {mode}: {m:.5} ± {m_se:.5} ({:+.2}%)",
            (m - p) / p * 100.0
        );
        // Photon-map blur of a smooth caustic: a few percent at most.
        assert!(
            (m - p).abs() < 0.03 * p + 4.0 * noise,
            "photon {mode} {m} vs path {p}: {:+.2}%",
            (m - p) / p * 100.0
        );
    }
}
