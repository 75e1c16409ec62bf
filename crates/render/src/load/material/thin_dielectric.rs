//! `thindielectric`: a two-sided thin slab of glass (reflection and
//! straight-through transmission).

use super::common::{eta_param, Built, Ctx};
use crate::load::Warnings;
use crate::material::{MaterialKind, ThinDielectricMaterial};
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    Ok((
        MaterialKind::ThinDielectric(ThinDielectricMaterial {
            eta: eta_param(c.desc, c.p, "eta", 1.5, w)?,
        }),
        vec!["eta"],
    ))
}
