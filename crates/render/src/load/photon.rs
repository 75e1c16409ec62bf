//! Parameters of the `photon` integrator: scene file first, command line wins.

use crate::integrator::photon::{
    check_memory, AlphaMode, CausticMode, Heuristic, Kernel, PhotonSettings,
};
use lumis_scene::{Diagnostic, Entity, Loc};

/// Command-line values for the photon integrator (all optional).
#[derive(Clone, Debug, Default)]
pub struct PhotonOverrides {
    pub caustics: Option<String>,
    pub heuristic: Option<String>,
    pub alpha: Option<String>,
    pub photons: Option<u64>,
    pub caustic_photons: Option<u64>,
    pub nearest: Option<usize>,
    pub gather_rays: Option<u32>,
    pub max_radius: Option<f32>,
    pub kernel: Option<String>,
    pub radiance_photons: Option<bool>,
    pub aim_caustics: Option<bool>,
}

/// Parameter names of `Integrator "photon"`.
pub const PARAMS: &[&str] = &[
    "maxdepth",
    "photons",
    "causticphotons",
    "nearest",
    "gatherrays",
    "maxradius",
    "caustics",
    "heuristic",
    "alpha",
    "kernel",
    "radiancephotons",
    "aimcaustics",
];

fn choice<T>(
    value: &str,
    what: &str,
    parse: impl Fn(&str) -> Option<T>,
    names: &str,
    loc: Option<&Loc>,
) -> Result<T, Diagnostic> {
    parse(value).ok_or_else(|| {
        let msg = format!("unknown {what} `{value}`");
        match loc {
            Some(l) => Diagnostic::error(l, msg),
            None => Diagnostic::plain_error(msg),
        }
        .with_help(format!("expected one of: {names}"))
    })
}

fn kernel(s: &str) -> Option<Kernel> {
    match s {
        "none" => Some(Kernel::None),
        "cone" => Some(Kernel::Cone),
        _ => None,
    }
}

pub fn photon_settings(
    e: Option<&Entity>,
    ov: &PhotonOverrides,
    max_depth: u32,
) -> Result<PhotonSettings, Diagnostic> {
    let mut s = PhotonSettings {
        max_depth,
        ..PhotonSettings::default()
    };
    if let Some(e) = e {
        let p = &e.params;
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
        s.max_radius = p.get_float("maxradius", s.max_radius)?;
        let string = |name: &str, d: &str| p.get_string(name, d);
        s.caustics = choice(
            &string("caustics", s.caustics.name())?,
            "caustics mode",
            CausticMode::from_name,
            "mis, photons, gather",
            p.loc_of("caustics").as_ref(),
        )?;
        s.heuristic = choice(
            &string("heuristic", s.heuristic.name())?,
            "heuristic",
            Heuristic::from_name,
            "balance, power",
            p.loc_of("heuristic").as_ref(),
        )?;
        s.alpha = choice(
            &string("alpha", s.alpha.name())?,
            "alpha",
            AlphaMode::from_name,
            AlphaMode::NAMES,
            p.loc_of("alpha").as_ref(),
        )?;
        s.kernel = choice(
            &string("kernel", "none")?,
            "kernel",
            kernel,
            "none, cone",
            p.loc_of("kernel").as_ref(),
        )?;
        s.radiance_photons = p.get_bool("radiancephotons", s.radiance_photons)?;
        s.aim_caustics = p.get_bool("aimcaustics", s.aim_caustics)?;
    }
    if let Some(v) = &ov.caustics {
        s.caustics = choice(
            v,
            "caustics mode",
            CausticMode::from_name,
            "mis, photons, gather",
            None,
        )?;
    }
    if let Some(v) = &ov.heuristic {
        s.heuristic = choice(v, "heuristic", Heuristic::from_name, "balance, power", None)?;
    }
    if let Some(v) = &ov.alpha {
        s.alpha = choice(v, "alpha", AlphaMode::from_name, AlphaMode::NAMES, None)?;
    }
    if let Some(v) = &ov.kernel {
        s.kernel = choice(v, "kernel", kernel, "none, cone", None)?;
    }
    s.global_photons = ov.photons.unwrap_or(s.global_photons);
    s.caustic_photons = ov.caustic_photons.unwrap_or(s.caustic_photons);
    s.nearest = ov.nearest.unwrap_or(s.nearest).max(1);
    s.gather_rays = ov.gather_rays.unwrap_or(s.gather_rays);
    s.max_radius = ov.max_radius.unwrap_or(s.max_radius);
    s.radiance_photons = ov.radiance_photons.unwrap_or(s.radiance_photons);
    s.aim_caustics = ov.aim_caustics.unwrap_or(s.aim_caustics);
    if !(s.max_radius >= 0.0) {
        return Err(Diagnostic::plain_error(format!(
            "max radius must be >= 0, found {}",
            s.max_radius
        )));
    }
    Ok(s)
}

/// The memory check, as a diagnostic (only for the photon integrator).
pub fn check(s: &PhotonSettings) -> Result<(), Diagnostic> {
    check_memory(s).map_err(Diagnostic::plain_error)
}
