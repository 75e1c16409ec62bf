//! `diffuse`: Lambertian reflection; also pbrt's default material (diffuse
//! 0.5), which shapes without a material and unsupported types get.

use super::common::{Built, Ctx};
use crate::load::Warnings;
use crate::material::{DiffuseMaterial, MaterialKind};
use crate::texture::TexRgb;
use lumis_math::Rgb;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, _w: &mut Warnings) -> Result<Built, Diagnostic> {
    Ok((
        MaterialKind::Diffuse(DiffuseMaterial {
            reflectance: c.tex.spectrum(c.p, "reflectance", Rgb::splat(0.5))?,
        }),
        vec!["reflectance"],
    ))
}

/// pbrt's default material: diffuse with reflectance 0.5.
pub(super) fn default_kind() -> MaterialKind {
    MaterialKind::Diffuse(DiffuseMaterial {
        reflectance: TexRgb::Const(Rgb::splat(0.5)),
    })
}
