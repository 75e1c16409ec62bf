//! Loading pbrt-v4 media: types, presets, interfaces on shapes and the
//! camera, and located errors and warnings for what is wrong or missing.

use lumis_render::load::{load_text, Overrides};
use lumis_render::media::MediumKind;
use std::path::Path;

/// A scene whose world starts at line 4 with `world`.
fn scene(options: &str, world: &str) -> String {
    format!("Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\n{options}\nCamera \"perspective\"\nWorldBegin\n{world}\nLightSource \"point\" \"rgb I\" [1 1 1]\n")
}

fn load(text: &str) -> Result<lumis_render::load::LoadedScene, String> {
    load_text(text, "m.pbrt", Path::new("."), &Overrides::default()).map_err(|e| e.to_string())
}

/// The error loading `text` gives.
fn error(text: &str) -> String {
    match load(text) {
        Ok(_) => panic!("loaded without an error:\n{text}"),
        Err(e) => e,
    }
}

#[test]
fn homogeneous_presets_scale_and_interfaces() {
    let l = load(&scene(
        r#"MakeNamedMedium "milk" "string type" "homogeneous" "string preset" "Wholemilk" "float scale" 10 "float g" 0.3
MediumInterface "" "milk""#,
        r#"MediumInterface "milk" ""
Material "dielectric"
Shape "sphere"
Shape "disk""#,
    ))
    .unwrap();
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let s = &l.scene;
    assert_eq!(s.media.len(), 1);
    assert_eq!(s.camera_medium, Some(0));
    let MediumKind::Homogeneous(h) = &s.media[0].kind else {
        panic!("{:?}", s.media[0]);
    };
    // pbrt-v4's Wholemilk: sigma_s (2.55, 3.21, 3.77), sigma_a (0.0011, 0.0024, 0.014), per mm.
    assert!(
        (h.sigma_s.r - 25.5).abs() < 1e-4 && (h.sigma_a.b - 0.14).abs() < 1e-6,
        "{h:?}"
    );
    // The sphere changes the medium, the disk (same interface, one side
    // each) too; their dielectric is one material with the interface.
    let with_media: Vec<_> = s.materials.iter().filter(|m| m.media.is_some()).collect();
    assert_eq!(with_media.len(), 1);
    let mi = with_media[0].media.unwrap();
    assert_eq!((mi.inside, mi.outside), (Some(0), None));
}

#[test]
fn grids_are_checked_against_their_resolution() {
    let e = error(&scene(
        "",
        r#"MakeNamedMedium "smoke" "string type" "uniformgrid"
  "integer nx" 2 "integer ny" 2 "integer nz" 2 "float density" [ 1 2 3 ]"#,
    ));
    assert!(
        e.contains("m.pbrt:6:") && e.contains("expected nx*ny*nz = 2*2*2 = 8"),
        "{e}"
    );
    let e = error(&scene(
        "",
        r#"MakeNamedMedium "smoke" "string type" "uniformgrid""#,
    ));
    assert!(e.contains("m.pbrt:5:") && e.contains("density"), "{e}");
    let e = error(&scene(
        "",
        r#"MakeNamedMedium "c" "string type" "rgbgrid" "rgb Le" [ 1 1 1 ] "rgb sigma_s" [ 1 1 1 ]"#,
    ));
    assert!(e.contains("sigma_a"), "{e}");
    let e = error(&scene(
        "",
        r#"MakeNamedMedium "s" "string type" "uniformgrid" "float density" [ 1 ] "point3 p0" [ 0 0 0 ] "point3 p1" [ 1 0 1 ]"#,
    ));
    assert!(e.contains("p1 > p0"), "{e}");
    let e = error(&scene(
        "",
        r#"MakeNamedMedium "s" "string type" "uniformgrid" "float density" [ 1 ] "float temperature" [ 1000 ] "rgb Le" [ 1 1 1 ]"#,
    ));
    assert!(e.contains("both"), "{e}");
}

#[test]
fn undefined_and_unknown_media_are_located_errors() {
    let e = error(&scene(
        r#"MakeNamedMedium "fog" "string type" "homogeneous""#,
        r#"MediumInterface "fgo" ""
Shape "sphere""#,
    ));
    assert!(
        e.contains("m.pbrt:5:17")
            && e.contains("medium `fgo` is not defined")
            && e.contains("`fog`"),
        "{e}"
    );
    let e = error(&scene(
        r#"MakeNamedMedium "fog" "string type" "homogenous""#,
        "",
    ));
    assert!(
        e.contains("unknown medium type") && e.contains("homogeneous"),
        "{e}"
    );
    let e = error(&scene(
        r#"MakeNamedMedium "fog" "string type" "homogeneous" "float g" 1"#,
        "",
    ));
    assert!(e.contains("(-1, 1)"), "{e}");
    let e = error(&scene(
        r#"MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ -1 0 0 ]"#,
        "",
    ));
    assert!(e.contains("non-negative"), "{e}");
}

#[test]
fn stand_ins_unknown_presets_and_other_integrators_warn() {
    let l = load(&scene(
        "",
        r#"MakeNamedMedium "a" "string type" "nanovdb" "string filename" "smoke.nvdb"
MakeNamedMedium "b" "string type" "cloud" "float density" 2
MakeNamedMedium "c" "string type" "homogeneous" "string preset" "Wholemlk""#,
    ))
    .unwrap();
    let w: Vec<String> = l.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(
        w[0].contains("m.pbrt:5:") && w[0].contains("NanoVDB") && w[0].contains("homogeneous"),
        "{w:?}"
    );
    assert!(
        w[1].contains("m.pbrt:7:") && w[1].contains("Wholemilk"),
        "{w:?}"
    );
    // The cloud (line 6) is pbrt-v4's procedural one, not a stand-in.
    assert!(matches!(l.scene.media[1].kind, MediumKind::Cloud(_)));
    // Integrators other than `path` leave media out, and say so where the
    // integrator is chosen.
    let l = load(&scene(
        r#"Integrator "bdpt""#,
        r#"MakeNamedMedium "a" "string type" "homogeneous"
MediumInterface "a" ""
Material "interface"
Shape "sphere""#,
    ))
    .unwrap();
    assert!(l.scene.media.is_empty());
    assert_eq!(l.warnings.len(), 1, "{:?}", l.warnings);
    let w = l.warnings[0].to_string();
    assert!(
        w.contains("m.pbrt:2:") && w.contains("`path` and `photon` do"),
        "{w}"
    );
}

#[test]
fn the_media_scenes_load_without_warnings() {
    for name in ["fog-glass", "tea"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenes/media")
            .join(format!("{name}.pbrt"));
        let l = lumis_render::load::load_path(&path, &Overrides::default()).unwrap();
        assert!(l.warnings.is_empty(), "{name}: {:?}", l.warnings);
        assert_eq!(l.scene.media.len(), 1, "{name}");
        assert!(
            l.scene.materials.iter().any(|m| m.media.is_some()),
            "{name}"
        );
    }
}
