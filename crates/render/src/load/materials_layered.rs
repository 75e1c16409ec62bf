//! pbrt-v4 materials beyond the basic ones: coateddiffuse, coatedconductor,
//! thindielectric, diffusetransmission.

use super::materials::{conductor_spec, eta_param, roughness, ROUGH};
use super::textures::TexBuilder;
use super::Warnings;
use crate::material::*;
use lumis_scene::{Diagnostic, ParamSet, SceneDesc};

type Built = Option<(MaterialKind, Vec<&'static str>)>;

pub fn build(
    desc: &SceneDesc,
    ty: &str,
    loc: &lumis_scene::Loc,
    p: &ParamSet,
    tex: &mut TexBuilder,
    w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    Ok(Some(match ty {
        "thindielectric" => {
            w.push(Diagnostic::warning(
                loc,
                "material `thindielectric` is not supported yet; using `dielectric`",
            ));
            (
                MaterialKind::Dielectric(DielectricMaterial {
                    eta: eta_param(desc, p, "eta", 1.5, w)?,
                    roughness: Roughness::SMOOTH,
                }),
                vec!["eta"],
            )
        }
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
