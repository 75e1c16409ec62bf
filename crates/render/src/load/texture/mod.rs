//! Textures from `Texture` descriptions, one file per pbrt-v4 texture type
//! (the solid noise textures share [`noise`]), named as the runtime's
//! [`crate::texture`] modules. This module builds the textures in order and
//! dispatches on the type name; [`common`] holds [`TexBuilder`] (the table
//! under construction, its image cache, and the texture-or-value parameter
//! readers materials use too) and the mapping parameters.
//!
//! To add a texture type: a file here whose `build(&mut TexBuilder,
//! &TextureDesc, float, &mut Warnings)` returns its [`Texture`] and the
//! names of the parameters it reads, and one line in [`build_texture`]'s
//! match.

mod bilerp;
mod checkerboard;
mod common;
mod constant;
mod directionmix;
mod dots;
mod imagemap;
mod mix;
mod noise;
mod ptex;
mod scale;

pub use common::TexBuilder;

use super::Warnings;
use crate::texture::Texture;
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, SceneDesc, TextureDesc};

/// Builds every texture of the description, in order (a texture may use earlier ones).
pub fn build_textures<'a>(
    desc: &'a SceneDesc,
    w: &mut Warnings,
) -> Result<TexBuilder<'a>, Diagnostic> {
    let mut b = TexBuilder::new(desc);
    for t in &desc.textures {
        let float = t.kind == "float";
        let tex = build_texture(&mut b, t, float, w)?;
        b.push(t, float, tex);
    }
    Ok(b)
}

/// Texture `t` (a float texture if `float`, else a spectrum texture).
fn build_texture(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    w: &mut Warnings,
) -> Result<Texture, Diagnostic> {
    let e = &t.entity;
    let p = &e.params;
    let (tex, known) = match e.ty.as_str() {
        "constant" => constant::build(b, t, float, w)?,
        "scale" => scale::build(b, t, float, w)?,
        "mix" => mix::build(b, t, float, w)?,
        "directionmix" => directionmix::build(b, t, float, w)?,
        "imagemap" => imagemap::build(b, t, float, w)?,
        "bilerp" => bilerp::build(b, t, float, w)?,
        "checkerboard" => checkerboard::build(b, t, float, w)?,
        "dots" => dots::build(b, t, float, w)?,
        "fbm" => noise::fbm(b, t, float, w)?,
        "wrinkled" => noise::wrinkled(b, t, float, w)?,
        "windy" => noise::windy(b, t, float, w)?,
        "marble" => noise::marble(b, t, float, w)?,
        "ptex" => ptex::build(b, t, float, w)?,
        other => {
            w.push(Diagnostic::warning(
                &e.loc,
                format!("texture type `{other}` is not supported yet; using a constant 0.5"),
            ));
            for q in p.unused() {
                q.mark_used();
            }
            (Texture::Constant(Rgb::splat(0.5)), vec![])
        }
    };
    w.unused(p, &format!("texture \"{}\"", e.ty), &known);
    Ok(tex)
}
