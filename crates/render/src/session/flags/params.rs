//! The integrators' own parameters as `lumis render` flags and Python
//! keywords: the list of the integrators' parameter tables, declared once
//! here, each parameter once (a name two integrators share is one flag),
//! and a flag's value as scene text.

use crate::integrator::{bdpt, photon, vcm};
use lumis_scene::{Overrides, ParamSpec};

/// The integrators' parameter tables the flags are made from.
pub const PARAM_TABLES: [(&str, &[ParamSpec]); 3] = [
    ("photon", photon::PARAMS),
    ("bdpt", bdpt::PARAMS),
    ("vcm", vcm::PARAMS),
];

/// One integrator parameter as a flag (`--caustic-photons N` for
/// `"integer causticphotons"`).
#[derive(Clone, Debug)]
pub struct IntegratorParam {
    /// The first table's declaration of it.
    pub spec: &'static ParamSpec,
    /// Each integrator that reads it and what it means there
    /// (`photon: ...; vcm: ...`).
    pub help: String,
}

impl IntegratorParam {
    /// Its command-line flag, `--caustic-photons`.
    pub fn flag(&self) -> String {
        format!("--{}", self.spec.words)
    }
}

/// Each parameter once, in table order (the order flags are applied in).
pub fn integrator_params() -> Vec<IntegratorParam> {
    let all = || {
        PARAM_TABLES
            .iter()
            .flat_map(|(name, table)| table.iter().map(move |s| (*name, s)))
    };
    let mut out: Vec<IntegratorParam> = Vec::new();
    for (_, s) in all() {
        if out.iter().any(|o| o.spec.name == s.name) {
            continue;
        }
        let help: Vec<String> = all()
            .filter(|(_, o)| o.name == s.name)
            .map(|(n, o)| format!("{n}: {}", o.help))
            .collect();
        out.push(IntegratorParam {
            spec: s,
            help: help.join("; "),
        });
    }
    out
}

/// `value` as typed on a command line, as scene text for a parameter of
/// type `ty`: a string quoted, `--strategy 2,3` a list of integers, any
/// other as is (the library's readers check it).
pub fn param_text(ty: &str, value: &str) -> String {
    match ty {
        "string" => format!("\"{value}\""),
        "integer" => value.replace(',', " "),
        _ => value.to_string(),
    }
}

/// Adds the integrator parameter `s` with `value` as typed, labelled
/// `origin` (the flag or keyword it came from).
pub(super) fn add_param(o: &mut Overrides, s: &ParamSpec, value: &str, origin: &str) {
    let decl = format!("{} {}", s.ty, s.name);
    o.param("Integrator", &decl, &param_text(s.ty, value), origin);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_parameter_once_with_every_integrators_help() {
        let all = integrator_params();
        for (i, p) in all.iter().enumerate() {
            assert!(all[..i].iter().all(|o| o.spec.name != p.spec.name));
            for (n, t) in PARAM_TABLES {
                for s in t.iter().filter(|s| s.name == p.spec.name) {
                    assert!(p.help.contains(&format!("{n}: {}", s.help)), "{}", s.name);
                }
            }
        }
        assert_eq!(all[0].spec.name, photon::PARAMS[0].name);
        assert_eq!(all[0].flag(), format!("--{}", photon::PARAMS[0].words));
    }

    #[test]
    fn values_become_scene_text() {
        assert_eq!(param_text("string", "mis"), "\"mis\"");
        assert_eq!(param_text("integer", "2,3"), "2 3");
        assert_eq!(param_text("float", "0.5"), "0.5");
        assert_eq!(param_text("bool", "true"), "true");
    }
}
