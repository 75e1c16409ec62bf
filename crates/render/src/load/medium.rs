//! `MakeNamedMedium` descriptions to [`Medium`]s, and the names shapes and
//! the camera use resolved to medium ids. Types: `homogeneous` (with
//! pbrt-v4's presets), `uniformgrid`, `rgbgrid`, `cloud`; `nanovdb` gets a
//! homogeneous stand-in with a located warning.

use super::medium_presets::PRESETS;
use super::spectrum::{light_rgb, rgb_param};
use super::Warnings;
use crate::media::voxels::Voxels;
use crate::media::{
    Cloud, Grid, GridEmission, HenyeyGreenstein, Homogeneous, Medium, MediumInterface, MediumKind,
    Phase, RgbGrid,
};
use lumis_math::spectrum::{xyz, xyz_to_linear_srgb, Spectrum, CIE_Y_INTEGRAL};
use lumis_math::{Mat4, Rgb, Transform, Vec3};
use lumis_scene::{Diagnostic, Entity, MediumDesc, MediumInterfaceDesc, MediumName, SceneDesc};
use std::collections::HashMap;

const TYPES: &[&str] = &["homogeneous", "uniformgrid", "rgbgrid", "cloud", "nanovdb"];

/// The scene's media and their names.
#[derive(Default)]
pub struct BuiltMedia {
    pub media: Vec<Medium>,
    ids: HashMap<String, u32>,
}

impl BuiltMedia {
    /// The id of a named medium; an undefined name is an error at its use.
    pub fn id(&self, name: &Option<MediumName>) -> Result<Option<u32>, Diagnostic> {
        let Some(n) = name else {
            return Ok(None);
        };
        if let Some(&i) = self.ids.get(&n.name) {
            return Ok(Some(i));
        }
        let names: Vec<&str> = self.ids.keys().map(|s| s.as_str()).collect();
        let d = Diagnostic::error(&n.loc, format!("medium `{}` is not defined", n.name));
        Err(match lumis_scene::loc::suggest(&n.name, &names, 2) {
            Some(s) => d.with_help(format!("did you mean `{s}`?")),
            None => d.with_help(
                "define it with `MakeNamedMedium \"name\" \"string type\" \"homogeneous\" ...`",
            ),
        })
    }

    /// The interface of a shape, `None` unless it changes the medium.
    pub fn interface(
        &self,
        d: &MediumInterfaceDesc,
    ) -> Result<Option<MediumInterface>, Diagnostic> {
        if !d.is_transition() {
            return Ok(None);
        }
        Ok(Some(MediumInterface {
            inside: self.id(&d.inside)?,
            outside: self.id(&d.outside)?,
        }))
    }
}

pub fn build_media(desc: &SceneDesc, w: &mut Warnings) -> Result<BuiltMedia, Diagnostic> {
    let mut out = BuiltMedia::default();
    for m in &desc.media {
        let medium = build_medium(desc, m, w)?;
        out.ids.insert(m.name.clone(), out.media.len() as u32);
        out.media.push(medium);
    }
    Ok(out)
}

fn build_medium(desc: &SceneDesc, m: &MediumDesc, w: &mut Warnings) -> Result<Medium, Diagnostic> {
    let e = &m.entity;
    let p = &e.params;
    let g = p.get_float("g", 0.0)?;
    if !(g > -1.0 && g < 1.0) {
        return Err(located(
            e,
            "g",
            format!("`g` must be in (-1, 1), found {g}"),
        ));
    }
    let kind = match e.ty.as_str() {
        "homogeneous" => MediumKind::Homogeneous(homogeneous(desc, e, w)?),
        "uniformgrid" => MediumKind::Grid(uniform_grid(desc, m, w)?),
        "rgbgrid" => MediumKind::RgbGrid(rgb_grid(m, w)?),
        "cloud" => MediumKind::Cloud(cloud(desc, m, w)?),
        "nanovdb" => {
            let scale = p.get_float("scale", 1.0)?;
            let sigma_a = rgb_param(desc, p, "sigma_a")?.unwrap_or(Rgb::WHITE) * scale;
            let sigma_s = rgb_param(desc, p, "sigma_s")?.unwrap_or(Rgb::WHITE) * scale;
            for q in p.unused() {
                q.mark_used();
            }
            w.push(Diagnostic::warning(
                &e.loc,
                format!(
                    "medium `{}`: type `nanovdb` is not supported (lumis has no NanoVDB reader); it renders as a homogeneous medium with its sigma_a and sigma_s (times scale) at density 1",
                    m.name
                ),
            ));
            MediumKind::Homogeneous(Homogeneous {
                sigma_a,
                sigma_s,
                le: Rgb::BLACK,
            })
        }
        other => {
            let d = Diagnostic::error(&e.loc, format!("unknown medium type `{other}`"));
            return Err(match lumis_scene::loc::suggest(other, TYPES, 2) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None => d.with_help(format!("medium types: {}", TYPES.join(", "))),
            });
        }
    };
    Ok(Medium {
        kind,
        phase: Phase::HenyeyGreenstein(HenyeyGreenstein::new(g)),
    })
}

fn located(e: &Entity, name: &str, msg: String) -> Diagnostic {
    Diagnostic::error(&e.params.loc_of(name).unwrap_or_else(|| e.loc.clone()), msg)
}

fn homogeneous(desc: &SceneDesc, e: &Entity, w: &mut Warnings) -> Result<Homogeneous, Diagnostic> {
    let p = &e.params;
    let mut preset = None;
    if let Some(name) = p.get_opt_string("preset")? {
        match PRESETS.iter().find(|(n, _, _)| *n == name) {
            Some(&(_, s, a)) => {
                preset = Some((Rgb::new(a[0], a[1], a[2]), Rgb::new(s[0], s[1], s[2])))
            }
            None => {
                let names: Vec<&str> = PRESETS.iter().map(|(n, _, _)| *n).collect();
                let d = Diagnostic::warning(
                    &p.loc_of("preset").unwrap_or_else(|| e.loc.clone()),
                    format!("medium preset \"{name}\" is not known; sigma_a and sigma_s are read instead"),
                );
                w.push(match lumis_scene::loc::suggest(&name, &names, 3) {
                    Some(s) => d.with_help(format!("did you mean \"{s}\"?")),
                    None => d,
                });
            }
        }
    }
    let (sigma_a, sigma_s) = match preset {
        Some(v) => {
            p.mark_used("sigma_a");
            p.mark_used("sigma_s");
            v
        }
        None => (
            rgb_param(desc, p, "sigma_a")?.unwrap_or(Rgb::WHITE),
            rgb_param(desc, p, "sigma_s")?.unwrap_or(Rgb::WHITE),
        ),
    };
    let scale = p.get_float("scale", 1.0)?;
    let le = light_rgb(desc, p, "Le")?.unwrap_or(Rgb::BLACK) * p.get_float("Lescale", 1.0)?;
    check_coefficients(e, sigma_a * scale, sigma_s * scale)?;
    w.unused(
        p,
        "medium \"homogeneous\"",
        &[
            "type", "preset", "sigma_a", "sigma_s", "scale", "g", "Le", "Lescale",
        ],
    );
    Ok(Homogeneous {
        sigma_a: sigma_a * scale,
        sigma_s: sigma_s * scale,
        le,
    })
}

fn check_coefficients(e: &Entity, a: Rgb, s: Rgb) -> Result<(), Diagnostic> {
    for (name, v) in [("sigma_a", a), ("sigma_s", s)] {
        if !(v.min_component() >= 0.0) || !v.is_finite() {
            return Err(located(
                e,
                name,
                format!("`{name}` (times `scale`) must be finite and non-negative, found {v:?}"),
            ));
        }
    }
    Ok(())
}

/// World space to the unit cube of the grid's box `[p0, p1]` (medium space).
fn unit_from_world(m: &MediumDesc) -> Result<Transform, Diagnostic> {
    let p = &m.entity.params;
    let p0 = p.get_point3("p0", Vec3::ZERO)?;
    let p1 = p.get_point3("p1", Vec3::ONE)?;
    let ext = p1 - p0;
    let unit = Transform::new(Mat4::from_scale(ext.recip()) * Mat4::from_translation(-p0))
        .filter(|_| ext.min_element() > 0.0)
        .ok_or_else(|| {
            located(
                &m.entity,
                "p1",
                format!("the grid's box needs p1 > p0 on every axis, found p0 {p0} and p1 {p1}"),
            )
        })?;
    Ok(unit.compose(&m.medium_to_world.inverse()))
}

/// The grid resolution, checked against the number of values of each named
/// array that is present.
fn resolution(e: &Entity, arrays: &[(&str, usize)]) -> Result<[usize; 3], Diagnostic> {
    let p = &e.params;
    let mut n = [0usize; 3];
    for (k, name) in ["nx", "ny", "nz"].iter().enumerate() {
        let v = p.get_int(name, 1)?;
        if v < 1 {
            return Err(located(
                e,
                name,
                format!("`{name}` must be at least 1, found {v}"),
            ));
        }
        n[k] = v as usize;
    }
    let total = n[0] * n[1] * n[2];
    for &(name, len) in arrays {
        if len != total {
            return Err(located(
                e,
                name,
                format!(
                    "`{name}` has {len} values; expected nx*ny*nz = {}*{}*{} = {total}",
                    n[0], n[1], n[2]
                ),
            ));
        }
    }
    Ok(n)
}

fn uniform_grid(desc: &SceneDesc, m: &MediumDesc, w: &mut Warnings) -> Result<Grid, Diagnostic> {
    let e = &m.entity;
    let p = &e.params;
    let Some(density) = p.get_floats("density")? else {
        return Err(Diagnostic::error(
            &e.loc,
            "a `uniformgrid` medium needs a \"float density\" array (nx*ny*nz values)",
        ));
    };
    let temperature = p.get_floats("temperature")?;
    let le_scale = p.get_floats("Lescale")?;
    let mut arrays = vec![("density", density.len())];
    if let Some(t) = &temperature {
        arrays.push(("temperature", t.len()));
    }
    if let Some(s) = le_scale.as_ref().filter(|s| s.len() != 1) {
        arrays.push(("Lescale", s.len()));
    }
    let n = resolution(e, &arrays)?;
    if density.iter().any(|d| !(*d >= 0.0) || !d.is_finite()) {
        return Err(located(
            e,
            "density",
            "`density` values must be finite and non-negative".into(),
        ));
    }
    let le = light_rgb(desc, p, "Le")?;
    if le.is_some() && temperature.is_some() {
        return Err(located(
            e,
            "Le",
            "both \"Le\" and \"temperature\" are given; a grid emits one or the other".into(),
        ));
    }
    let scale = p.get_float("scale", 1.0)?;
    let sigma_a = rgb_param(desc, p, "sigma_a")?.unwrap_or(Rgb::WHITE) * scale;
    let sigma_s = rgb_param(desc, p, "sigma_s")?.unwrap_or(Rgb::WHITE) * scale;
    check_coefficients(e, sigma_a, sigma_s)?;
    let offset = p.get_float("temperatureoffset", p.get_float("temperaturecutoff", 0.0)?)?;
    let t_scale = p.get_float("temperaturescale", 1.0)?;
    let scale_at = |i: usize| {
        le_scale
            .as_ref()
            .map_or(1.0, |s| if s.len() == 1 { s[0] } else { s[i] })
    };
    let emission = match (le, &temperature) {
        (_, Some(t)) => {
            let bb = Blackbodies::default();
            GridEmission::PerVoxel(Voxels {
                n,
                values: t
                    .iter()
                    .enumerate()
                    .map(|(i, &t)| bb.rgb((t - offset) * t_scale) * scale_at(i))
                    .collect(),
            })
        }
        (Some(le), None) if le.is_black() => GridEmission::None,
        (Some(le), None) => match le_scale.as_ref().filter(|s| s.len() != 1) {
            Some(s) => GridEmission::Scaled(
                le,
                Voxels {
                    n,
                    values: s.clone(),
                },
            ),
            None => GridEmission::Uniform(le * scale_at(0)),
        },
        (None, None) => GridEmission::None,
    };
    let known = [
        "type",
        "density",
        "temperature",
        "nx",
        "ny",
        "nz",
        "p0",
        "p1",
        "g",
        "sigma_a",
        "sigma_s",
        "scale",
        "Le",
        "Lescale",
        "temperatureoffset",
        "temperaturecutoff",
        "temperaturescale",
    ];
    let unit = unit_from_world(m)?;
    w.unused(p, "medium \"uniformgrid\"", &known);
    Ok(Grid::new(
        unit,
        sigma_a,
        sigma_s,
        Voxels { n, values: density },
        emission,
    ))
}

fn cloud(desc: &SceneDesc, m: &MediumDesc, w: &mut Warnings) -> Result<Cloud, Diagnostic> {
    let e = &m.entity;
    let p = &e.params;
    let sigma_a = rgb_param(desc, p, "sigma_a")?.unwrap_or(Rgb::WHITE);
    let sigma_s = rgb_param(desc, p, "sigma_s")?.unwrap_or(Rgb::WHITE);
    check_coefficients(e, sigma_a, sigma_s)?;
    let density = p.get_float("density", 1.0)?;
    let wispiness = p.get_float("wispiness", 1.0)?;
    let frequency = p.get_float("frequency", 5.0)?;
    let unit = unit_from_world(m)?;
    w.unused(
        p,
        "medium \"cloud\"",
        &[
            "type",
            "sigma_a",
            "sigma_s",
            "density",
            "wispiness",
            "frequency",
            "p0",
            "p1",
            "g",
        ],
    );
    let medium_from_world = m.medium_to_world.inverse();
    Ok(Cloud::new(
        medium_from_world,
        unit,
        sigma_a,
        sigma_s,
        density,
        wispiness,
        frequency,
    ))
}

fn rgb_grid(m: &MediumDesc, w: &mut Warnings) -> Result<RgbGrid, Diagnostic> {
    let e = &m.entity;
    let p = &e.params;
    let to_rgb = |v: Vec<Vec3>| {
        v.into_iter()
            .map(|c| Rgb::new(c.x, c.y, c.z))
            .collect::<Vec<_>>()
    };
    let sigma_a = p.get_rgbs("sigma_a")?.map(to_rgb);
    let sigma_s = p.get_rgbs("sigma_s")?.map(to_rgb);
    let le = p.get_rgbs("Le")?.map(to_rgb);
    if sigma_a.is_none() && sigma_s.is_none() {
        return Err(Diagnostic::error(
            &e.loc,
            "an `rgbgrid` medium needs \"rgb sigma_a\" and/or \"rgb sigma_s\" arrays",
        ));
    }
    if le.is_some() && sigma_a.is_none() {
        return Err(located(
            e,
            "Le",
            "an emitting `rgbgrid` needs \"rgb sigma_a\" (emission is sigma_a times Le)".into(),
        ));
    }
    let mut arrays = Vec::new();
    for (name, v) in [("sigma_a", &sigma_a), ("sigma_s", &sigma_s), ("Le", &le)] {
        if let Some(v) = v {
            if name != "Le"
                && v.iter()
                    .any(|c| !(c.min_component() >= 0.0) || !c.is_finite())
            {
                return Err(located(
                    e,
                    name,
                    format!("`{name}` values must be finite and non-negative"),
                ));
            }
            arrays.push((name, v.len()));
        }
    }
    let n = resolution(e, &arrays)?;
    let grid = |v: Option<Vec<Rgb>>| v.map(|values| Voxels { n, values });
    let scale = p.get_float("scale", 1.0)?;
    let le_scale = p.get_float("Lescale", 1.0)?;
    let unit = unit_from_world(m)?;
    w.unused(
        p,
        "medium \"rgbgrid\"",
        &[
            "type", "sigma_a", "sigma_s", "Le", "Lescale", "nx", "ny", "nz", "p0", "p1", "g",
            "scale",
        ],
    );
    Ok(RgbGrid::new(
        unit,
        grid(sigma_a),
        grid(sigma_s),
        scale,
        grid(le),
        le_scale,
    ))
}

/// Blackbody radiance as linear sRGB, pbrt-v4's way for media: the spectrum
/// normalized to a peak of 1 (not to unit luminance), tabulated every 10 K.
#[derive(Default)]
struct Blackbodies {
    cache: std::cell::RefCell<HashMap<u32, Rgb>>,
}

impl Blackbodies {
    fn rgb(&self, kelvin: f32) -> Rgb {
        // pbrt-v4 treats temperatures up to 100 K as not emitting.
        if !(kelvin > 100.0) {
            return Rgb::BLACK;
        }
        let at = |k: u32| {
            *self.cache.borrow_mut().entry(k).or_insert_with(|| {
                let c = xyz(&Spectrum::Blackbody(k as f64 * 10.0)).map(|v| v / CIE_Y_INTEGRAL);
                xyz_to_linear_srgb(c)
            })
        };
        let x = kelvin / 10.0;
        let k = x.floor() as u32;
        let f = x - k as f32;
        at(k) * (1.0 - f) + at(k + 1) * f
    }
}
