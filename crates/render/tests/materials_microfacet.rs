//! Loading rough conductors and dielectrics: pbrt-v4's roughness parameters
//! and lumis' `"string distribution"` extension (Trowbridge-Reitz or
//! Beckmann), with located errors.

use crate::common;

use lumis_math::{Vec2, Vec3};
use lumis_render::bsdf::microfacet::{Microfacet, MicrofacetModel};
use lumis_render::bsdf::Bsdf;
use lumis_render::load::LoadedScene;
use lumis_render::texture::TexCtx;

use common::load_material as load;

/// The microfacet distribution of the scene's first material.
fn microfacet(l: &LoadedScene) -> Microfacet {
    let c = TexCtx::at(Vec3::ZERO, Vec3::Z, Vec2::ZERO);
    match l.scene.materials[0].bsdf(&l.scene.textures, &c) {
        Bsdf::Conductor(b) => b.distrib,
        Bsdf::Dielectric(b) => b.distrib,
        other => panic!("not a microfacet BSDF: {other:?}"),
    }
}

#[test]
fn distribution_defaults_to_trowbridge_reitz() {
    for m in [
        r#"Material "conductor" "float roughness" 0.04"#,
        r#"Material "dielectric" "float roughness" 0.04"#,
        r#"Material "conductor" "float roughness" 0.04 "string distribution" "ggx""#,
        r#"Material "dielectric" "float roughness" 0.04 "string distribution" "trowbridgereitz""#,
    ] {
        let l = load(m).unwrap();
        assert!(l.warnings.is_empty(), "{m}: {:?}", l.warnings);
        let d = microfacet(&l);
        assert_eq!(d.model, MicrofacetModel::TrowbridgeReitz, "{m}");
        // remaproughness defaults to true: alpha = sqrt(roughness).
        assert!((d.alpha_x - 0.2).abs() < 1e-6 && (d.alpha_y - 0.2).abs() < 1e-6);
    }
}

#[test]
fn beckmann_on_conductors_and_dielectrics() {
    for m in [
        r#"Material "conductor" "float uroughness" 0.01 "float vroughness" 0.05
           "bool remaproughness" false "string distribution" "beckmann""#,
        r#"Material "dielectric" "float uroughness" 0.01 "float vroughness" 0.05
           "bool remaproughness" false "string distribution" "beckmann""#,
    ] {
        let l = load(m).unwrap();
        assert!(l.warnings.is_empty(), "{m}: {:?}", l.warnings);
        let d = microfacet(&l);
        assert_eq!(d, Microfacet::beckmann(0.01, 0.05), "{m}");
    }
}

#[test]
fn unknown_distribution_is_a_located_error() {
    let e = load(r#"Material "conductor" "string distribution" "blinn""#)
        .err()
        .unwrap();
    assert!(
        e.contains("s.pbrt:5:") && e.contains("`blinn`") && e.contains("beckmann"),
        "{e}"
    );
}

#[test]
fn distribution_elsewhere_is_an_unknown_parameter() {
    // Only conductors and dielectrics take it: the layered coats stay
    // pbrt-v4's Trowbridge-Reitz, and say so.
    let l = load(r#"Material "coateddiffuse" "string distribution" "beckmann""#).unwrap();
    assert!(
        l.warnings
            .iter()
            .any(|w| w.message.contains("distribution")),
        "{:?}",
        l.warnings
    );
}
