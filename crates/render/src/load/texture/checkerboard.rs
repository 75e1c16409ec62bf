//! `checkerboard`: `tex1` and `tex2` alternating, over a 2D mapping
//! (`dimension` 2) or in the texture's space (`dimension` 3).

use super::common::{map3d, Built, TexBuilder, MAP2D};
use crate::load::Warnings;
use crate::texture::{CheckerboardTexture, Mapping2D, Texture};
use lumis_scene::{Diagnostic, TextureDesc};

pub(super) fn build(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    let e = &t.entity;
    let p = &e.params;
    let dim = p.get_int("dimension", 2)?;
    if dim != 2 && dim != 3 {
        return Err(Diagnostic::error(
            &p.loc_of("dimension").unwrap_or_else(|| e.loc.clone()),
            format!("checkerboard `dimension` must be 2 or 3, found {dim}"),
        ));
    }
    let solid = (dim == 3).then(|| map3d(t));
    let mapping = if dim == 2 {
        b.mapping(t, w)?
    } else {
        Mapping2D::Uv {
            su: 1.0,
            sv: 1.0,
            du: 0.0,
            dv: 0.0,
        }
    };
    Ok((
        Texture::Checkerboard(CheckerboardTexture {
            mapping,
            map3d: solid,
            tex1: b.value(p, "tex1", 1.0, float)?,
            tex2: b.value(p, "tex2", 0.0, float)?,
        }),
        if dim == 2 {
            [&["tex1", "tex2", "dimension"][..], &MAP2D].concat()
        } else {
            vec!["tex1", "tex2", "dimension"]
        },
    ))
}
