//! `dots`: randomly placed polka dots (`inside`) on a background
//! (`outside`), over a 2D mapping.

use super::common::{Built, TexBuilder, MAP2D};
use crate::load::Warnings;
use crate::texture::{DotsTexture, Texture};
use lumis_scene::{Diagnostic, TextureDesc};

pub(super) fn build(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    let p = &t.entity.params;
    Ok((
        Texture::Dots(DotsTexture {
            mapping: b.mapping(t, w)?,
            inside: b.value(p, "inside", 1.0, float)?,
            outside: b.value(p, "outside", 0.0, float)?,
        }),
        [&["inside", "outside"][..], &MAP2D].concat(),
    ))
}
