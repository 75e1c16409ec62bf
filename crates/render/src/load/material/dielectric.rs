//! `dielectric`: glass-like refraction with a scalar index of refraction,
//! smooth or rough (with lumis' `distribution` extension).

use super::common::{eta_param, roughness_with_distribution, Built, Ctx, ROUGH};
use crate::load::Warnings;
use crate::material::{DielectricMaterial, MaterialKind};
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    Ok((
        MaterialKind::Dielectric(DielectricMaterial {
            eta: eta_param(c.desc, c.p, "eta", 1.5, w)?,
            roughness: roughness_with_distribution(c.tex, c.p)?,
        }),
        [&["eta", "distribution"][..], &ROUGH].concat(),
    ))
}
