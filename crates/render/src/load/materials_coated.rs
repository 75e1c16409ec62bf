//! pbrt-v4's `coateddiffuse` and `coatedconductor` (layered BSDFs), with
//! pbrt-v4's parameter names and defaults.

use super::materials::{conductor_spec, eta_param, roughness, ROUGH};
use super::texture::TexBuilder;
use super::Warnings;
use crate::material::*;
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, ParamSet, SceneDesc};

/// Parameters of the coat and slab every coated material has.
const COAT: [&str; 5] = ["thickness", "albedo", "g", "maxdepth", "nsamples"];

pub fn build(
    desc: &SceneDesc,
    ty: &str,
    p: &ParamSet,
    tex: &TexBuilder,
    w: &mut Warnings,
) -> Result<(MaterialKind, Vec<&'static str>), Diagnostic> {
    Ok(if ty == "coateddiffuse" {
        let m = CoatedDiffuseMaterial {
            reflectance: tex.spectrum(p, "reflectance", Rgb::splat(0.5))?,
            coat: coat(
                tex,
                p,
                roughness(tex, p, "", 0.0)?,
                eta_param(desc, p, "eta", 1.5, w)?,
            )?,
        };
        let known = [&["reflectance", "eta"][..], &ROUGH, &COAT].concat();
        (MaterialKind::CoatedDiffuse(m), known)
    } else {
        let iface = roughness(tex, p, "interface.", 0.0)?;
        let eta = eta_param(desc, p, "interface.eta", 1.5, w)?;
        let m = CoatedConductorMaterial {
            spec: spec(tex, p)?,
            roughness: roughness(tex, p, "conductor.", 0.0)?,
            coat: coat(tex, p, iface, eta)?,
        };
        let known = [
            &[
                "interface.roughness",
                "interface.uroughness",
                "interface.vroughness",
                "interface.eta",
                "conductor.roughness",
                "conductor.uroughness",
                "conductor.vroughness",
                "conductor.eta",
                "conductor.k",
                "reflectance",
                "remaproughness",
            ][..],
            &COAT,
        ]
        .concat();
        (MaterialKind::CoatedConductor(m), known)
    })
}

fn coat(tex: &TexBuilder, p: &ParamSet, r: Roughness, eta: f32) -> Result<Coat, Diagnostic> {
    let count = |name: &str, default: i32, min: i32| -> Result<u32, Diagnostic> {
        let v = p.get_int(name, default)?;
        if v < min {
            return Err(Diagnostic::error(
                &p.loc_of(name).unwrap_or_else(lumis_scene::Loc::none),
                format!("`{name}` must be at least {min}, found {v}"),
            ));
        }
        Ok(v as u32)
    };
    Ok(Coat {
        roughness: r,
        eta,
        thickness: tex.float(p, "thickness", 0.01)?,
        albedo: tex.spectrum(p, "albedo", Rgb::BLACK)?,
        g: tex.float(p, "g", 0.0)?,
        max_depth: count("maxdepth", 10, 0)?,
        n_samples: count("nsamples", 1, 1)?,
    })
}

/// The base conductor: `reflectance`, or `conductor.eta` / `conductor.k`
/// (copper by default, spectra reduced as for `conductor`); giving both is
/// an error, as in pbrt-v4.
fn spec(tex: &TexBuilder, p: &ParamSet) -> Result<ConductorSpec, Diagnostic> {
    if p.has("reflectance") {
        if let Some(n) = ["conductor.eta", "conductor.k"].iter().find(|n| p.has(n)) {
            return Err(Diagnostic::error(
                &p.loc_of(n).unwrap_or_else(lumis_scene::Loc::none),
                "coatedconductor takes either `reflectance` or `conductor.eta`/`conductor.k`, not both",
            ));
        }
        return Ok(ConductorSpec::Reflectance(tex.spectrum(
            p,
            "reflectance",
            Rgb::WHITE,
        )?));
    }
    conductor_spec(tex, p, "conductor.")
}
