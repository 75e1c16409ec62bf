//! `mix`: two named materials (defined before this one) blended by `amount`.

use super::common::{Built, Ctx};
use crate::load::Warnings;
use crate::material::{MaterialKind, MixMaterial};
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, _w: &mut Warnings) -> Result<Built, Diagnostic> {
    let p = c.p;
    let loc = p
        .loc_of("materials")
        .unwrap_or_else(|| c.m.entity.loc.clone());
    let names = match p.param("materials").map(|q| &q.value) {
        Some(lumis_scene::params::Value::Strings(s)) if s.len() == 2 => s.clone(),
        _ => {
            return Err(Diagnostic::error(
                &loc,
                "mix material needs `string materials` with exactly two material names",
            ))
        }
    };
    p.mark_used("materials");
    let mut ids = [0u32; 2];
    for (k, n) in names.iter().enumerate() {
        let Some(&i) = c.desc.named_materials.get(n) else {
            return Err(Diagnostic::error(&loc, format!("no material named `{n}`")));
        };
        if i as usize >= c.index {
            return Err(Diagnostic::error(
                &loc,
                format!("material `{n}` must be defined before the mix that uses it"),
            ));
        }
        ids[k] = i;
    }
    Ok((
        MaterialKind::Mix(MixMaterial {
            materials: ids,
            amount: c.tex.float(p, "amount", 0.5)?,
        }),
        vec!["materials", "amount"],
    ))
}
