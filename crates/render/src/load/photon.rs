//! Parameters of the `photon` integrator, read from the scene file's
//! `Integrator "photon"` with the overrides layered on
//! (see [`lumis_scene::Overrides`]): each is declared once, in
//! [`crate::integrator::photon::PARAMS`].

use crate::integrator::photon::{check_memory, AlphaMode, CausticMode, Heuristic, Kernel};
use crate::integrator::photon::{PhotonSettings, Progressive, PARAMS};
use lumis_scene::{Diagnostic, Entity, ParamSpec};

fn choice<T>(
    e: &Entity,
    name: &str,
    default: &str,
    what: &str,
    parse: impl Fn(&str) -> Option<T>,
) -> Result<T, Diagnostic> {
    let p = &e.params;
    let value = p.get_string(name, default)?;
    parse(&value).ok_or_else(|| {
        let names = PARAMS
            .iter()
            .find(|s| s.name == name)
            .map_or("", |s| s.value);
        Diagnostic::error(
            &p.loc_of(name).unwrap_or(e.loc.clone()),
            format!("unknown {what} `{value}`"),
        )
        .with_help(format!("expected one of: {}", names.replace('|', ", ")))
    })
}

fn kernel(s: &str) -> Option<Kernel> {
    match s {
        "none" => Some(Kernel::None),
        "cone" => Some(Kernel::Cone),
        _ => None,
    }
}

/// The settings `e` asks for (its parameters over the defaults).
pub fn photon_settings(e: &Entity, max_depth: u32) -> Result<PhotonSettings, Diagnostic> {
    let p = &e.params;
    let defaults = match p.get_bool("progressive", true)? {
        true => PhotonSettings::default(),
        false => PhotonSettings::single_map(),
    };
    let mut s = PhotonSettings {
        max_depth,
        ..defaults
    };
    let count = |name: &str, d: u64| -> Result<u64, Diagnostic> {
        let v = p.get_int(name, d.min(i32::MAX as u64) as i32)?;
        if v < 0 {
            return Err(Diagnostic::error(
                &p.loc_of(name).unwrap_or(e.loc.clone()),
                format!("`{name}` must be >= 0"),
            ));
        }
        Ok(v as u64)
    };
    s.global_photons = count("photons", s.global_photons)?;
    s.caustic_photons = count("causticphotons", s.caustic_photons)?;
    s.nearest = count("nearest", s.nearest as u64)?.max(1) as usize;
    s.gather_rays = count("gatherrays", s.gather_rays as u64)? as u32;
    s.specular_splits = match count("specularsplits", s.specular_splits as u64)? {
        k @ 0..=64 => k as u32,
        k => {
            return Err(Diagnostic::error(
                &p.loc_of("specularsplits").unwrap_or(e.loc.clone()),
                format!("`specularsplits` must be at most 64, found {k}"),
            )
            .with_help("each split doubles a camera path's branches; `maxdepth` bounds them"))
        }
    };
    s.max_radius = p.get_float("maxradius", s.max_radius)?;
    s.gather_gain = p.get_float("gathergain", s.gather_gain)?;
    if !(s.gather_gain > 0.0 && s.gather_gain.is_finite()) {
        let what = format!(
            "`gathergain` must be a positive number, found {}",
            s.gather_gain
        );
        return Err(bad(e, "gathergain", what));
    }
    s.gather_boost = p.get_float("gatherboost", s.gather_boost)?;
    if !(s.gather_boost >= 1.0 && s.gather_boost <= 64.0) {
        let what = format!(
            "`gatherboost` must be a number from 1 to 64, found {}",
            s.gather_boost
        );
        return Err(bad(e, "gatherboost", what));
    }
    s.caustics = choice(
        e,
        "caustics",
        s.caustics.name(),
        "caustics mode",
        CausticMode::from_name,
    )?;
    s.heuristic = choice(
        e,
        "heuristic",
        s.heuristic.name(),
        "heuristic",
        Heuristic::from_name,
    )?;
    s.alpha = choice(e, "alpha", s.alpha.name(), "alpha", AlphaMode::from_name)?;
    s.kernel = choice(e, "kernel", "none", "kernel", kernel)?;
    s.radiance_photons = p.get_bool("radiancephotons", s.radiance_photons)?;
    s.aim_caustics = p.get_bool("aimcaustics", s.aim_caustics)?;
    s.connect_caustics = p.get_bool("connectcaustics", s.connect_caustics)?;
    if s.progressive.is_some() {
        s.progressive = Some(progressive(e)?);
    }
    if !(s.max_radius >= 0.0) {
        return Err(Diagnostic::error(
            &p.loc_of("maxradius").unwrap_or(e.loc.clone()),
            format!("max radius must be >= 0, found {}", s.max_radius),
        ));
    }
    check_memory(&s).map_err(|m| {
        let which = match s.caustic_photons > s.global_photons {
            true => "causticphotons",
            false => "photons",
        };
        Diagnostic::error(&p.loc_of(which).unwrap_or(e.loc.clone()), m)
    })?;
    Ok(s)
}

/// An error at parameter `name` of `e` (at `e` itself when not given).
fn bad(e: &Entity, name: &str, what: String) -> Diagnostic {
    Diagnostic::error(&e.params.loc_of(name).unwrap_or(e.loc.clone()), what)
}

/// The progressive mode's settings `e` asks for.
fn progressive(e: &Entity) -> Result<Progressive, Diagnostic> {
    let p = &e.params;
    let d = Progressive::default();
    let bad = |name: &str, what: String| bad(e, name, what);
    let spp = p.get_int("iterationspp", d.iteration_spp as i32)?;
    if spp < 1 {
        return Err(bad(
            "iterationspp",
            format!("`iterationspp` must be >= 1, found {spp}"),
        ));
    }
    let shrink = p.get_float("shrink", d.shrink)?;
    if !(shrink > 0.0 && shrink <= 1.0) {
        return Err(bad(
            "shrink",
            format!("`shrink` must be in (0, 1], found {shrink}"),
        ));
    }
    let r0 = p.get_float("initialradius", d.initial_radius)?;
    if !(r0 >= 0.0) {
        return Err(bad(
            "initialradius",
            format!("`initialradius` must be >= 0, found {r0}"),
        ));
    }
    let iterations = p.get_int("iterations", 0)?;
    if iterations < 0 {
        return Err(bad(
            "iterations",
            format!("`iterations` must be >= 0, found {iterations}"),
        ));
    }
    let share = p.get_float("photonshare", d.photon_share)?;
    if !(0.0..1.0).contains(&share) {
        return Err(bad(
            "photonshare",
            format!("`photonshare` must be in [0, 1), found {share}"),
        ));
    }
    // Photon counts given by the scene or the command line are kept.
    let counts_given = ["photons", "causticphotons"]
        .iter()
        .any(|n| p.loc_of(n).is_some());
    Ok(Progressive {
        iteration_spp: spp as u32,
        shrink,
        initial_radius: r0,
        iterations: iterations as u32,
        photon_share: if counts_given { 0.0 } else { share },
    })
}

/// Parameter names of `Integrator "photon"`, for the unused-parameter report.
pub fn names() -> Vec<&'static str> {
    ParamSpec::names(PARAMS)
}
