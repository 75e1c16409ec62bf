//! Runs of external settings (another renderer's command line, see
//! [`super::config::SettingCfg`]): which settings are skipped because their
//! program is missing, the scene copies for `integrator`, the calibrations
//! that turn time budgets into sample counts, and each run's command.

use super::calibrate::{calibrate, Calibration};
use super::command::{self, Vars};
use super::config::{Budget, Config, Run};
use super::error::{Context, Result};
use super::store::write_atomic;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// One external run, ready to start.
pub struct Planned {
    /// The command, placeholders substituted.
    pub args: Vec<String>,
    pub spp: u32,
    /// The image the command writes.
    pub image: PathBuf,
}

pub struct Externals<'a> {
    c: &'a Config,
    out: &'a Path,
    log: &'a dyn Fn(&str),
    cancel: &'a AtomicBool,
    /// Per setting: the program, if the setting is external and it is missing.
    missing: Vec<Option<String>>,
    copies: HashMap<(usize, usize), PathBuf>,
    calibrations: HashMap<(usize, usize), Calibration>,
}

impl<'a> Externals<'a> {
    /// Checks every external setting's program; says once which are skipped.
    pub fn new(
        c: &'a Config,
        out: &'a Path,
        log: &'a dyn Fn(&str),
        cancel: &'a AtomicBool,
    ) -> Self {
        let vars = Vars {
            config_dir: c.dir.display().to_string(),
            ..Vars::default()
        };
        let missing: Vec<Option<String>> = c
            .settings
            .iter()
            .map(|s| {
                let prog = command::substitute(&s.external.as_ref()?[..1], &vars).remove(0);
                command::find_program(&prog).is_none().then_some(prog)
            })
            .collect();
        let e = Externals {
            c,
            out,
            log,
            cancel,
            missing,
            copies: HashMap::new(),
            calibrations: HashMap::new(),
        };
        for m in e.skipped() {
            log(&format!("lumis: study: {m}"));
        }
        e
    }

    pub fn is_skipped(&self, setting: usize) -> bool {
        self.missing[setting].is_some()
    }

    /// A sentence per skipped setting.
    pub fn skipped(&self) -> Vec<String> {
        self.c
            .settings
            .iter()
            .zip(&self.missing)
            .filter_map(|(s, m)| {
                let n = self
                    .c
                    .runs()
                    .iter()
                    .filter(|r| self.c.settings[r.setting].name == s.name)
                    .count();
                m.as_ref().map(|p| {
                    format!(
                        "setting `{}`: its {n} runs are skipped, program `{p}` not found",
                        s.name
                    )
                })
            })
            .collect()
    }

    /// Every calibration used so far, in the config's order.
    pub fn calibrations(&self) -> Vec<Calibration> {
        let mut v: Vec<(&(usize, usize), &Calibration)> = self.calibrations.iter().collect();
        v.sort_by_key(|e| *e.0);
        v.into_iter().map(|e| e.1.clone()).collect()
    }

    /// The run's placeholder values, without spp, seed and output.
    fn vars(&mut self, scene: usize, setting: usize) -> Result<Vars> {
        let (sc, st) = (&self.c.scenes[scene], &self.c.settings[setting]);
        let file = match &st.integrator {
            None => std::path::absolute(&sc.file)?,
            Some(name) => match self.copies.get(&(scene, setting)) {
                Some(p) => p.clone(),
                None => {
                    let dir = std::path::absolute(self.out.join(&sc.name))?
                        .join(format!("{}.scene", st.name));
                    let p = super::scene_copy::write_copy(
                        &sc.file,
                        &dir,
                        name,
                        st.integrator_params.as_deref(),
                    )
                    .with_context(|| format!("scene `{}`: its copy for `{}`", sc.name, st.name))?;
                    self.copies.insert((scene, setting), p.clone());
                    p
                }
            },
        };
        Ok(Vars {
            config_dir: self.c.dir.display().to_string(),
            scene: file.display().to_string(),
            threads: self.c.resolved_threads().to_string(),
            ..Vars::default()
        })
    }

    /// The command of `run` (id `id`); None if interrupted while calibrating.
    pub fn plan(&mut self, run: &Run, id: &str) -> Result<Option<Planned>> {
        let vars = self.vars(run.scene, run.setting)?;
        let spp = match run.budget {
            Budget::Spp(n) => n,
            Budget::Time(t) => match self.calibration(run.scene, run.setting, &vars)? {
                Some(cal) => cal.spp_for(t),
                None => return Ok(None),
            },
        };
        let st = &self.c.settings[run.setting];
        let image = self
            .out
            .join(&self.c.scenes[run.scene].name)
            .join(format!("{id}.{}", st.output_ext()));
        let args = command::substitute(
            st.external.as_deref().unwrap_or_default(),
            &Vars {
                spp: Some(spp.to_string()),
                seed: Some(run.seed.to_string()),
                out: Some(std::path::absolute(&image)?.display().to_string()),
                ..vars
            },
        );
        Ok(Some(Planned { args, spp, image }))
    }

    /// Runs `p` in the scene's report folder; its wall seconds, None if interrupted.
    pub fn run(&self, p: &Planned, dir: &Path, id: &str) -> Result<Option<f64>> {
        let _ = std::fs::remove_file(&p.image);
        command::run_timed(&p.args, dir, &dir.join(format!("{id}.log")), self.cancel)
    }

    /// The stored calibration of a scene and setting, or a new one (None
    /// if interrupted).
    fn calibration(
        &mut self,
        scene: usize,
        setting: usize,
        vars: &Vars,
    ) -> Result<Option<&Calibration>> {
        if !self.calibrations.contains_key(&(scene, setting)) {
            let (sc, st) = (&self.c.scenes[scene], &self.c.settings[setting]);
            let key = command::substitute(st.external.as_deref().unwrap_or_default(), vars);
            let file = self
                .out
                .join("calibration")
                .join(format!("{}__{}.json", sc.name, st.name));
            let threads = self.c.resolved_threads();
            let stored = || {
                std::fs::read_to_string(&file)
                    .ok()
                    .and_then(|t| serde_json::from_str::<Calibration>(&t).ok())
                    .filter(|cal| cal.command == key && cal.threads == threads)
            };
            let cal = match stored() {
                Some(cal) => cal,
                None => {
                    let what = format!("calibrating `{}` on `{}`", st.name, sc.name);
                    (self.log)(&what);
                    let Some(cal) = self.measure(scene, setting, vars).with_context(|| what)?
                    else {
                        return Ok(None);
                    };
                    // A study of the same config running beside this one (one
                    // process per seed) may have stored its calibration
                    // meanwhile: keep the first, so both plan the same runs.
                    match stored() {
                        Some(first) => first,
                        None => {
                            write_atomic(&file, serde_json::to_string_pretty(&cal)?.as_bytes())?;
                            cal
                        }
                    }
                }
            };
            self.calibrations.insert((scene, setting), cal);
        }
        Ok(self.calibrations.get(&(scene, setting)))
    }

    /// Runs the calibration of a scene and setting (first seed), its images
    /// and logs in `calibration/`.
    fn measure(&self, scene: usize, setting: usize, vars: &Vars) -> Result<Option<Calibration>> {
        let (sc, st) = (&self.c.scenes[scene], &self.c.settings[setting]);
        let template = st.external.as_deref().unwrap_or_default();
        let dir = std::path::absolute(self.out.join("calibration"))?;
        std::fs::create_dir_all(&dir)?;
        let spread = st.calibration_seconds.unwrap_or_else(|| {
            let longest = self.c.time.iter().cloned().fold(0.0, f64::max);
            (longest / 4.0).max(2.0)
        });
        let measured = calibrate(spread, |n| {
            let stem = format!("{}__{}__{n}spp", sc.name, st.name);
            let v = Vars {
                spp: Some(n.to_string()),
                seed: Some(self.c.seeds[0].to_string()),
                out: Some(
                    dir.join(format!("{stem}.{}", st.output_ext()))
                        .display()
                        .to_string(),
                ),
                ..vars.clone()
            };
            let args = command::substitute(template, &v);
            let log = dir.join(format!("{stem}.log"));
            let t = command::run_timed(&args, &dir, &log, self.cancel)?;
            if let Some(t) = t {
                (self.log)(&format!("  {n} spp: {t:.3} s"));
            }
            Ok(t)
        })?;
        let Some((points, line)) = measured else {
            return Ok(None);
        };
        (self.log)(&format!(
            "  wall time = {:.3} s + {:.4} s x spp over all runs",
            line.intercept, line.slope
        ));
        Ok(Some(Calibration {
            scene: sc.name.clone(),
            setting: st.name.clone(),
            threads: self.c.resolved_threads(),
            command: command::substitute(template, vars),
            points,
            t0: line.intercept,
            k: line.slope,
        }))
    }
}
