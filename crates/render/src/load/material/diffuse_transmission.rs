//! `diffusetransmission`: two-sided Lambertian reflection and transmission,
//! both scaled by `scale`.

use super::common::{Built, Ctx};
use crate::load::Warnings;
use crate::material::{DiffuseTransmissionMaterial, MaterialKind};
use lumis_math::Rgb;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, _w: &mut Warnings) -> Result<Built, Diagnostic> {
    let p = c.p;
    let scale = p.get_float("scale", 1.0)?;
    if !(scale >= 0.0) || !scale.is_finite() {
        return Err(Diagnostic::error(
            &p.loc_of("scale").unwrap_or_else(lumis_scene::Loc::none),
            format!("diffusetransmission `scale` must be a finite number >= 0, found {scale}"),
        ));
    }
    Ok((
        MaterialKind::DiffuseTransmission(DiffuseTransmissionMaterial {
            reflectance: c.tex.spectrum(p, "reflectance", Rgb::splat(0.25))?,
            transmittance: c.tex.spectrum(p, "transmittance", Rgb::splat(0.25))?,
            scale,
        }),
        vec!["reflectance", "transmittance", "scale"],
    ))
}
