//! `scale`: `tex` times a float `scale`.

use super::common::{Built, TexBuilder};
use crate::load::Warnings;
use crate::texture::{ScaleTexture, Texture};
use lumis_scene::{Diagnostic, TextureDesc};

pub(super) fn build(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    _w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    let p = &t.entity.params;
    Ok((
        Texture::Scale(ScaleTexture {
            tex: b.value(p, "tex", 1.0, float)?,
            scale: b.float_rgb(p, "scale", 1.0)?,
        }),
        vec!["tex", "scale"],
    ))
}
