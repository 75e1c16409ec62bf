//! pbrt-v4's procedural textures (and the 3D checkerboard) through the
//! loader: a tiny scene using each (float and spectrum variants) loads
//! without a warning and renders;
//! values seen through a material match the texture's definition; bad or
//! unknown parameters are reported at their location; `ptex` is a located
//! warning.

use crate::common;

use common::*;
use lumis_math::{Rgb, Vec3};
use lumis_render::bsdf::TransportMode;
use lumis_render::geometry::Ray;
use lumis_render::load::{load_text, LoadedScene};
use std::path::Path;

/// A unit square in z = 0 (uv = xy), lit from above, with `body` before it.
fn scene(body: &str) -> String {
    format!(
        r#"LookAt 0.5 0.5 3  0.5 0.5 0  0 1 0
Camera "perspective" "float fov" 30
Sampler "independent" "integer pixelsamples" 2
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
WorldBegin
LightSource "distant" "point3 from" [0 0 1] "point3 to" [0 0 0]
{body}
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 1 1 0 0 1 0] "integer indices" [0 1 2 0 2 3]
    "point2 uv" [0 0 1 0 1 1 0 1]
"#
    )
}

fn try_load(body: &str) -> Result<LoadedScene, lumis_scene::Diagnostic> {
    load_text(&scene(body), "p.pbrt", Path::new("."), &Default::default())
}

/// Reflectance (pi f) of the square at (x, y).
fn reflectance(l: &LoadedScene, x: f32, y: f32) -> Rgb {
    let s = &l.scene;
    let h = s
        .intersect(&Ray::new(Vec3::new(x, y, 1.0), -Vec3::Z))
        .unwrap();
    s.bsdf(&h, Vec3::Z)
        .eval(Vec3::Z, Vec3::Z, TransportMode::Radiance)
        * lumis_math::PI
}

#[test]
fn every_procedural_texture_loads_and_renders() {
    let textures = [
        r#"Texture "t" "float" "bilerp" "float v00" 0.1 "float v01" 0.2 "float v10" 0.3 "float v11" 0.4"#,
        r#"Texture "t" "spectrum" "bilerp" "rgb v00" [1 0 0] "rgb v11" [0 0 1] "float uscale" 2"#,
        r#"Texture "t" "float" "dots" "float inside" 0.8 "float outside" 0.1 "float uscale" 8 "float vscale" 8"#,
        r#"Texture "t" "spectrum" "dots" "rgb inside" [0.9 0.1 0.1] "rgb outside" [0.1 0.1 0.9] "string mapping" "planar" "vector3 v1" [8 0 0] "vector3 v2" [0 8 0]"#,
        r#"Texture "t" "float" "fbm" "integer octaves" 6 "float roughness" 0.6"#,
        r#"Texture "t" "spectrum" "fbm""#,
        r#"Texture "t" "float" "wrinkled" "integer octaves" 4 "float roughness" 0.4"#,
        r#"Texture "t" "float" "windy""#,
        r#"Texture "t" "spectrum" "checkerboard" "integer dimension" 3 "rgb tex1" [0.8 0.8 0.8]"#,
        r#"Texture "t" "spectrum" "marble" "float scale" 4 "float variation" 0.5 "integer octaves" 6 "float roughness" 0.5"#,
    ];
    for tex in textures {
        let body = format!(
            "AttributeBegin\nScale 0.2 0.2 0.2\n{tex}\nAttributeEnd\nMaterial \"diffuse\" \"texture reflectance\" \"t\""
        );
        let l = try_load(&body).unwrap_or_else(|e| panic!("{tex}: {e}"));
        let msgs: Vec<_> = l.warnings.iter().map(|d| &d.message).collect();
        assert!(msgs.is_empty(), "{tex}: {msgs:?}");
        let out = render_loaded(&l, 2, 1, 0);
        assert_eq!(out.bad_samples, 0, "{tex}");
        let mean = image_mean(&out.film, None);
        // The texture varies over the square.
        let vals: Vec<f64> = image_means(&out.film)
            .iter()
            .map(|m| (m[0] + m[1] + m[2]) / 3.0)
            .collect();
        let spread = vals.iter().cloned().fold(f64::MIN, f64::max)
            - vals.iter().cloned().fold(f64::MAX, f64::min);
        eprintln!("{tex}: mean {mean:.4}, spread {spread:.4}");
        assert!(mean.is_finite() && spread > 1e-3, "{tex}: flat image");
    }
}

#[test]
fn values_through_a_material() {
    // bilerp over uv: corners and centre by hand.
    let l = try_load(
        r#"Texture "t" "spectrum" "bilerp" "rgb v00" [0.2 0 0] "rgb v10" [0 0.4 0] "rgb v01" [0 0 0.6] "rgb v11" [0.2 0.2 0.2]
Material "diffuse" "texture reflectance" "t""#,
    )
    .unwrap();
    let close = |a: Rgb, b: Rgb| (0..3).all(|k| (a[k] - b[k]).abs() < 2e-3);
    let c = reflectance(&l, 0.002, 0.002);
    assert!(close(c, Rgb::new(0.2, 0.0, 0.0)), "{c:?}");
    let c = reflectance(&l, 0.5, 0.5);
    assert!(close(c, Rgb::new(0.1, 0.15, 0.2)), "{c:?}");
    // dots with a huge dot scale: outside everywhere but the dot at the origin cell
    // when noise puts one there; a constant inside texture shows through exactly.
    let l = try_load(
        r#"Texture "d" "spectrum" "dots" "rgb inside" [0.7 0.7 0.7] "rgb outside" [0.3 0.3 0.3] "float uscale" 0.01 "float vscale" 0.01 "float udelta" 3 "float vdelta" 5
Material "diffuse" "texture reflectance" "d""#,
    )
    .unwrap();
    let inside = lumis_render::texture::noise::noise2(3.0 + 0.5, 5.0 + 0.5) > 0.0;
    let c = reflectance(&l, 0.5, 0.5);
    assert!(
        close(c, Rgb::splat(if inside { 0.7 } else { 0.3 })),
        "{c:?}"
    );
}

#[test]
fn parameters_are_checked_with_locations() {
    let l = try_load(
        r#"Texture "f" "float" "fbm" "float octave" 3
Texture "m" "float" "marble"
Texture "p" "spectrum" "ptex" "string filename" "face.ptx" "float scale" 2
Material "diffuse" "texture reflectance" "p""#,
    )
    .unwrap();
    let lines: Vec<(u32, &str)> = l
        .warnings
        .iter()
        .map(|d| (d.loc.as_ref().map_or(0, |l| l.line), d.message.as_str()))
        .collect();
    assert_eq!(lines.len(), 3, "{lines:?}");
    assert!(
        lines[0].0 == 7 && lines[0].1.contains("octave"),
        "{lines:?}"
    );
    assert!(
        lines[1].0 == 8 && lines[1].1.contains("marble"),
        "{lines:?}"
    );
    assert!(lines[2].0 == 9 && lines[2].1.contains("ptex"), "{lines:?}");
    let e = try_load(r#"Texture "f" "float" "wrinkled" "integer octaves" -2"#)
        .err()
        .expect("negative octaves is an error");
    assert!(e.loc.is_some() && e.message.contains("octaves"), "{e:?}");
}
