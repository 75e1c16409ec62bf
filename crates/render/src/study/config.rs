//! The study configuration (TOML) and its expansion into runs.

use super::error::{bail, Context, Result};
pub use super::setting::SettingCfg;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// `studies/*.toml`: scenes x settings x budgets x seeds.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Config {
    #[serde(default = "default_title")]
    pub title: String,
    pub seeds: Vec<u64>,
    /// Time budgets in seconds (photon tracing and map building included).
    #[serde(default)]
    pub time: Vec<f64>,
    /// Sample-count budgets.
    #[serde(default)]
    pub spp: Vec<u32>,
    /// Worker threads per run (0: all cores).
    #[serde(default)]
    pub threads: usize,
    /// Heatmap error: `rel` or `abs`.
    #[serde(default = "default_heatmap")]
    pub heatmap: String,
    /// Heatmap log range, the same for every run.
    #[serde(default = "default_range")]
    pub heatmap_range: [f64; 2],
    /// Which images the report shows: `all`, `first-seed` or `largest-budget`
    /// (first seed at the largest budget). Every run's files are written anyway.
    #[serde(default = "default_show")]
    pub show_images: String,
    #[serde(rename = "scene")]
    pub scenes: Vec<SceneCfg>,
    #[serde(rename = "setting")]
    pub settings: Vec<SettingCfg>,
    /// The config file's folder (absolute): `{config_dir}` in external commands.
    #[serde(skip)]
    pub dir: PathBuf,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneCfg {
    pub name: String,
    /// Scene file, relative to the config's folder.
    pub file: PathBuf,
    /// Reference image (EXR/PFM), relative to the config's folder.
    pub reference: PathBuf,
    /// Metrics region x0,x1,y0,y1 (fractions, as --mask); heatmaps cover the whole image.
    pub mask: Option<[f32; 4]>,
    /// Metrics only over the pixels the reference covers: not black, nor
    /// next to black (as `lumis compare --lit`). For a `lighttracer`
    /// reference, black where only a specular bounce shows the camera.
    #[serde(default)]
    pub lit_only: bool,
    /// PNG exposure in stops (default: the reference's 98th percentile maps to 1).
    pub exposure: Option<f32>,
    /// Extra render flags for every run of this scene.
    #[serde(default)]
    pub flags: Vec<String>,
}

fn default_title() -> String {
    "lumis study".into()
}
fn default_heatmap() -> String {
    "rel".into()
}
fn default_range() -> [f64; 2] {
    [1e-4, 10.0]
}
fn default_show() -> String {
    "all".into()
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Budget {
    Time(f64),
    Spp(u32),
}

impl Budget {
    /// Short label used in file names and tables: `t2s`, `64spp`.
    pub fn label(&self) -> String {
        match self {
            Budget::Time(t) => format!("t{t}s"),
            Budget::Spp(n) => format!("{n}spp"),
        }
    }

    pub fn flags(&self) -> [String; 2] {
        match self {
            Budget::Time(t) => ["--time".into(), t.to_string()],
            Budget::Spp(n) => ["--spp".into(), n.to_string()],
        }
    }
}

/// One render of the matrix.
#[derive(Clone, Debug)]
pub struct Run {
    pub scene: usize,
    pub setting: usize,
    pub budget: Budget,
    pub seed: u64,
}

impl Run {
    /// File-name stem, unique in the study.
    pub fn id(&self, c: &Config) -> String {
        format!(
            "{}__{}__{}__s{}",
            c.scenes[self.scene].name,
            c.settings[self.setting].name,
            self.budget.label(),
            self.seed
        )
    }
}

fn check_name(what: &str, n: &str) -> Result<()> {
    if n.is_empty()
        || !n
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_' || c == '.')
        || n.contains("__")
    {
        bail!("{what} name `{n}`: use letters, digits, `-`, `_` or `.` (no `__`)");
    }
    Ok(())
}

impl Config {
    /// Reads and checks a config; scene and reference paths become absolute
    /// (the config's folder joined with them), so that a run's recorded
    /// arguments do not depend on how the config's path was written.
    pub fn load(path: &Path) -> Result<Config> {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let mut c: Config = toml::from_str(&text).with_context(|| path.display().to_string())?;
        let base = path.parent().unwrap_or(Path::new("."));
        let dir = if base.as_os_str().is_empty() {
            Path::new(".")
        } else {
            base
        };
        c.dir = std::path::absolute(dir).with_context(|| dir.display().to_string())?;
        for s in &mut c.scenes {
            s.file = c.dir.join(&s.file);
            s.reference = c.dir.join(&s.reference);
        }
        c.check()
            .with_context(|| format!("in {}", path.display()))?;
        Ok(c)
    }

    pub(super) fn check(&self) -> Result<()> {
        if self.scenes.is_empty() || self.settings.is_empty() || self.seeds.is_empty() {
            bail!("a study needs at least one [[scene]], one [[setting]] and one seed");
        }
        if self.time.is_empty() && self.spp.is_empty() {
            bail!("a study needs budgets: `time = [...]` (seconds) and/or `spp = [...]`");
        }
        if let Some(t) = self.time.iter().find(|t| !(**t > 0.0 && t.is_finite())) {
            bail!("time budgets are positive seconds, found {t}");
        }
        if self.spp.contains(&0) {
            bail!("spp budgets are at least 1");
        }
        let [lo, hi] = self.heatmap_range;
        if !(lo > 0.0 && hi > lo && hi.is_finite()) {
            bail!("heatmap_range needs 0 < lo < hi, found [{lo}, {hi}]");
        }
        if crate::metrics::PixelError::from_name(&self.heatmap).is_none() {
            bail!("heatmap = `{}`: expected `rel` or `abs`", self.heatmap);
        }
        if !["all", "first-seed", "largest-budget"].contains(&self.show_images.as_str()) {
            bail!(
                "show_images = `{}`: expected all, first-seed or largest-budget",
                self.show_images
            );
        }
        let mut names = std::collections::HashSet::new();
        for n in self.scenes.iter().map(|s| &s.name) {
            check_name("scene", n)?;
            if !names.insert(("scene", n)) {
                bail!("scene `{n}` appears twice");
            }
        }
        for s in &self.settings {
            let n = &s.name;
            check_name("setting", n)?;
            if !names.insert(("setting", n)) {
                bail!("setting `{n}` appears twice");
            }
            super::setting::check_external(s).with_context(|| format!("setting `{n}`"))?;
        }
        const OWNED: [&str; 6] = ["--time", "--spp", "--seed", "--threads", "-o", "--output"];
        let all = self.scenes.iter().flat_map(|s| &s.flags);
        for f in all.chain(self.settings.iter().flat_map(|s| &s.flags)) {
            if OWNED.contains(&f.as_str()) {
                bail!("flag `{f}` is set by the study itself (budgets, seeds, threads, outputs)");
            }
        }
        Ok(())
    }

    /// The thread count runs use: `threads`, or all cores for 0.
    pub fn resolved_threads(&self) -> usize {
        match self.threads {
            0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
            n => n,
        }
    }

    pub fn budgets(&self) -> Vec<Budget> {
        let mut b: Vec<Budget> = self.time.iter().map(|&t| Budget::Time(t)).collect();
        b.extend(self.spp.iter().map(|&n| Budget::Spp(n)));
        b
    }

    /// Every run, scene-major, then setting, budget, seed.
    pub fn runs(&self) -> Vec<Run> {
        let mut v = Vec::new();
        for scene in 0..self.scenes.len() {
            for setting in 0..self.settings.len() {
                for budget in self.budgets() {
                    for &seed in &self.seeds {
                        v.push(Run {
                            scene,
                            setting,
                            budget,
                            seed,
                        });
                    }
                }
            }
        }
        v
    }

    /// The `lumis render` arguments of a run (without output).
    pub fn render_args(&self, r: &Run) -> Vec<String> {
        let s = &self.scenes[r.scene];
        let mut a = vec![s.file.display().to_string()];
        a.extend(s.flags.iter().cloned());
        a.extend(self.settings[r.setting].flags.iter().cloned());
        a.extend(r.budget.flags());
        a.extend(["--seed".into(), r.seed.to_string()]);
        a.extend(["--threads".into(), self.threads.to_string()]);
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
        seeds = [1, 2]
        time = [0.5, 2]
        spp = [4]
        [[scene]]
        name = "a"
        file = "a.pbrt"
        reference = "a.exr"
        [[setting]]
        name = "mis"
        flags = ["--caustics", "mis"]
    "#;

    #[test]
    fn expands_the_matrix() {
        let c: Config = toml::from_str(GOOD).unwrap();
        c.check().unwrap();
        let runs = c.runs();
        assert_eq!(runs.len(), 6);
        assert_eq!(runs[0].id(&c), "a__mis__t0.5s__s1");
        assert_eq!(runs[5].id(&c), "a__mis__4spp__s2");
        let a = c.render_args(&runs[2]);
        assert_eq!(
            a,
            [
                "a.pbrt",
                "--caustics",
                "mis",
                "--time",
                "2",
                "--seed",
                "1",
                "--threads",
                "0"
            ]
        );
    }

    #[test]
    fn rejects_bad_configs() {
        let bad = |s: &str| {
            let c: Config = toml::from_str(s).unwrap();
            c.check().unwrap_err().to_string()
        };
        assert!(bad(&GOOD.replace("time = [0.5, 2]", "time = [0]")).contains("positive"));
        assert!(bad(&GOOD.replace("\"mis\"]", "\"mis\", \"--seed\", \"3\"]")).contains("--seed"));
        assert!(bad(&GOOD.replace("name = \"a\"", "name = \"a b\"")).contains("scene name"));
        assert!(bad(&GOOD
            .replace("spp = [4]", "spp = []")
            .replace("time = [0.5, 2]", ""))
        .contains("budgets"));
        assert!(toml::from_str::<Config>(&GOOD.replace("seeds", "seed")).is_err());
    }
}
