//! Materials from `Material` / `MakeNamedMaterial` descriptions.

use super::spectrum::rgb_param;
use super::Warnings;
use crate::material::conductor::ConductorSpec;
use crate::material::spectra::metal;
use crate::material::*;
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, MaterialDesc, ParamSet, SceneDesc};

pub struct BuiltMaterials {
    pub materials: Vec<Material>,
    /// Index of the default material (pbrt's diffuse 0.5), appended last.
    pub default: u32,
}

pub fn build_materials(desc: &SceneDesc, w: &mut Warnings) -> Result<BuiltMaterials, Diagnostic> {
    let mut materials = Vec::with_capacity(desc.materials.len() + 1);
    for m in &desc.materials {
        materials.push(build_material(desc, m, w)?);
    }
    let default = materials.len() as u32;
    materials.push(Material::Diffuse(DiffuseMaterial {
        reflectance: Rgb::splat(0.5),
    }));
    Ok(BuiltMaterials { materials, default })
}

/// Spectrum or texture parameter as a constant RGB (textures: constant only, for now).
fn color(
    desc: &SceneDesc,
    p: &ParamSet,
    name: &str,
    default: Rgb,
    w: &mut Warnings,
) -> Result<Rgb, Diagnostic> {
    if let Some(tex) = p.get_texture(name) {
        return Ok(texture_constant(desc, p, name, &tex, w).unwrap_or(default));
    }
    Ok(rgb_param(desc, p, name)?.unwrap_or(default))
}

fn float(
    desc: &SceneDesc,
    p: &ParamSet,
    name: &str,
    default: f32,
    w: &mut Warnings,
) -> Result<f32, Diagnostic> {
    if let Some(tex) = p.get_texture(name) {
        return Ok(texture_constant(desc, p, name, &tex, w)
            .map(|c| c.average())
            .unwrap_or(default));
    }
    p.get_float(name, default)
}

/// The value of a named constant texture; other texture types are a warning.
fn texture_constant(
    desc: &SceneDesc,
    p: &ParamSet,
    param: &str,
    name: &str,
    w: &mut Warnings,
) -> Option<Rgb> {
    let loc = p.loc_of(param).unwrap_or_else(lumis_scene::Loc::none);
    let Some(t) = desc.textures.iter().rev().find(|t| t.name == name) else {
        w.push(Diagnostic::warning(
            &loc,
            format!("texture `{name}` is not defined; using the default value"),
        ));
        return None;
    };
    if t.entity.ty == "constant" {
        if let Ok(Some(v)) = rgb_param(desc, &t.entity.params, "value") {
            return Some(v);
        }
        if let Ok(v) = t.entity.params.get_float("value", 1.0) {
            return Some(Rgb::splat(v));
        }
    }
    for q in t.entity.params.unused() {
        q.mark_used();
    }
    w.push(Diagnostic::warning(
        &t.entity.loc,
        format!(
            "texture type `{}` is not supported yet; `{param}` uses its default value",
            t.entity.ty
        ),
    ));
    None
}

/// Trowbridge-Reitz alphas from pbrt-v4's roughness parameters.
fn alphas(desc: &SceneDesc, p: &ParamSet, w: &mut Warnings) -> Result<(f32, f32), Diagnostic> {
    let r = float(desc, p, "roughness", 0.0, w)?;
    let u = if p.has("uroughness") {
        float(desc, p, "uroughness", r, w)?
    } else {
        r
    };
    let v = if p.has("vroughness") {
        float(desc, p, "vroughness", r, w)?
    } else {
        r
    };
    let remap = p.get_bool("remaproughness", true)?;
    let f = |x: f32| if remap { x.max(0.0).sqrt() } else { x.max(0.0) };
    Ok((f(u), f(v)))
}

fn build_material(
    desc: &SceneDesc,
    m: &MaterialDesc,
    w: &mut Warnings,
) -> Result<Material, Diagnostic> {
    let e = &m.entity;
    let p = &e.params;
    p.mark_used("type");
    p.mark_used("displacement");
    let rough = ["roughness", "uroughness", "vroughness", "remaproughness"];
    let (mat, known): (Material, Vec<&str>) = match e.ty.as_str() {
        "diffuse" => (
            Material::Diffuse(DiffuseMaterial {
                reflectance: color(desc, p, "reflectance", Rgb::splat(0.5), w)?,
            }),
            vec!["reflectance"],
        ),
        "conductor" => {
            let (ax, ay) = alphas(desc, p, w)?;
            let spec = if p.has("reflectance") {
                ConductorSpec::Reflectance(color(desc, p, "reflectance", Rgb::WHITE, w)?)
            } else {
                let (cu_eta, cu_k) = metal("metal-Cu-eta").unwrap();
                ConductorSpec::EtaK {
                    eta: color(desc, p, "eta", cu_eta, w)?,
                    k: color(desc, p, "k", cu_k, w)?,
                }
            };
            (
                Material::Conductor(ConductorMaterial {
                    spec,
                    alpha_x: ax,
                    alpha_y: ay,
                }),
                [&["eta", "k", "reflectance"][..], &rough].concat(),
            )
        }
        "dielectric" | "thindielectric" => {
            if e.ty == "thindielectric" {
                w.push(Diagnostic::warning(
                    &e.loc,
                    "material `thindielectric` is not supported yet; using `dielectric`",
                ));
            }
            let (ax, ay) = alphas(desc, p, w)?;
            let eta = match p.param("eta").map(|q| q.ty.clone()) {
                Some(t) if t == "float" => p.get_float("eta", 1.5)?,
                Some(_) => {
                    let c = rgb_param(desc, p, "eta")?.unwrap_or(Rgb::splat(1.5));
                    if c.max_component() - c.min_component() > 1e-3 {
                        w.push(Diagnostic::warning(
                            &p.loc_of("eta").unwrap(),
                            "dispersion is not rendered: using the mean index of refraction",
                        ));
                    }
                    c.average()
                }
                None => 1.5,
            };
            if !(eta > 0.0) {
                return Err(Diagnostic::error(
                    &p.loc_of("eta").unwrap_or(e.loc.clone()),
                    format!("eta must be positive, found {eta}"),
                ));
            }
            (
                Material::Dielectric(DielectricMaterial {
                    eta,
                    alpha_x: ax,
                    alpha_y: ay,
                }),
                [&["eta"][..], &rough].concat(),
            )
        }
        "phong" => {
            let kd = color(desc, p, "Kd", Rgb::splat(0.5), w)?;
            let ks = color(desc, p, "Ks", Rgb::splat(0.0), w)?;
            let n = p.get_float("exponent", 10.0)?;
            if !(n >= 0.0) {
                return Err(Diagnostic::error(
                    &p.loc_of("exponent").unwrap_or(e.loc.clone()),
                    "phong exponent must be >= 0",
                ));
            }
            (
                Material::Phong(PhongMaterial {
                    kd,
                    ks,
                    exponent: n,
                }),
                vec!["Kd", "Ks", "exponent"],
            )
        }
        "interface" | "" | "none" => (
            Material::Dielectric(DielectricMaterial {
                eta: 1.0,
                alpha_x: 0.0,
                alpha_y: 0.0,
            }),
            vec![],
        ),
        "coateddiffuse" => {
            w.push(Diagnostic::warning(
                &e.loc,
                "material `coateddiffuse` is not supported yet; rendering its base as `diffuse`",
            ));
            let r = color(desc, p, "reflectance", Rgb::splat(0.5), w)?;
            mark_all(p);
            (
                Material::Diffuse(DiffuseMaterial { reflectance: r }),
                vec![],
            )
        }
        "coatedconductor" => {
            w.push(Diagnostic::warning(&e.loc, "material `coatedconductor` is not supported yet; rendering its base as `conductor`"));
            let (cu_eta, cu_k) = metal("metal-Cu-eta").unwrap();
            let eta = color(desc, p, "conductor.eta", cu_eta, w)?;
            let k = color(desc, p, "conductor.k", cu_k, w)?;
            let r = float(desc, p, "conductor.roughness", 0.0, w)?
                .max(0.0)
                .sqrt();
            mark_all(p);
            (
                Material::Conductor(ConductorMaterial {
                    spec: ConductorSpec::EtaK { eta, k },
                    alpha_x: r,
                    alpha_y: r,
                }),
                vec![],
            )
        }
        other => {
            w.push(Diagnostic::warning(
                &e.loc,
                format!("material `{other}` is not supported yet; using diffuse 0.5"),
            ));
            mark_all(p);
            (
                Material::Diffuse(DiffuseMaterial {
                    reflectance: Rgb::splat(0.5),
                }),
                vec![],
            )
        }
    };
    w.unused(p, &format!("material \"{}\"", e.ty), &known);
    Ok(mat)
}

fn mark_all(p: &ParamSet) {
    for q in p.unused() {
        q.mark_used();
    }
}
