//! `directionmix`: `tex1` and `tex2` blended by the shading normal's
//! alignment with `dir` (given in the texture's space).

use super::common::{Built, TexBuilder};
use crate::load::Warnings;
use crate::texture::{DirectionMixTexture, Texture};
use lumis_math::Vec3;
use lumis_scene::{Diagnostic, TextureDesc};

pub(super) fn build(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    _w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    let p = &t.entity.params;
    let d = t.object_to_world.vector(p.get_vector3("dir", Vec3::Y)?);
    Ok((
        Texture::DirectionMix(DirectionMixTexture {
            tex1: b.value(p, "tex1", 0.0, float)?,
            tex2: b.value(p, "tex2", 1.0, float)?,
            dir: d.normalize_or_zero(),
        }),
        vec!["tex1", "tex2", "dir"],
    ))
}
