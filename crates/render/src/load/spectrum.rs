//! Spectrum-valued parameters (`rgb`, `blackbody`, `spectrum` given inline,
//! by name or by `.spd` file) reduced to linear sRGB with the conventions of
//! `lumis_math::spectrum`: emitted spectra to unit luminance, reflectances
//! under white light, conductors' `eta`/`k` by a per-channel fit.

use lumis_math::spectrum::{self, illuminant_rgb, reflectance_rgb, Spectrum};
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, Loc, ParamSet, SceneDesc, SpectrumValue};

/// A spectrum parameter as written: an RGB triple or a spectrum.
#[derive(Clone, Debug)]
pub enum Value {
    Rgb(Rgb),
    Spectrum(Spectrum),
}

/// The parameter `name` (not a texture) as RGB or spectrum; `None` when absent.
pub fn spectrum_value(
    desc: &SceneDesc,
    params: &ParamSet,
    name: &str,
) -> Result<Option<Value>, Diagnostic> {
    let Some(v) = params.get_spectrum(name)? else {
        return Ok(None);
    };
    let loc = params.loc_of(name).unwrap_or_else(Loc::none);
    Ok(Some(match v {
        SpectrumValue::Rgb(c) => Value::Rgb(Rgb::new(c[0], c[1], c[2])),
        SpectrumValue::Blackbody(t) => {
            if !(t > 0.0) {
                return Err(Diagnostic::error(
                    &loc,
                    format!("blackbody temperature must be positive, found {t}"),
                ));
            }
            Value::Spectrum(Spectrum::Blackbody(t as f64))
        }
        SpectrumValue::Sampled(pairs) => {
            let s = pairs.iter().map(|&(l, v)| (l as f64, v as f64)).collect();
            Value::Spectrum(
                Spectrum::piecewise(s)
                    .map_err(|e| Diagnostic::error(&loc, format!("spectrum `{name}`: {e}")))?,
            )
        }
        SpectrumValue::Named(n) => match spectrum::named(&n) {
            Some(s) => Value::Spectrum(s),
            // pbrt-v4 reads a string that is no known name as a file.
            None if desc.resolve_path(&n).is_file() => Value::Spectrum(read_spd(desc, &n, &loc)?),
            None => {
                return Err(
                    Diagnostic::error(&loc, format!("unknown named spectrum `{n}`")).with_help(
                        format!(
                            "known names: {}; or give a .spd file of wavelength/value pairs",
                            spectrum::NAMED.join(", ")
                        ),
                    ),
                )
            }
        },
        SpectrumValue::File(f) => Value::Spectrum(read_spd(desc, &f, &loc)?),
    }))
}

/// A `.spd` file: whitespace-separated (wavelength nm, value) pairs, `#`
/// starting a comment, wavelengths increasing (as pbrt-v4 reads it).
fn read_spd(desc: &SceneDesc, file: &str, loc: &Loc) -> Result<Spectrum, Diagnostic> {
    let path = desc.read_path(file);
    let text = std::fs::read_to_string(&path).map_err(|e| {
        Diagnostic::error(
            loc,
            format!("cannot read spectrum file {}: {e}", path.display()),
        )
    })?;
    let mut nums = Vec::new();
    for (i, line) in text.lines().enumerate() {
        for tok in line.split('#').next().unwrap_or("").split_whitespace() {
            let v = tok.parse::<f64>().map_err(|_| {
                Diagnostic::error(
                    loc,
                    format!("{}:{}: `{tok}` is not a number", path.display(), i + 1),
                )
            })?;
            nums.push(v);
        }
    }
    if nums.is_empty() || nums.len() % 2 != 0 {
        return Err(Diagnostic::error(
            loc,
            format!(
                "{}: expected wavelength/value pairs, found {} numbers",
                path.display(),
                nums.len()
            ),
        ));
    }
    Spectrum::piecewise(nums.chunks(2).map(|c| (c[0], c[1])).collect())
        .map_err(|e| Diagnostic::error(loc, format!("{}: {e}", path.display())))
}

/// A reflectance-like parameter (albedo, reflectance, any unitless
/// spectrum) as RGB; `None` when absent.
pub fn rgb_param(
    desc: &SceneDesc,
    params: &ParamSet,
    name: &str,
) -> Result<Option<Rgb>, Diagnostic> {
    Ok(spectrum_value(desc, params, name)?.map(|v| match v {
        Value::Rgb(c) => c,
        Value::Spectrum(s) => reflectance_rgb(&s),
    }))
}

/// A light's emitted spectrum (`L`, `I`) as RGB, as pbrt-v4 renders it: an
/// `rgb` as given, a spectrum with luminance 1 (pbrt-v4 divides the light's
/// `scale` by the spectrum's luminance); `None` when absent.
pub fn light_rgb(
    desc: &SceneDesc,
    params: &ParamSet,
    name: &str,
) -> Result<Option<Rgb>, Diagnostic> {
    Ok(spectrum_value(desc, params, name)?.map(|v| match v {
        Value::Rgb(c) => c,
        Value::Spectrum(s) => illuminant_rgb(&s),
    }))
}
