//! Textures through the loader: a scene's `Texture` directives become
//! textures that materials evaluate at hits; bad texture input is an error.

use lumis_math::{Rgb, Vec2, Vec3};
use lumis_render::bsdf::TransportMode;
use lumis_render::geometry::Ray;
use lumis_render::load::{load_text, Overrides};

/// A unit square in z = 0 (uv = xy), seen from above, with material `mat`.
fn scene(textures: &str, mat: &str, dir: &std::path::Path) -> String {
    let _ = dir;
    format!(
        r#"LookAt 0.5 0.5 5  0.5 0.5 0  0 1 0
Camera "perspective" "float fov" 10
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
LightSource "distant" "point3 from" [0 0 1] "point3 to" [0 0 0]
{textures}
{mat}
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 1 1 0 0 1 0] "integer indices" [0 1 2 0 2 3]
    "point2 uv" [0 0 1 0 1 1 0 1]
"#
    )
}

/// Diffuse reflectance at (x, y) of the square: pi * f.
fn reflectance(text: &str, dir: &std::path::Path, x: f32, y: f32) -> Rgb {
    let l = load_text(text, "t.pbrt", dir, &Overrides::default()).unwrap();
    let msgs: Vec<_> = l.warnings.iter().map(|d| &d.message).collect();
    assert!(msgs.is_empty(), "unexpected warnings: {msgs:?}");
    let s = &l.scene;
    let r = Ray::new(Vec3::new(x, y, 1.0), Vec3::new(0.0, 0.0, -1.0));
    let h = s.intersect(&r).unwrap();
    let b = s.bsdf(&h, Vec3::Z);
    b.eval(Vec3::Z, Vec3::Z, TransportMode::Radiance) * lumis_math::PI
}

fn tmpdir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("lumis-texload-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn imagemap_scale_checkerboard_mix() {
    let dir = tmpdir("a");
    // 2x1 TGA, linear: left red, right blue (bottom-up, one row).
    let mut tga = vec![0u8; 18];
    tga[2] = 2;
    tga[12] = 2;
    tga[14] = 1;
    tga[16] = 24;
    tga.extend_from_slice(&[0, 0, 255, 255, 0, 0]);
    std::fs::write(dir.join("t.tga"), &tga).unwrap();
    let tex = r#"Texture "img" "spectrum" "imagemap" "string filename" "t.tga"
    "string encoding" "linear" "string filter" "point" "string wrap" "clamp"
Texture "half" "spectrum" "scale" "texture tex" "img" "float scale" 0.5
Texture "amt" "float" "checkerboard" "float uscale" 2 "float vscale" 2
Texture "m" "spectrum" "mix" "texture tex1" "half" "rgb tex2" [0 1 0] "texture amount" "amt""#;
    let text = scene(tex, r#"Material "diffuse" "texture reflectance" "m""#, &dir);
    // Checker square (0,0) has tex1 = 1 -> amount 1 -> green.
    let c = reflectance(&text, &dir, 0.25, 0.25);
    assert!(
        (c - Rgb::new(0.0, 1.0, 0.0)).max_component().abs() < 1e-4,
        "{c:?}"
    );
    // Square (1,0): amount 0 -> half of the image: the right texel is blue.
    let c = reflectance(&text, &dir, 0.75, 0.25);
    assert!(
        (c - Rgb::new(0.0, 0.0, 0.5)).max_component().abs() < 1e-4,
        "{c:?}"
    );
    let c = reflectance(&text, &dir, 0.25, 0.75);
    assert!(
        (c - Rgb::new(0.5, 0.0, 0.0)).max_component().abs() < 1e-4,
        "{c:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_texture_input_is_an_error_with_location() {
    let dir = tmpdir("b");
    let cases = [
        r#"Material "diffuse" "texture reflectance" "nope""#,
        r#"Texture "i" "spectrum" "imagemap" "string filename" "missing.png"
Material "diffuse" "texture reflectance" "i""#,
        r#"Texture "i" "spectrum" "imagemap" "string filename" "x.png" "string wrap" "mirror""#,
    ];
    for c in cases {
        let text = scene(c, "", &dir);
        let e = load_text(&text, "t.pbrt", &dir, &Overrides::default())
            .err()
            .unwrap_or_else(|| panic!("no error for {c}"));
        assert!(e.loc.is_some(), "{}", e.message);
    }
    let _ = Vec2::ZERO;
    std::fs::remove_dir_all(&dir).ok();
}
