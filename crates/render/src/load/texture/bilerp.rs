//! `bilerp`: bilinear interpolation of four corner values over a 2D mapping.

use super::common::{Built, TexBuilder, MAP2D};
use crate::load::spectrum::rgb_param;
use crate::load::Warnings;
use crate::texture::{BilerpTexture, Texture};
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, ParamSet, TextureDesc};

pub(super) fn build(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    let p = &t.entity.params;
    let v = |name: &str, default: f32| corner(b, p, name, default, float);
    Ok((
        Texture::Bilerp(BilerpTexture {
            mapping: b.mapping(t, w)?,
            v00: v("v00", 0.0)?,
            v01: v("v01", 1.0)?,
            v10: v("v10", 0.0)?,
            v11: v("v11", 1.0)?,
        }),
        [&["v00", "v01", "v10", "v11"][..], &MAP2D].concat(),
    ))
}

/// A corner: a float, or (for spectrum textures) a spectrum value.
fn corner(
    b: &TexBuilder,
    p: &ParamSet,
    name: &str,
    default: f32,
    float: bool,
) -> Result<Rgb, Diagnostic> {
    if float || p.param(name).is_some_and(|q| q.ty == "float") {
        return Ok(Rgb::splat(p.get_float(name, default)?));
    }
    Ok(rgb_param(b.desc(), p, name)?.unwrap_or(Rgb::splat(default)))
}
