//! pbrt-v4's `coateddiffuse`: a diffuse base under a dielectric coat (a
//! layered BSDF).

use super::coat::{coat, COAT};
use super::common::{eta_param, roughness, Built, Ctx, ROUGH};
use crate::load::Warnings;
use crate::material::{CoatedDiffuseMaterial, MaterialKind};
use lumis_math::Rgb;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    let (tex, p) = (c.tex, c.p);
    let m = CoatedDiffuseMaterial {
        reflectance: tex.spectrum(p, "reflectance", Rgb::splat(0.5))?,
        coat: coat(
            tex,
            p,
            roughness(tex, p, "", 0.0)?,
            eta_param(c.desc, p, "eta", 1.5, w)?,
        )?,
    };
    let known = [&["reflectance", "eta"][..], &ROUGH, &COAT].concat();
    Ok((MaterialKind::CoatedDiffuse(m), known))
}
