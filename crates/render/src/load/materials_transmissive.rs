//! pbrt-v4's two-sided transmissive materials: `thindielectric` and
//! `diffusetransmission`.

use super::materials::eta_param;
use super::texture::TexBuilder;
use super::Warnings;
use crate::material::*;
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, ParamSet, SceneDesc};

/// The material of type `ty` (one of this file's) and its known parameters.
pub fn build(
    desc: &SceneDesc,
    ty: &str,
    p: &ParamSet,
    tex: &mut TexBuilder,
    w: &mut Warnings,
) -> Result<(MaterialKind, Vec<&'static str>), Diagnostic> {
    Ok(match ty {
        "thindielectric" => (
            MaterialKind::ThinDielectric(ThinDielectricMaterial {
                eta: eta_param(desc, p, "eta", 1.5, w)?,
            }),
            vec!["eta"],
        ),
        _ => {
            let scale = p.get_float("scale", 1.0)?;
            if !(scale >= 0.0) || !scale.is_finite() {
                return Err(Diagnostic::error(
                    &p.loc_of("scale").unwrap_or_else(lumis_scene::Loc::none),
                    format!(
                        "diffusetransmission `scale` must be a finite number >= 0, found {scale}"
                    ),
                ));
            }
            (
                MaterialKind::DiffuseTransmission(DiffuseTransmissionMaterial {
                    reflectance: tex.spectrum(p, "reflectance", Rgb::splat(0.25))?,
                    transmittance: tex.spectrum(p, "transmittance", Rgb::splat(0.25))?,
                    scale,
                }),
                vec!["reflectance", "transmittance", "scale"],
            )
        }
    })
}
