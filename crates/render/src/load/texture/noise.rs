//! pbrt-v4's solid noise textures, in the texture's own space: `fbm`,
//! `wrinkled`, `windy` and `marble`. Each has its `build` here; a new noise
//! texture reading `octaves` belongs here too.

use super::common::{map3d, Built, TexBuilder};
use crate::load::Warnings;
use crate::texture::{FbmTexture, MarbleTexture, Texture, WindyTexture, WrinkledTexture};
use lumis_scene::{Diagnostic, TextureDesc};

/// `octaves`: 0 to 64.
fn octaves(t: &TextureDesc) -> Result<u32, Diagnostic> {
    let p = &t.entity.params;
    let n = p.get_int("octaves", 8)?;
    if !(0..=64).contains(&n) {
        return Err(Diagnostic::error(
            &p.loc_of("octaves").unwrap_or_else(|| t.entity.loc.clone()),
            format!("`octaves` must be between 0 and 64, found {n}"),
        ));
    }
    Ok(n as u32)
}

pub(super) fn fbm(
    _b: &mut TexBuilder,
    t: &TextureDesc,
    _float: bool,
    _w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    Ok((
        Texture::Fbm(FbmTexture {
            mapping: map3d(t),
            octaves: octaves(t)?,
            omega: t.entity.params.get_float("roughness", 0.5)?,
        }),
        vec!["octaves", "roughness"],
    ))
}

pub(super) fn wrinkled(
    _b: &mut TexBuilder,
    t: &TextureDesc,
    _float: bool,
    _w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    Ok((
        Texture::Wrinkled(WrinkledTexture {
            mapping: map3d(t),
            octaves: octaves(t)?,
            omega: t.entity.params.get_float("roughness", 0.5)?,
        }),
        vec!["octaves", "roughness"],
    ))
}

pub(super) fn windy(
    _b: &mut TexBuilder,
    t: &TextureDesc,
    _float: bool,
    _w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    Ok((Texture::Windy(WindyTexture { mapping: map3d(t) }), vec![]))
}

pub(super) fn marble(
    _b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    let p = &t.entity.params;
    if float {
        w.push(Diagnostic::warning(
            &t.entity.loc,
            "`marble` is a spectrum texture in pbrt-v4; as a float texture its red channel is used",
        ));
    }
    Ok((
        Texture::Marble(MarbleTexture {
            mapping: map3d(t),
            octaves: octaves(t)?,
            omega: p.get_float("roughness", 0.5)?,
            scale: p.get_float("scale", 1.0)?,
            variation: p.get_float("variation", 0.2)?,
        }),
        vec!["octaves", "roughness", "scale", "variation"],
    ))
}
