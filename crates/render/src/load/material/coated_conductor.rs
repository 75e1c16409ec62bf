//! pbrt-v4's `coatedconductor`: a conductor base (`conductor.*`) under a
//! dielectric coat (`interface.*`), a layered BSDF.

use super::coat::{coat, COAT};
use super::common::{conductor_spec, eta_param, roughness, Built, Ctx};
use crate::load::texture::TexBuilder;
use crate::load::Warnings;
use crate::material::{CoatedConductorMaterial, ConductorSpec, MaterialKind};
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, ParamSet};

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    let (tex, p) = (c.tex, c.p);
    let iface = roughness(tex, p, "interface.", 0.0)?;
    let eta = eta_param(c.desc, p, "interface.eta", 1.5, w)?;
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
    Ok((MaterialKind::CoatedConductor(m), known))
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
