//! pbrt-v4's layered materials: coateddiffuse, coatedconductor.

use super::materials::{conductor_spec, roughness, ROUGH};
use super::textures::TexBuilder;
use super::Warnings;
use crate::material::*;
use lumis_scene::{Diagnostic, ParamSet, SceneDesc};

type Built = Option<(MaterialKind, Vec<&'static str>)>;

pub fn build(
    _desc: &SceneDesc,
    ty: &str,
    loc: &lumis_scene::Loc,
    p: &ParamSet,
    tex: &mut TexBuilder,
    w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    Ok(Some(match ty {
        "coatedconductor" => {
            w.push(Diagnostic::warning(
                loc,
                "material `coatedconductor` is not supported yet; rendering its base as `conductor`",
            ));
            let k = MaterialKind::Conductor(ConductorMaterial {
                spec: conductor_spec(tex, p, "conductor.")?,
                roughness: roughness(tex, p, "conductor.", 0.0)?,
            });
            for q in p.unused() {
                q.mark_used();
            }
            (k, [&ROUGH[..]].concat())
        }
        _ => return Ok(None),
    }))
}
