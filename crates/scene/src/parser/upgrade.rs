//! pbrt-v3 → pbrt-v4, following the rules of pbrt-v4's `--upgrade`
//! (`FormattingParserTarget` in pbrt-v4's parser.cpp): renamed material,
//! film, sampler, integrator, camera and light types, renamed and folded
//! parameters. Every rule fires only on pbrt-v3 syntax (names and
//! parameters pbrt-v4 does not have), so pbrt-v4 files pass unchanged, and
//! the result is a plain pbrt-v4 description. Information the upgrade drops
//! is a warning at its location, as in pbrt-v4.

use crate::desc::Entity;
use crate::loc::{Diagnostic, Loc};
use crate::params::{Param, ParamSet, Value};

fn take(ps: &mut ParamSet, name: &str) -> Option<Param> {
    let i = ps.params.iter().position(|p| p.name == name)?;
    Some(ps.params.remove(i))
}

fn rename(ps: &mut ParamSet, from: &str, to: &str) {
    if ps.has(to) {
        return;
    }
    if let Some(p) = ps.params.iter_mut().find(|p| p.name == from) {
        p.name = to.to_string();
    }
}

fn add(ps: &mut ParamSet, ty: &str, name: &str, value: Value, loc: &Loc) {
    take(ps, name);
    ps.push(Param::new(ty, name, value, loc.clone(), Vec::new()));
}

/// The grey value of a constant `rgb` parameter, if it is one.
fn grey(p: &Param) -> Option<f32> {
    match (&p.ty[..], &p.value) {
        ("rgb", Value::Floats(f)) if f.len() == 3 && f[0] == f[1] && f[1] == f[2] => Some(f[0]),
        _ => None,
    }
}

fn one_float(p: &Param) -> Option<f32> {
    match &p.value {
        Value::Floats(f) if f.len() == 1 => Some(f[0]),
        _ => None,
    }
}

/// Removes spectrum/texture parameter `name`; a warning unless it was the
/// constant `value` (what the new material does anyway).
fn drop_unless_const(
    ps: &mut ParamSet,
    name: &str,
    value: f32,
    mat: &str,
    w: &mut Vec<Diagnostic>,
) {
    if let Some(p) = take(ps, name) {
        if grey(&p) != Some(value) {
            w.push(Diagnostic::warning(
                &p.loc,
                format!("pbrt-v3 parameter `{name}` is dropped converting to pbrt-v4's \"{mat}\" material (as pbrt-v4's --upgrade does)"),
            ));
        }
    }
}

/// Whether spectrum parameter `name` is the constant `value` (false if absent).
fn is_const(ps: &ParamSet, name: &str, value: f32) -> bool {
    ps.param(name).and_then(grey) == Some(value)
}

/// A pbrt-v3 material type and parameters as pbrt-v4 ones.
pub fn material(e: &mut Entity, w: &mut Vec<Diagnostic>) -> Result<(), Diagnostic> {
    let ps = &mut e.params;
    if matches!(e.ty.as_str(), "glass" | "uber") {
        if let Some(p) = take(ps, "index") {
            if ps.has("eta") {
                return Err(Diagnostic::error(
                    &p.loc,
                    format!("material \"{}\" has both \"index\" and \"eta\"", e.ty),
                ));
            }
            let mut p = p;
            p.name = "eta".into();
            ps.push(p);
        }
    }
    rename(ps, "bumpmap", "displacement");
    let new = match e.ty.as_str() {
        "uber" => {
            let diffuse = is_const(ps, "Ks", 0.0);
            let name = if diffuse { "diffuse" } else { "coateddiffuse" };
            drop_unless_const(ps, "Ks", 0.0, name, w);
            if diffuse {
                take(ps, "eta");
                take(ps, "roughness");
            }
            drop_unless_const(ps, "Kr", 0.0, name, w);
            drop_unless_const(ps, "Kt", 0.0, name, w);
            rename(ps, "Kd", "reflectance");
            if let Some(p) = take(ps, "opacity") {
                if grey(&p) != Some(1.0) {
                    return Err(Diagnostic::error(
                        &p.loc,
                        "a non-opaque \"opacity\" in the \"uber\" material is not supported in pbrt-v4",
                    ));
                }
            }
            name
        }
        "substrate" => {
            drop_unless_const(ps, "Ks", 1.0, "coateddiffuse", w);
            rename(ps, "Kd", "reflectance");
            "coateddiffuse"
        }
        "glass" => {
            drop_unless_const(ps, "Kr", 1.0, "dielectric", w);
            drop_unless_const(ps, "Kt", 1.0, "dielectric", w);
            "dielectric"
        }
        "plastic" => {
            let diffuse = is_const(ps, "Ks", 0.0);
            let name = if diffuse { "diffuse" } else { "coateddiffuse" };
            drop_unless_const(ps, "Ks", 0.0, name, w);
            if diffuse {
                take(ps, "roughness");
                take(ps, "eta");
            }
            rename(ps, "Kd", "reflectance");
            name
        }
        "matte" => {
            rename(ps, "Kd", "reflectance");
            if let Some(p) = take(ps, "sigma") {
                if one_float(&p) != Some(0.0) {
                    w.push(Diagnostic::warning(
                        &p.loc,
                        "pbrt-v4's \"diffuse\" material has no Oren-Nayar `sigma`: it is Lambertian; `sigma` ignored",
                    ));
                }
            }
            "diffuse"
        }
        "metal" => {
            drop_unless_const(ps, "Kr", 1.0, "conductor", w);
            "conductor"
        }
        "mirror" => {
            drop_unless_const(ps, "Kr", 0.0, "conductor", w);
            let loc = e.loc.clone();
            add(ps, "float", "roughness", Value::Floats(vec![0.0]), &loc);
            add(
                ps,
                "spectrum",
                "eta",
                Value::Strings(vec!["metal-Ag-eta".into()]),
                &loc,
            );
            add(
                ps,
                "spectrum",
                "k",
                Value::Strings(vec!["metal-Ag-k".into()]),
                &loc,
            );
            "conductor"
        }
        "translucent" => {
            rename(ps, "Kd", "transmittance");
            drop_unless_const(ps, "reflect", 0.0, "diffusetransmission", w);
            drop_unless_const(ps, "transmit", 1.0, "diffusetransmission", w);
            drop_unless_const(ps, "Ks", 0.0, "diffusetransmission", w);
            take(ps, "roughness");
            "diffusetransmission"
        }
        "kdsubsurface" => {
            rename(ps, "Kd", "reflectance");
            "subsurface"
        }
        "disney" => {
            rename(ps, "color", "reflectance");
            "diffuse"
        }
        "mix" if ps.has("namedmaterial1") || ps.has("namedmaterial2") => {
            mix(e.loc.clone(), ps, w)?;
            "mix"
        }
        "" | "none" => "interface",
        _ => return Ok(()),
    };
    e.ty = new.to_string();
    Ok(())
}

/// pbrt-v3 `mix`: `amount` becomes a float, and `namedmaterial1/2` become
/// `string materials` in swapped order.
fn mix(loc: Loc, ps: &mut ParamSet, w: &mut Vec<Diagnostic>) -> Result<(), Diagnostic> {
    if let Some(p) = take(ps, "amount") {
        match (&p.ty[..], &p.value) {
            ("rgb", Value::Floats(f)) if f.len() == 3 => {
                let avg = (f[0] + f[1] + f[2]) / 3.0;
                if grey(&p).is_none() {
                    w.push(Diagnostic::warning(
                        &p.loc,
                        format!("RGB `amount` becomes its average {avg}"),
                    ));
                }
                add(ps, "float", "amount", Value::Floats(vec![avg]), &p.loc);
            }
            _ => ps.push(p),
        }
    }
    let name = |ps: &mut ParamSet, n: &str| -> Result<String, Diagnostic> {
        match take(ps, n).map(|p| p.value) {
            Some(Value::Strings(s)) if s.len() == 1 => Ok(s[0].clone()),
            _ => Err(Diagnostic::error(
                &loc,
                format!("pbrt-v3 \"mix\" material needs \"string {n}\""),
            )),
        }
    };
    let (m1, m2) = (name(ps, "namedmaterial1")?, name(ps, "namedmaterial2")?);
    add(
        ps,
        "string",
        "materials",
        Value::Strings(vec![m2, m1]),
        &loc,
    );
    Ok(())
}

/// Light parameters: `rgb scale` → float, `blackbody [T s]` → T with `s`
/// folded into `scale`, `mapname` → `filename`, `samples` dropped, and an
/// infinite light's constant `L` with a map folded into `scale`.
pub fn light(e: &mut Entity, area: bool) -> Result<(), Diagnostic> {
    if area && e.ty == "area" {
        e.ty = "diffuse".into();
    }
    let ps = &mut e.params;
    let mut total = 1.0f32;
    if let Some((g, loc)) = ps
        .param("scale")
        .filter(|p| p.ty != "float")
        .map(|p| (grey(p), p.loc.clone()))
    {
        let Some(g) = g else {
            return Err(Diagnostic::error(
                &loc,
                "in pbrt-v4, \"scale\" is a \"float\" parameter of lights",
            ));
        };
        total *= g;
        take(ps, "scale");
    }
    take(ps, "samples");
    take(ps, "nsamples");
    if ps.has("mapname") && matches!(e.ty.as_str(), "infinite" | "projection") {
        let which = if e.ty == "infinite" { "L" } else { "I" };
        if let Some((g, loc)) = ps.param(which).map(|p| (grey(p), p.loc.clone())) {
            let Some(g) = g else {
                return Err(Diagnostic::error(
                    &loc,
                    format!("a non-constant \"{which}\" together with \"mapname\" is not supported by pbrt-v4"),
                ));
            };
            total *= g;
            take(ps, which);
        }
    }
    for name in ["I", "L"] {
        if let Some(p) = ps
            .params
            .iter_mut()
            .find(|p| p.name == name && p.ty == "blackbody")
        {
            if let Value::Floats(f) = &mut p.value {
                if f.len() == 2 {
                    total *= f[1];
                    f.pop();
                    p.value_locs.truncate(1);
                } else if f.len() != 1 {
                    return Err(Diagnostic::error(
                        &p.loc,
                        "expected one value (pbrt-v4) or two (pbrt-v3) for \"blackbody\"",
                    ));
                }
            }
        }
    }
    if ps.has("mapname") && e.ty == "infinite" {
        // pbrt-v3 environment maps are latitude-longitude images (pbrt-v4's
        // are equal-area squares): say so (a lumis extension parameter).
        let loc = ps.loc_of("mapname").expect("present");
        add(
            ps,
            "string",
            "mapping",
            Value::Strings(vec!["latlong".into()]),
            &loc,
        );
    }
    rename(ps, "mapname", "filename");
    if total != 1.0 {
        let (old, loc) = match take(ps, "scale") {
            Some(p) => (one_float(&p).unwrap_or(1.0), p.loc),
            None => (1.0, e.loc.clone()),
        };
        add(ps, "float", "scale", Value::Floats(vec![total * old]), &loc);
    }
    Ok(())
}

/// Film `image` → `rgb`; `scale` → `iso` (100 × scale); `maxsampleluminance` → `maxcomponentvalue`.
pub fn film(e: &mut Entity) {
    if e.ty == "image" {
        e.ty = "rgb".into();
    }
    let ps = &mut e.params;
    rename(ps, "maxsampleluminance", "maxcomponentvalue");
    if let Some((s, loc)) = ps
        .param("scale")
        .filter(|p| p.ty == "float")
        .and_then(|p| Some((one_float(p)?, p.loc.clone())))
    {
        take(ps, "scale");
        add(ps, "float", "iso", Value::Floats(vec![100.0 * s]), &loc);
    }
}

/// PixelFilter `xwidth`/`ywidth` → `xradius`/`yradius`; gaussian `alpha` → `sigma`.
pub fn filter(e: &mut Entity) {
    let ps = &mut e.params;
    rename(ps, "xwidth", "xradius");
    rename(ps, "ywidth", "yradius");
    if e.ty == "gaussian" {
        if let Some(a) = ps.param("alpha").and_then(one_float) {
            let loc = ps.loc_of("alpha").expect("present");
            take(ps, "alpha");
            let sigma = 1.0 / (2.0 * a).sqrt();
            add(ps, "float", "sigma", Value::Floats(vec![sigma]), &loc);
        }
    }
}

/// pbrt-v3 sampler names.
pub fn sampler(e: &mut Entity) {
    match e.ty.as_str() {
        "lowdiscrepancy" | "02sequence" => e.ty = "paddedsobol".into(),
        "maxmindist" => e.ty = "pmj02bn".into(),
        _ => {}
    }
}

/// pbrt-v3 integrator names and parameters.
pub fn integrator(e: &mut Entity, w: &mut Vec<Diagnostic>) {
    let ps = &mut e.params;
    take(ps, "rrthreshold");
    if e.ty == "sppm" {
        take(ps, "imagewritefrequency");
        if let Some(p) = take(ps, "numiterations") {
            w.push(Diagnostic::warning(
                &p.loc,
                "pbrt-v4's SPPM has no \"numiterations\": it is the sampler's pixel samples; ignored",
            ));
        }
    }
    let spatial = Value::Strings(vec!["spatial".into()]);
    if let Some(loc) = ps
        .param("lightsamplestrategy")
        .filter(|p| p.value == spatial)
        .map(|p| p.loc.clone())
    {
        add(
            ps,
            "string",
            "lightsamplestrategy",
            Value::Strings(vec!["bvh".into()]),
            &loc,
        );
    }
    if e.ty == "directlighting" {
        e.ty = "path".into();
        let loc = e.loc.clone();
        add(
            &mut e.params,
            "integer",
            "maxdepth",
            Value::Ints(vec![1]),
            &loc,
        );
    }
}

/// Camera `environment` → `spherical` with equirectangular mapping.
pub fn camera(e: &mut Entity) {
    if e.ty == "environment" {
        e.ty = "spherical".into();
        let loc = e.loc.clone();
        add(
            &mut e.params,
            "string",
            "mapping",
            Value::Strings(vec!["equirectangular".into()]),
            &loc,
        );
    }
    if e.ty == "realistic" {
        take(&mut e.params, "simpleweighting");
    }
}

/// Shape parameters: loopsubdiv `nlevels` → `levels`; trianglemesh `st`/float `uv` → `point2 uv`.
pub fn shape(e: &mut Entity) {
    let ps = &mut e.params;
    rename(ps, "Kd", "reflectance");
    if e.ty == "loopsubdiv" {
        rename(ps, "nlevels", "levels");
    }
    if e.ty == "trianglemesh" || e.ty == "plymesh" {
        take(ps, "discarddegenerateUVs");
        if ps.param("shadowalpha").is_some_and(|p| p.ty == "texture") {
            take(ps, "shadowalpha");
        }
    }
    if e.ty == "trianglemesh" {
        for name in ["st", "uv"] {
            if let Some(p) = ps.params.iter_mut().find(|p| p.name == name) {
                if p.ty == "float" || p.ty == "point2" {
                    p.ty = "point2".into();
                    p.name = "uv".into();
                }
            }
        }
    }
}

/// Texture parameters: `scale` texture `tex1`/`tex2`, imagemap `trilinear`
/// and `gamma`.
pub fn texture(e: &mut Entity, kind: &str) -> Result<(), Diagnostic> {
    let ps = &mut e.params;
    if e.ty == "scale" && (ps.has("tex1") || ps.has("tex2")) {
        if kind == "float" {
            rename(ps, "tex1", "tex");
            rename(ps, "tex2", "scale");
        } else {
            for n in ["tex1", "tex2"] {
                let Some(p) = ps.params.iter_mut().find(|p| p.name == n) else {
                    continue;
                };
                if p.ty == "rgb" {
                    let Some(g) = grey(p) else {
                        return Err(Diagnostic::error(
                            &p.loc,
                            "a non-constant \"rgb\" operand of a pbrt-v3 \"scale\" texture cannot be upgraded",
                        ));
                    };
                    p.ty = "float".into();
                    p.name = "scale".into();
                    p.value = Value::Floats(vec![g]);
                    p.value_locs.truncate(1);
                } else {
                    p.name = "tex".into();
                }
            }
        }
    }
    if e.ty == "imagemap" || e.ty == "ptex" {
        if let Some(p) = take(ps, "trilinear") {
            let tri = p.value == Value::Bools(vec![true]);
            let f = if tri { "trilinear" } else { "bilinear" };
            add(
                ps,
                "string",
                "filter",
                Value::Strings(vec![f.into()]),
                &p.loc,
            );
        }
        if let Some(p) = ps.param("gamma").cloned() {
            let enc = match &p.value {
                Value::Floats(f) if f.len() == 1 && f[0] != 0.0 => Some(format!("gamma {}", f[0])),
                Value::Bools(b) if b.len() == 1 => {
                    Some(if b[0] { "sRGB" } else { "linear" }.to_string())
                }
                _ => None,
            };
            if let Some(enc) = enc {
                take(ps, "gamma");
                add(ps, "string", "encoding", Value::Strings(vec![enc]), &p.loc);
            }
        }
    }
    Ok(())
}
