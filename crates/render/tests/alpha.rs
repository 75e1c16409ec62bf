//! Shape `alpha` cutouts (pbrt-v4): constant and textured, for camera rays,
//! shadow rays and photons.

use crate::common;

use common::{header, load, render_loaded};
use lumis_render::load::Overrides;

/// A 16x16 view of a two-sided emitter (L = 1) behind a black quad that
/// fills the view, with `alpha` on the quad (and `extra` scene lines).
fn cutout_scene(alpha: &str, extra: &str) -> String {
    format!(
        r#"Integrator "path" "integer maxdepth" [ 5 ]
{}
LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 20 ]
WorldBegin
{extra}
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  Shape "trianglemesh" "point3 P" [ -9 -9 -2  9 -9 -2  9 9 -2  -9 9 -2 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0 0 0 ]
Shape "trianglemesh" "point3 P" [ -2 -2 0  2 -2 0  2 2 0  -2 2 0 ] "point2 uv" [ 0 0 1 0 1 1 0 1 ]
  "integer indices" [ 0 1 2 0 2 3 ] {alpha}
"#,
        header(16)
    )
}

fn mean(text: &str, spp: u32) -> f64 {
    let l = load(text, &Overrides::default());
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let img = render_loaded(&l, spp, 1, 0).film.mean_image();
    img.iter().map(|&v| v as f64).sum::<f64>() / img.len() as f64
}

#[test]
fn constant_alpha_lets_that_fraction_of_rays_through() {
    assert!(mean(&cutout_scene("", ""), 4) < 1e-6);
    assert!((mean(&cutout_scene(r#""float alpha" 0"#, ""), 4) - 1.0).abs() < 1e-5);
    // alpha 0.3: 70% of camera rays pass (a hash per ray); 16x16x64 rays.
    let n = (16 * 16 * 64) as f64;
    let m = mean(&cutout_scene(r#""float alpha" 0.3"#, ""), 64);
    let se = (0.21f64 / n).sqrt();
    assert!(((m - 0.7) / se).abs() < 4.5, "{m} (se {se})");
}

#[test]
fn textured_alpha_cuts_the_texture_out() {
    // A 4x4 checkerboard of alpha 0 and 1 over the quad: half of the quad.
    let tex = r#"Texture "cut" "float" "checkerboard" "float tex1" 0 "float tex2" 1 "float uscale" 4 "float vscale" 4"#;
    let l = load(
        &cutout_scene(r#""texture alpha" "cut""#, tex),
        &Overrides::default(),
    );
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let img = render_loaded(&l, 16, 1, 0).film.mean_image();
    let lit = img.chunks(3).filter(|p| p[0] > 0.99).count();
    let dark = img.chunks(3).filter(|p| p[0] < 0.01).count();
    // The quad fills the view (fov 20 at distance 5 sees 1.76 across): a
    // checker square spans ~9 pixels, so most pixels are wholly one or the other.
    assert!(lit > 80 && dark > 80, "lit {lit}, dark {dark}");
}

/// A floor lit by a small area light through an occluder that `alpha`
/// removes; by `integrator`.
fn shadow_scene(integrator: &str, occluder: &str) -> String {
    format!(
        r#"Integrator "{integrator}" "integer maxdepth" [ 5 ]
{}
LookAt 0 4 4  0 0 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 20 20 20 ]
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  Shape "trianglemesh" "point3 P" [ -0.3 3 -0.3  0.3 3 -0.3  0.3 3 0.3  -0.3 3 0.3 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -3 0 -3  -3 0 3  3 0 3  3 0 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
{occluder}
"#,
        header(16)
    )
}

#[test]
fn shadow_rays_and_photons_pass_cutouts() {
    let occluder = |alpha: &str| {
        format!(
            r#"Material "diffuse" "rgb reflectance" [ 0 0 0 ]
Shape "trianglemesh" "point3 P" [ -2 1.5 -2  2 1.5 -2  2 1.5 2  -2 1.5 2 ] "integer indices" [ 0 1 2 0 2 3 ] {alpha}"#
        )
    };
    for integrator in ["path", "photon"] {
        let open = mean(&shadow_scene(integrator, ""), 16);
        let cut = mean(
            &shadow_scene(integrator, &occluder(r#""float alpha" 0"#)),
            16,
        );
        let shut = mean(&shadow_scene(integrator, &occluder("")), 16);
        eprintln!("{integrator}: open {open}, cut out {cut}, shut {shut}");
        assert!(
            shut < 0.5 * open,
            "{integrator}: the black occluder hides the floor"
        );
        assert!(
            (cut / open - 1.0).abs() < 1e-3,
            "{integrator}: {cut} vs {open}"
        );
    }
}

#[test]
fn negative_alpha_is_a_located_error() {
    let e = match lumis_render::load::load_text(
        &cutout_scene(r#""float alpha" -0.5"#, ""),
        "a.pbrt",
        std::path::Path::new("."),
        &Overrides::default(),
    ) {
        Ok(_) => panic!("alpha -0.5 loaded"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("a.pbrt:16:") && e.contains("[0, 1]"), "{e}");
}

#[test]
fn alpha_on_an_emitter_is_ignored_with_a_warning() {
    let text = cutout_scene("", "").replace(
        r#"Shape "trianglemesh" "point3 P" [ -9 -9 -2"#,
        r#"Shape "trianglemesh" "float alpha" 0 "point3 P" [ -9 -9 -2"#,
    );
    let l = lumis_render::load::load_text(
        &text,
        "e.pbrt",
        std::path::Path::new("."),
        &Overrides::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(l.warnings.len(), 1, "{:?}", l.warnings);
    let w = l.warnings[0].to_string();
    assert!(w.contains("e.pbrt:12:") && w.contains("emitting"), "{w}");
    assert!(!l.scene.has_alpha);
}
