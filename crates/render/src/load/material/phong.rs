//! `phong`: lumis' Phong material (diffuse `Kd` plus a Phong lobe `Ks` of
//! `exponent`), for scenes converted from renderers that have one.

use super::common::{Built, Ctx};
use crate::load::Warnings;
use crate::material::{MaterialKind, PhongMaterial};
use lumis_math::Rgb;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, _w: &mut Warnings) -> Result<Built, Diagnostic> {
    let p = c.p;
    let n = p.get_float("exponent", 10.0)?;
    if !(n >= 0.0) {
        return Err(Diagnostic::error(
            &p.loc_of("exponent").unwrap_or(c.m.entity.loc.clone()),
            "phong exponent must be >= 0",
        ));
    }
    Ok((
        MaterialKind::Phong(PhongMaterial {
            kd: c.tex.spectrum(p, "Kd", Rgb::splat(0.5))?,
            ks: c.tex.spectrum(p, "Ks", Rgb::splat(0.0))?,
            exponent: n,
        }),
        vec!["Kd", "Ks", "exponent"],
    ))
}
