//! Loading pbrt-v4's `coateddiffuse` and `coatedconductor`: parameter names,
//! defaults, the coat-relative conductor constants and located errors.

use crate::common;

use lumis_math::{Rgb, Vec2, Vec3};
use lumis_render::bsdf::layered::Base;
use lumis_render::bsdf::Bsdf;
use lumis_render::load::LoadedScene;
use lumis_render::material::MaterialKind;
use lumis_render::texture::TexCtx;

use common::load_material as load;

/// The layered BSDF of the scene's first material.
fn layered(l: &LoadedScene) -> lumis_render::bsdf::Layered {
    let m = &l.scene.materials[0];
    assert!(matches!(
        m.kind,
        MaterialKind::CoatedDiffuse(_) | MaterialKind::CoatedConductor(_)
    ));
    let c = TexCtx::at(Vec3::ZERO, Vec3::Z, Vec2::ZERO);
    match m.bsdf(&l.scene.textures, &c) {
        Bsdf::Layered(b) => b,
        other => panic!("not layered: {other:?}"),
    }
}

#[test]
fn coateddiffuse_defaults_and_parameters() {
    let l = load(r#"Material "coateddiffuse""#).unwrap();
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let b = layered(&l);
    assert_eq!((b.top.eta, b.thickness, b.g), (1.5, 0.01, 0.0));
    assert_eq!((b.max_depth, b.n_samples), (10, 1));
    assert!(b.albedo.is_black() && b.top.is_delta());
    assert_eq!(
        b.bottom,
        Base::Diffuse(lumis_render::bsdf::Diffuse::new(Rgb::splat(0.5)))
    );

    let l = load(
        r#"Material "coateddiffuse" "rgb reflectance" [0.2 0.3 0.4] "float roughness" 0.04
        "float eta" 1.33 "float thickness" 0.2 "rgb albedo" [0.5 0.5 0.5] "float g" 0.4
        "integer maxdepth" 5 "integer nsamples" 4"#,
    )
    .unwrap();
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let b = layered(&l);
    // remaproughness defaults to true: alpha = sqrt(roughness).
    assert!((b.top.distrib.alpha_x - 0.2).abs() < 1e-6);
    assert_eq!(
        (b.top.eta, b.thickness, b.g, b.max_depth, b.n_samples),
        (1.33, 0.2, 0.4, 5, 4)
    );
    assert_eq!(b.albedo, Rgb::splat(0.5));
}

#[test]
fn coatedconductor_constants_are_relative_to_the_coat() {
    let l = load(
        r#"Material "coatedconductor" "rgb conductor.eta" [0.3 0.6 1.2] "rgb conductor.k" [3 2.4 2]
        "float interface.eta" 1.5 "float conductor.roughness" 0.09 "float interface.roughness" 0"#,
    )
    .unwrap();
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let b = layered(&l);
    let Base::Conductor(c) = b.bottom else {
        panic!("{:?}", b.bottom)
    };
    assert!(
        (c.eta - Rgb::new(0.2, 0.4, 0.8))
            .map(f32::abs)
            .max_component()
            < 1e-6
    );
    assert!(
        (c.k - Rgb::new(2.0, 1.6, 4.0 / 3.0))
            .map(f32::abs)
            .max_component()
            < 1e-6
    );
    assert!((c.distrib.alpha_x - 0.3).abs() < 1e-6 && b.top.is_delta());
    // `reflectance` (not `conductor.reflectance`) as in pbrt-v4.
    let l = load(r#"Material "coatedconductor" "rgb reflectance" [0.9 0.9 0.9]"#).unwrap();
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
}

#[test]
fn coated_errors_are_located() {
    let e = load(
        r#"Material "coatedconductor" "rgb reflectance" [0.9 0.9 0.9] "rgb conductor.eta" [1 1 1]"#,
    )
    .err()
    .unwrap();
    assert!(e.contains("s.pbrt:5:") && e.contains("not both"), "{e}");
    let e = load(r#"Material "coateddiffuse" "integer nsamples" 0"#)
        .err()
        .unwrap();
    assert!(
        e.contains("s.pbrt:5:") && e.contains("`nsamples` must be at least 1"),
        "{e}"
    );
    let l = load(r#"Material "coateddiffuse" "float thicknes" 0.1"#).unwrap();
    assert!(l.warnings.iter().any(|w| w.message.contains("thicknes")));
}
