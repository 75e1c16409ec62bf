//! Materials from `Material` / `MakeNamedMaterial` descriptions.

use super::spectrum::{spectrum_value, Value};
use super::texture::TexBuilder;
use super::Warnings;
use crate::bsdf::microfacet::MicrofacetModel;
use crate::material::*;
use crate::texture::{TexFloat, TexRgb};
use lumis_math::spectrum::{conductor_rgb, mean_under_white, named, reflectance_rgb};
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, MaterialDesc, ParamSet, SceneDesc};

pub struct BuiltMaterials {
    pub materials: Vec<Material>,
    /// Index of the default material (pbrt's diffuse 0.5), appended last.
    pub default: u32,
}

pub fn build_materials(
    desc: &SceneDesc,
    tex: &mut TexBuilder,
    w: &mut Warnings,
) -> Result<BuiltMaterials, Diagnostic> {
    let mut materials = Vec::with_capacity(desc.materials.len() + 1);
    for (i, m) in desc.materials.iter().enumerate() {
        materials.push(build_material(desc, i, m, tex, w)?);
    }
    let default = materials.len() as u32;
    materials.push(
        MaterialKind::Diffuse(DiffuseMaterial {
            reflectance: TexRgb::Const(Rgb::splat(0.5)),
        })
        .into(),
    );
    Ok(BuiltMaterials { materials, default })
}

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
fn roughness_with_distribution(tex: &TexBuilder, p: &ParamSet) -> Result<Roughness, Diagnostic> {
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

fn build_material(
    desc: &SceneDesc,
    index: usize,
    m: &MaterialDesc,
    tex: &mut TexBuilder,
    w: &mut Warnings,
) -> Result<Material, Diagnostic> {
    let e = &m.entity;
    let p = &e.params;
    p.mark_used("type");
    let rough = ROUGH;
    let (kind, known): (MaterialKind, Vec<&str>) = match e.ty.as_str() {
        "diffuse" => (
            MaterialKind::Diffuse(DiffuseMaterial {
                reflectance: tex.spectrum(p, "reflectance", Rgb::splat(0.5))?,
            }),
            vec!["reflectance"],
        ),
        "conductor" => (
            MaterialKind::Conductor(ConductorMaterial {
                spec: conductor_spec(tex, p, "")?,
                roughness: roughness_with_distribution(tex, p)?,
            }),
            [&["eta", "k", "reflectance", "distribution"][..], &rough].concat(),
        ),
        "dielectric" => (
            MaterialKind::Dielectric(DielectricMaterial {
                eta: eta_param(desc, p, "eta", 1.5, w)?,
                roughness: roughness_with_distribution(tex, p)?,
            }),
            [&["eta", "distribution"][..], &rough].concat(),
        ),
        "phong" => {
            let n = p.get_float("exponent", 10.0)?;
            if !(n >= 0.0) {
                return Err(Diagnostic::error(
                    &p.loc_of("exponent").unwrap_or(e.loc.clone()),
                    "phong exponent must be >= 0",
                ));
            }
            (
                MaterialKind::Phong(PhongMaterial {
                    kd: tex.spectrum(p, "Kd", Rgb::splat(0.5))?,
                    ks: tex.spectrum(p, "Ks", Rgb::splat(0.0))?,
                    exponent: n,
                }),
                vec!["Kd", "Ks", "exponent"],
            )
        }
        "mix" => (
            MaterialKind::Mix(mix(desc, index, m, tex)?),
            vec!["materials", "amount"],
        ),
        "interface" | "" | "none" => (MaterialKind::Interface(InterfaceMaterial), vec![]),
        "thindielectric" | "diffusetransmission" => {
            super::materials_transmissive::build(desc, &e.ty, p, tex, w)?
        }
        other => {
            if let Some(k) = super::materials_layered::build(desc, other, &e.loc, p, tex, w)? {
                k
            } else {
                w.push(Diagnostic::warning(
                    &e.loc,
                    format!("material `{other}` is not supported yet; using diffuse 0.5"),
                ));
                for q in p.unused() {
                    q.mark_used();
                }
                (
                    MaterialKind::Diffuse(DiffuseMaterial {
                        reflectance: TexRgb::Const(Rgb::splat(0.5)),
                    }),
                    vec![],
                )
            }
        }
    };
    let shading = if let Some(id) = tex.normal_map(p)? {
        Shading::NormalMap(id)
    } else if p.has("displacement") {
        match tex.float(p, "displacement", 0.0)? {
            TexFloat::Const(_) => Shading::Smooth,
            d => Shading::Bump(d),
        }
    } else {
        Shading::Smooth
    };
    let known = [&known[..], &["displacement", "normalmap"]].concat();
    w.unused(p, &format!("material \"{}\"", e.ty), &known);
    Ok(Material { kind, shading })
}

/// `mix`: two named materials (defined before this one) and an amount.
fn mix(
    desc: &SceneDesc,
    index: usize,
    m: &MaterialDesc,
    tex: &TexBuilder,
) -> Result<MixMaterial, Diagnostic> {
    let p = &m.entity.params;
    let loc = p
        .loc_of("materials")
        .unwrap_or_else(|| m.entity.loc.clone());
    let names = match p.param("materials").map(|q| &q.value) {
        Some(lumis_scene::params::Value::Strings(s)) if s.len() == 2 => s.clone(),
        _ => {
            return Err(Diagnostic::error(
                &loc,
                "mix material needs `string materials` with exactly two material names",
            ))
        }
    };
    p.mark_used("materials");
    let mut ids = [0u32; 2];
    for (k, n) in names.iter().enumerate() {
        let Some(&i) = desc.named_materials.get(n) else {
            return Err(Diagnostic::error(&loc, format!("no material named `{n}`")));
        };
        if i as usize >= index {
            return Err(Diagnostic::error(
                &loc,
                format!("material `{n}` must be defined before the mix that uses it"),
            ));
        }
        ids[k] = i;
    }
    Ok(MixMaterial {
        materials: ids,
        amount: tex.float(p, "amount", 0.5)?,
    })
}
