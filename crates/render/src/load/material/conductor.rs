//! `conductor`: a metal from `eta`/`k` (copper by default) or `reflectance`,
//! smooth or rough (with lumis' `distribution` extension).

use super::common::{conductor_spec, roughness_with_distribution, Built, Ctx, ROUGH};
use crate::load::Warnings;
use crate::material::{ConductorMaterial, MaterialKind};
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, _w: &mut Warnings) -> Result<Built, Diagnostic> {
    Ok((
        MaterialKind::Conductor(ConductorMaterial {
            spec: conductor_spec(c.tex, c.p, "")?,
            roughness: roughness_with_distribution(c.tex, c.p)?,
        }),
        [&["eta", "k", "reflectance", "distribution"][..], &ROUGH].concat(),
    ))
}
