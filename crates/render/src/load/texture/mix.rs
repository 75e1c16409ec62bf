//! `mix`: `tex1` and `tex2` blended by a float `amount`.

use super::common::{Built, TexBuilder};
use crate::load::Warnings;
use crate::texture::{MixTexture, Texture};
use lumis_scene::{Diagnostic, TextureDesc};

pub(super) fn build(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    _w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    let p = &t.entity.params;
    Ok((
        Texture::Mix(MixTexture {
            tex1: b.value(p, "tex1", 0.0, float)?,
            tex2: b.value(p, "tex2", 1.0, float)?,
            amount: b.float_rgb(p, "amount", 0.5)?,
        }),
        vec!["tex1", "tex2", "amount"],
    ))
}
