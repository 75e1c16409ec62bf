//! `constant`: one value everywhere (`value`, which may itself name a texture).

use super::common::{Built, TexBuilder};
use crate::load::Warnings;
use crate::texture::{TexRgb, Texture};
use lumis_scene::{Diagnostic, TextureDesc};

pub(super) fn build(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    _w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    let p = &t.entity.params;
    Ok(match b.value(p, "value", 1.0, float)? {
        TexRgb::Const(c) => (Texture::Constant(c), vec!["value"]),
        TexRgb::Tex(id) => {
            // A copy of the named texture; its other parameters are not reported.
            for q in p.unused() {
                q.mark_used();
            }
            (b.textures.textures[id as usize], vec![])
        }
    })
}
