//! A `[[setting]]` of the study configuration: lumis render flags, or
//! another renderer's command line, and the checks of the latter.

use super::error::{bail, Result};
use serde::Deserialize;

/// A setting: lumis render flags, or another renderer's command line.
///
/// An external setting runs `external` (program and arguments) once per run,
/// in the scene's report folder, after substituting these placeholders in
/// every argument: `{config_dir}` (the config's folder), `{scene}` (the
/// scene file, or the copy made for `integrator`), `{out}` (the image the
/// program must write), `{spp}`, `{seed}` and `{threads}` (the study's
/// thread count, all cores for 0). `{scene}`, `{out}` and `{spp}` are
/// required. A time budget becomes an `{spp}` from a calibration (see
/// `external.rs`); the run's seconds are the process's wall time. If the
/// program does not exist, the setting's runs are skipped with a notice.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SettingCfg {
    pub name: String,
    /// Render flags, as on the command line (`--integrator photon --caustics mis`).
    #[serde(default)]
    pub flags: Vec<String>,
    /// Instead of `flags`: another renderer's command line, with placeholders.
    pub external: Option<Vec<String>>,
    /// With `external`: `{scene}` is a copy of the scene file whose
    /// `Integrator` directive has this name (its parameters kept), with its
    /// relative paths made absolute.
    pub integrator: Option<String>,
    /// With `external`: the format of `{out}`, `exr` (default) or `pfm`.
    pub output: Option<String>,
    /// With `external` and time budgets: the calibration adds runs (4x the
    /// spp each) until the slowest is this many seconds slower than the
    /// fastest (default: a quarter of the largest time budget, at least 2).
    pub calibration_seconds: Option<f64>,
    /// With `integrator`: parameters added to the renamed directive, in
    /// pbrt syntax (`"float radius" [ 0.05 ]`).
    pub integrator_params: Option<String>,
}

impl SettingCfg {
    /// The extension of an external setting's image.
    pub fn output_ext(&self) -> &str {
        self.output.as_deref().unwrap_or("exr")
    }
}

/// `integrator_params`: pbrt parameters, each a `"type name"` string and
/// its values.
fn check_params(text: &str) -> Result<()> {
    use lumis_scene::lexer::{tokenize, TokenKind};
    let src = lumis_scene::SourceFile::new("integrator_params", text);
    let toks = tokenize(&src).map_err(|d| d.to_string())?;
    let decl = |k: &TokenKind| matches!(k, TokenKind::Str(s) if s.split_whitespace().count() == 2);
    match toks.first() {
        Some(t) if !decl(&t.kind) => {
            bail!("integrator_params: expected a parameter such as `\"float radius\" [ 0.05 ]`, found {}", t.describe())
        }
        _ => {}
    }
    if let Some(t) = toks
        .iter()
        .find(|t| matches!(&t.kind, TokenKind::Ident(w) if w != "true" && w != "false"))
    {
        bail!("integrator_params: only parameters, found {}", t.describe());
    }
    Ok(())
}

/// The keys of an external setting, or their absence in a lumis one.
pub(super) fn check_external(s: &SettingCfg) -> Result<()> {
    let Some(cmd) = &s.external else {
        if s.integrator.is_some() || s.output.is_some() || s.calibration_seconds.is_some() {
            bail!("`integrator`, `output` and `calibration_seconds` need `external = [...]`");
        }
        if s.integrator_params.is_some() {
            bail!("`integrator_params` needs `external = [...]` and `integrator`");
        }
        return Ok(());
    };
    if !s.flags.is_empty() {
        bail!("give either `flags` (a lumis setting) or `external` (a command), not both");
    }
    if cmd.is_empty() || cmd[0].is_empty() {
        bail!("`external` needs a program: external = [\"path/to/program\", ...]");
    }
    let mut used = Vec::new();
    for arg in cmd {
        for p in super::command::placeholders(arg) {
            if !super::command::PLACEHOLDERS.contains(&p.as_str()) {
                bail!(
                    "external: unknown placeholder `{{{p}}}` in `{arg}`; known: {}",
                    super::command::PLACEHOLDERS
                        .map(|k| format!("{{{k}}}"))
                        .join(", ")
                );
            }
            used.push(p);
        }
    }
    for need in ["scene", "out", "spp"] {
        if !used.iter().any(|u| u == need) {
            bail!("external: the command needs `{{{need}}}`");
        }
    }
    if let Some(i) = &s.integrator {
        if i.is_empty()
            || !i
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        {
            bail!("integrator = `{i}`: expected a name such as `sppm`");
        }
    }
    if let Some(p) = &s.integrator_params {
        if s.integrator.is_none() {
            bail!("`integrator_params` needs `integrator`");
        }
        check_params(p)?;
    }
    if !["exr", "pfm"].contains(&s.output_ext()) {
        bail!("output = `{}`: expected `exr` or `pfm`", s.output_ext());
    }
    if let Some(t) = s.calibration_seconds {
        if !(t > 0.0 && t.is_finite()) {
            bail!("calibration_seconds: expected positive seconds, found {t}");
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::config::Config;

    const GOOD: &str = r#"
        seeds = [1]
        time = [3]
        [[scene]]
        name = "a"
        file = "a.pbrt"
        reference = "a.exr"
        [[setting]]
        name = "mis"
        flags = ["--caustics", "mis"]
    "#;

    #[test]
    fn external_settings_are_checked() {
        let ext = GOOD.to_string()
            + r#"
            [[setting]]
            name = "pbrt"
            external = ["{config_dir}/pbrt", "--spp", "{spp}", "--outfile", "{out}", "{scene}"]
            integrator = "sppm"
        "#;
        let c: Config = toml::from_str(&ext).unwrap();
        c.check().unwrap();
        assert_eq!(c.settings[1].output_ext(), "exr");
        let bad = |from: &str, to: &str| {
            let c: Config = toml::from_str(&ext.replace(from, to)).unwrap();
            c.check().unwrap_err().to_string()
        };
        let e = bad("\"{scene}\"", "\"{scne}\"");
        assert!(
            e.contains("setting `pbrt`") && e.contains("unknown placeholder `{scne}`"),
            "{e}"
        );
        assert!(bad("\"{out}\", ", "").contains("needs `{out}`"));
        assert!(bad("\"sppm\"", "\"a b\"").contains("integrator = `a b`"));
        assert!(bad("integrator = ", "flags = [\"-v\"]\nintegrator = ").contains("not both"));
        assert!(bad("integrator = ", "output = \"png\"\nintegrator = ").contains("`exr` or `pfm`"));
        let params = |p: &str| format!("integrator_params = '{p}'\nintegrator = ");
        let c: Config =
            toml::from_str(&ext.replace("integrator = ", &params("\"float radius\" [ 0.05 ]")))
                .unwrap();
        c.check().unwrap();
        let e = bad("integrator = ", &params("radius 0.05"));
        assert!(
            e.contains("expected a parameter") && e.contains("`radius`"),
            "{e}"
        );
        let e = bad("integrator = ", &params("\"float radius\" 1 WorldBegin"));
        assert!(
            e.contains("only parameters") && e.contains("`WorldBegin`"),
            "{e}"
        );
        let e = bad("external = [", "external = [] #");
        assert!(e.contains("needs a program"), "{e}");
        let lumis = GOOD.replace("flags = [", "integrator = \"x\"\nflags = [");
        let c: Config = toml::from_str(&lumis).unwrap();
        assert!(c
            .check()
            .unwrap_err()
            .to_string()
            .contains("need `external"));
    }
}
