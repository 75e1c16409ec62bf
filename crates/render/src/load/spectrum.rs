//! Spectrum-valued parameters reduced to linear RGB.

use crate::material::spectra::{blackbody_rgb, glass_ior, metal_component, sampled_rgb};
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, ParamSet, SceneDesc, SpectrumValue};

/// Reads a spectrum parameter as RGB; `None` when absent. Textures are not
/// handled here (see materials).
pub fn rgb_param(
    desc: &SceneDesc,
    params: &ParamSet,
    name: &str,
) -> Result<Option<Rgb>, Diagnostic> {
    let Some(v) = params.get_spectrum(name)? else {
        return Ok(None);
    };
    let loc = params.loc_of(name).unwrap_or_else(lumis_scene::Loc::none);
    Ok(Some(match v {
        SpectrumValue::Rgb(c) => Rgb::new(c[0], c[1], c[2]),
        SpectrumValue::Blackbody(t) => blackbody_rgb(t),
        SpectrumValue::Sampled(pairs) => sampled_rgb(&pairs),
        SpectrumValue::Named(n) => {
            if let Some(c) = metal_component(&n) {
                c
            } else if let Some(ior) = glass_ior(&n) {
                Rgb::splat(ior)
            } else if n.starts_with("stdillum") || n.starts_with("illum-") {
                Rgb::WHITE
            } else {
                return Err(Diagnostic::error(&loc, format!("unknown named spectrum `{n}`"))
                    .with_help("known: metal-{Ag,Al,Au,Cu,CuZn}-{eta,k}, glass-BK7 and other glass-* names, stdillum-*"));
            }
        }
        SpectrumValue::File(f) => {
            let path = desc.resolve_path(&f);
            let text = std::fs::read_to_string(&path).map_err(|e| {
                Diagnostic::error(
                    &loc,
                    format!("cannot read spectrum file {}: {e}", path.display()),
                )
            })?;
            let nums: Result<Vec<f32>, _> = text
                .lines()
                .map(|l| l.split('#').next().unwrap_or(""))
                .flat_map(|l| l.split_whitespace())
                .map(|t| t.parse::<f32>())
                .collect();
            let nums = nums.map_err(|_| {
                Diagnostic::error(&loc, format!("{}: not a list of numbers", path.display()))
            })?;
            if nums.len() < 2 || nums.len() % 2 != 0 {
                return Err(Diagnostic::error(
                    &loc,
                    format!("{}: expected wavelength/value pairs", path.display()),
                ));
            }
            sampled_rgb(&nums.chunks(2).map(|c| (c[0], c[1])).collect::<Vec<_>>())
        }
    }))
}
