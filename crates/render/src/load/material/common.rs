//! What the material builders share: their context ([`Ctx`]), what each
//! returns ([`Built`]), and the parameter readers several material types use
//! (roughness, index of refraction, conductor optics). Imports no sibling
//! module, so every material file may use it.

use crate::bsdf::microfacet::MicrofacetModel;
use crate::load::spectrum::{spectrum_value, Value};
use crate::load::texture::TexBuilder;
use crate::load::Warnings;
use crate::material::{ConductorSpec, MaterialKind, Roughness};
use crate::texture::TexRgb;
use lumis_math::spectrum::{conductor_rgb, mean_under_white, named, reflectance_rgb};
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, MaterialDesc, ParamSet, SceneDesc};

/// One material description being built.
pub(super) struct Ctx<'a> {
    pub desc: &'a SceneDesc,
    /// Its index in `desc.materials` (a `mix` may only use earlier ones).
    pub index: usize,
    pub m: &'a MaterialDesc,
    /// `m`'s parameters.
    pub p: &'a ParamSet,
    pub tex: &'a TexBuilder<'a>,
}

/// A material's kind and the names of the parameters its type reads.
pub(super) type Built = (MaterialKind, Vec<&'static str>);

pub(super) const ROUGH: [&str; 4] = ["roughness", "uroughness", "vroughness", "remaproughness"];

/// Trowbridge-Reitz roughness from pbrt-v4's parameters (`prefix` for the
/// layered materials' `interface.` / `conductor.`).
pub(super) fn roughness(
    tex: &TexBuilder,
    p: &ParamSet,
    prefix: &str,
    default: f32,
) -> Result<Roughness, Diagnostic> {
    let n = |s: &str| format!("{prefix}{s}");
    let r = tex.float(p, &n("roughness"), default)?;
    let u = if p.has(&n("uroughness")) {
        tex.float(p, &n("uroughness"), 0.0)?
    } else {
        r
    };
    let v = if p.has(&n("vroughness")) {
        tex.float(p, &n("vroughness"), 0.0)?
    } else {
        r
    };
    Ok(Roughness {
        u,
        v,
        remap: p.get_bool("remaproughness", true)?,
        model: MicrofacetModel::TrowbridgeReitz,
    })
}

/// [`roughness`] with lumis' `"string distribution"` extension
/// (`trowbridgereitz`/`ggx`, the default, or `beckmann`), as Mitsuba and
/// Tungsten scenes name their conductors' and dielectrics' distributions.
pub(super) fn roughness_with_distribution(
    tex: &TexBuilder,
    p: &ParamSet,
) -> Result<Roughness, Diagnostic> {
    let mut r = roughness(tex, p, "", 0.0)?;
    if let Some(name) = p.get_opt_string("distribution")? {
        r.model = MicrofacetModel::from_name(&name).ok_or_else(|| {
            Diagnostic::error(
                &p.loc_of("distribution").unwrap(),
                format!(
                    "unknown microfacet distribution `{name}`: expected one of {}",
                    MicrofacetModel::NAMES.join(", ")
                ),
            )
        })?;
    }
    Ok(r)
}

/// A scalar index of refraction: a `float`, or a spectrum reduced to its
/// mean under white light's luminance (an `rgb` to its channels' mean),
/// with a warning when it disperses (dispersion is not rendered).
pub(super) fn eta_param(
    desc: &SceneDesc,
    p: &ParamSet,
    name: &str,
    default: f32,
    w: &mut Warnings,
) -> Result<f32, Diagnostic> {
    let eta = match p.param(name).map(|q| q.ty.clone()) {
        Some(t) if t == "float" => p.get_float(name, default)?,
        Some(t) if t == "texture" => {
            w.unsupported(
                p,
                &[name],
                "material",
                "using a constant index of refraction",
            );
            default
        }
        Some(_) => {
            let (eta, disperses) = match spectrum_value(desc, p, name)? {
                Some(Value::Spectrum(s)) => (mean_under_white(&s) as f32, !s.is_constant()),
                Some(Value::Rgb(c)) => (c.average(), c.max_component() - c.min_component() > 1e-3),
                None => (default, false),
            };
            if disperses {
                w.push(Diagnostic::warning(
                    &p.loc_of(name).unwrap(),
                    format!(
                        "dispersion is not rendered: using the mean index of refraction {eta:.4}"
                    ),
                ));
            }
            eta
        }
        None => default,
    };
    if !(eta > 0.0) {
        return Err(Diagnostic::error(
            &p.loc_of(name).unwrap_or_else(lumis_scene::Loc::none),
            format!("eta must be positive, found {eta}"),
        ));
    }
    Ok(eta)
}

/// Conductor optics from `eta`/`k` or `reflectance` (with `prefix`).
/// Spectral `eta` and `k` (pbrt-v4's default is copper's) are reduced
/// together to one `(eta, k)` per channel (`lumis_math::spectrum::conductor_rgb`);
/// a spectrum paired with an `rgb` or a texture is reduced alone.
pub(super) fn conductor_spec(
    tex: &TexBuilder,
    p: &ParamSet,
    prefix: &str,
) -> Result<ConductorSpec, Diagnostic> {
    let n = |s: &str| format!("{prefix}{s}");
    if p.has(&n("reflectance")) {
        return Ok(ConductorSpec::Reflectance(tex.spectrum(
            p,
            &n("reflectance"),
            Rgb::WHITE,
        )?));
    }
    let (eta_name, k_name) = (n("eta"), n("k"));
    let value = |name: &str, default: &str| -> Result<Option<Value>, Diagnostic> {
        if p.param(name)
            .is_some_and(|q| q.ty == "texture" || q.ty == "float")
        {
            return Ok(None);
        }
        Ok(Some(spectrum_value(tex.desc(), p, name)?.unwrap_or_else(
            || Value::Spectrum(named(default).expect("copper is a named spectrum")),
        )))
    };
    let eta_v = value(&eta_name, "metal-Cu-eta")?;
    let k_v = value(&k_name, "metal-Cu-k")?;
    let lone = |v: &Value| match v {
        Value::Rgb(c) => *c,
        Value::Spectrum(s) => reflectance_rgb(s),
    };
    let (eta, k) = match (&eta_v, &k_v) {
        (Some(Value::Spectrum(e)), Some(Value::Spectrum(k))) => {
            let (e, k) = conductor_rgb(e, k);
            (TexRgb::Const(e), TexRgb::Const(k))
        }
        _ => (
            match &eta_v {
                Some(v) => TexRgb::Const(lone(v)),
                None => tex.spectrum(p, &eta_name, Rgb::WHITE)?,
            },
            match &k_v {
                Some(v) => TexRgb::Const(lone(v)),
                None => tex.spectrum(p, &k_name, Rgb::BLACK)?,
            },
        ),
    };
    Ok(ConductorSpec::EtaK { eta, k })
}
