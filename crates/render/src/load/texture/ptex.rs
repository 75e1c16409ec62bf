//! `ptex`: not read (lumis has no Ptex reader); a located warning and a
//! constant 0.5.

use super::common::{Built, TexBuilder};
use crate::load::Warnings;
use crate::texture::Texture;
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, TextureDesc};

pub(super) fn build(
    _b: &mut TexBuilder,
    t: &TextureDesc,
    _float: bool,
    w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    let p = &t.entity.params;
    let file = p.get_string("filename", "")?;
    w.push(Diagnostic::warning(
        &p.loc_of("filename").unwrap_or_else(|| t.entity.loc.clone()),
        format!("ptex textures are not supported (no Ptex reader): `{file}` is rendered as a constant 0.5"),
    ));
    p.mark_used("encoding");
    p.mark_used("scale");
    Ok((Texture::Constant(Rgb::splat(0.5)), vec!["filename"]))
}
