//! `imagemap`: an image file (read once per file and encoding) through a 2D
//! mapping, with its filter and wrap mode.

use super::common::{Built, TexBuilder, MAP2D};
use crate::load::Warnings;
use crate::texture::image::Encoding;
use crate::texture::{FilterKind, ImageTexture, Texture, WrapMode};
use lumis_scene::{Diagnostic, TextureDesc};

pub(super) fn build(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    w: &mut Warnings,
) -> Result<Built, Diagnostic> {
    Ok((
        Texture::Image(image(b, t, float, w)?),
        [
            &[
                "filename",
                "filter",
                "maxanisotropy",
                "wrap",
                "scale",
                "invert",
                "encoding",
            ][..],
            &MAP2D,
        ]
        .concat(),
    ))
}

fn image(
    b: &mut TexBuilder,
    t: &TextureDesc,
    float: bool,
    w: &mut Warnings,
) -> Result<ImageTexture, Diagnostic> {
    let e = &t.entity;
    let p = &e.params;
    let loc = |n: &str| p.loc_of(n).unwrap_or_else(|| e.loc.clone());
    let Some(file) = p.get_opt_string("filename")? else {
        return Err(Diagnostic::error(
            &e.loc,
            "imagemap texture needs a `filename`",
        ));
    };
    let enc_name = p.get_string("encoding", "sRGB")?;
    let enc = Encoding::parse(&enc_name).ok_or_else(|| {
        Diagnostic::error(&loc("encoding"), format!("unknown encoding `{enc_name}`"))
            .with_help("expected sRGB, linear or \"gamma <value>\"")
    })?;
    let filter = match p.get_string("filter", "bilinear")?.as_str() {
        "point" => FilterKind::Point,
        "bilinear" => FilterKind::Bilinear,
        "trilinear" => FilterKind::Trilinear,
        "ewa" | "EWA" => {
            w.push(Diagnostic::warning(
                &loc("filter"),
                "EWA filtering is not supported yet; using trilinear",
            ));
            FilterKind::Trilinear
        }
        other => {
            return Err(
                Diagnostic::error(&loc("filter"), format!("unknown filter `{other}`"))
                    .with_help("expected point, bilinear, trilinear or ewa"),
            )
        }
    };
    let wrap_name = p.get_string("wrap", "repeat")?;
    let wrap = WrapMode::parse(&wrap_name).ok_or_else(|| {
        Diagnostic::error(&loc("wrap"), format!("unknown wrap mode `{wrap_name}`"))
            .with_help("expected repeat, black or clamp")
    })?;
    p.mark_used("maxanisotropy");
    let path = b.desc().read_path(&file);
    let mipmap = b.image(path, enc_name, enc, &loc("filename"))?;
    Ok(ImageTexture {
        mipmap,
        mapping: b.mapping(t, w)?,
        filter,
        wrap,
        scale: p.get_float("scale", 1.0)?,
        invert: p.get_bool("invert", false)?,
        float,
    })
}
