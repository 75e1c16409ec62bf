//! pbrt-v4's layered materials: coateddiffuse, coatedconductor.

use super::texture::TexBuilder;
use super::Warnings;
use crate::material::*;
use lumis_scene::{Diagnostic, ParamSet, SceneDesc};

type Built = Option<(MaterialKind, Vec<&'static str>)>;

pub fn build(
    desc: &SceneDesc,
    ty: &str,
    _loc: &lumis_scene::Loc,
    p: &ParamSet,
    tex: &mut TexBuilder,
    w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    Ok(Some(match ty {
        "coateddiffuse" | "coatedconductor" => super::materials_coated::build(desc, ty, p, tex, w)?,
        _ => return Ok(None),
    }))
}
