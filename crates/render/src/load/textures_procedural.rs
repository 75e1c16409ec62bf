//! pbrt-v4's pattern and procedural textures from `Texture` descriptions:
//! `checkerboard` (2D or 3D), `bilerp`, `dots` (2D mappings), `fbm`,
//! `wrinkled`, `windy`, `marble` (3D: the texture's own space), and `ptex`
//! (not read: a located warning).

use super::spectrum::rgb_param;
use super::textures::TexBuilder;
use super::Warnings;
use crate::texture::*;
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, ParamSet, TextureDesc};

/// Parameter names of the 2D mappings.
pub const MAP2D: [&str; 7] = [
    "mapping", "uscale", "vscale", "udelta", "vdelta", "v1", "v2",
];

/// The texture of type `ty` with its known parameters, or `None` when `ty`
/// is not one of this file's.
pub fn build(
    b: &TexBuilder,
    t: &TextureDesc,
    float: bool,
    w: &mut Warnings,
) -> Result<Option<(Texture, Vec<&'static str>)>, Diagnostic> {
    let e = &t.entity;
    let p = &e.params;
    let map3d = || Mapping3D {
        tex_from_world: t.object_to_world.inverse(),
    };
    let octaves = || -> Result<u32, Diagnostic> {
        let n = p.get_int("octaves", 8)?;
        if !(0..=64).contains(&n) {
            return Err(Diagnostic::error(
                &p.loc_of("octaves").unwrap_or_else(|| e.loc.clone()),
                format!("`octaves` must be between 0 and 64, found {n}"),
            ));
        }
        Ok(n as u32)
    };
    Ok(Some(match e.ty.as_str() {
        "bilerp" => {
            let v = |name: &str, default: f32| corner(b, p, name, default, float);
            (
                Texture::Bilerp(BilerpTexture {
                    mapping: b.mapping(t, w)?,
                    v00: v("v00", 0.0)?,
                    v01: v("v01", 1.0)?,
                    v10: v("v10", 0.0)?,
                    v11: v("v11", 1.0)?,
                }),
                [&["v00", "v01", "v10", "v11"][..], &MAP2D].concat(),
            )
        }
        "checkerboard" => {
            let dim = p.get_int("dimension", 2)?;
            if dim != 2 && dim != 3 {
                return Err(Diagnostic::error(
                    &p.loc_of("dimension").unwrap_or_else(|| e.loc.clone()),
                    format!("checkerboard `dimension` must be 2 or 3, found {dim}"),
                ));
            }
            let map3d = (dim == 3).then(|| Mapping3D {
                tex_from_world: t.object_to_world.inverse(),
            });
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
            (
                Texture::Checkerboard(CheckerboardTexture {
                    mapping,
                    map3d,
                    tex1: b.value(p, "tex1", 1.0, float)?,
                    tex2: b.value(p, "tex2", 0.0, float)?,
                }),
                if dim == 2 {
                    [&["tex1", "tex2", "dimension"][..], &MAP2D].concat()
                } else {
                    vec!["tex1", "tex2", "dimension"]
                },
            )
        }
        "dots" => (
            Texture::Dots(DotsTexture {
                mapping: b.mapping(t, w)?,
                inside: b.value(p, "inside", 1.0, float)?,
                outside: b.value(p, "outside", 0.0, float)?,
            }),
            [&["inside", "outside"][..], &MAP2D].concat(),
        ),
        "fbm" => (
            Texture::Fbm(FbmTexture {
                mapping: map3d(),
                octaves: octaves()?,
                omega: p.get_float("roughness", 0.5)?,
            }),
            vec!["octaves", "roughness"],
        ),
        "wrinkled" => (
            Texture::Wrinkled(WrinkledTexture {
                mapping: map3d(),
                octaves: octaves()?,
                omega: p.get_float("roughness", 0.5)?,
            }),
            vec!["octaves", "roughness"],
        ),
        "windy" => (Texture::Windy(WindyTexture { mapping: map3d() }), vec![]),
        "marble" => {
            if float {
                w.push(Diagnostic::warning(
                    &e.loc,
                    "`marble` is a spectrum texture in pbrt-v4; as a float texture its red channel is used",
                ));
            }
            (
                Texture::Marble(MarbleTexture {
                    mapping: map3d(),
                    octaves: octaves()?,
                    omega: p.get_float("roughness", 0.5)?,
                    scale: p.get_float("scale", 1.0)?,
                    variation: p.get_float("variation", 0.2)?,
                }),
                vec!["octaves", "roughness", "scale", "variation"],
            )
        }
        "ptex" => {
            let file = p.get_string("filename", "")?;
            w.push(Diagnostic::warning(
                &p.loc_of("filename").unwrap_or_else(|| e.loc.clone()),
                format!("ptex textures are not supported (no Ptex reader): `{file}` is rendered as a constant 0.5"),
            ));
            p.mark_used("encoding");
            p.mark_used("scale");
            (Texture::Constant(Rgb::splat(0.5)), vec!["filename"])
        }
        _ => return Ok(None),
    }))
}

/// A bilerp corner: a float, or (for spectrum textures) a spectrum value.
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
