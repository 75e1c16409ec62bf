//! A study's runs one at a time, for front ends that spread them over
//! processes or machines: [`plan`] lists the runs, [`run_one`] renders one
//! into the study's folder and records it as [`run`](super::run) does.
//! Since a study skips the runs it finds finished, a last [`run`](super::run)
//! on the same folder then only measures the summary and writes the report.
//! External settings (other renderers, calibrated at the study's start)
//! are left to that last run.

use super::config::Config;
use super::error::{Context, Result};
use super::store::{RunResult, Store};
use super::{reference, runs, StudyRun};
use crate::study::StudyError;

/// One run of a study.
#[derive(Clone, Debug)]
pub struct PlannedRun {
    /// Its id (file-name stem, unique in the study).
    pub id: String,
    /// Its `lumis render` arguments (without output).
    pub args: Vec<String>,
    /// Whether an external program renders it (not [`run_one`]'s).
    pub external: bool,
}

/// What [`run_one`] did.
pub enum OneRun {
    /// Rendered and recorded now.
    Rendered(RunResult),
    /// Recorded before with the same arguments: nothing done.
    Finished(RunResult),
    /// Cancelled: nothing of it kept.
    Interrupted,
}

/// Every run of `c`, in the order the study runs them.
pub fn plan(c: &Config) -> Vec<PlannedRun> {
    c.runs()
        .iter()
        .map(|r| PlannedRun {
            id: r.id(c),
            args: c.render_args(r),
            external: c.settings[r.setting].external.is_some(),
        })
        .collect()
}

/// Renders the run `id` of `c` into `a.out` (its image, PNG, heatmap and
/// record), unless it is recorded there already.
pub fn run_one(c: &Config, a: &StudyRun, id: &str) -> Result<OneRun> {
    let runs = c.runs();
    let Some(run) = runs.iter().find(|r| r.id(c) == id) else {
        return Err(StudyError(format!("the study has no run `{id}`")));
    };
    if c.settings[run.setting].external.is_some() {
        return Err(StudyError(format!(
            "run `{id}` is an external program's: the study runs those itself"
        )));
    }
    let store = Store::new(&a.out)?;
    let args = c.render_args(run);
    if let Some(r) = store.finished(id, &args) {
        return Ok(OneRun::Finished(r));
    }
    let (r, info) = reference(&c.scenes[run.scene], &a.out, false)?;
    let done = runs::lumis_run(c, a, run, id, &args, &r, &info)
        .with_context(|| format!("run {id} (lumis render {})", args.join(" ")))?;
    match done {
        None => Ok(OneRun::Interrupted),
        Some(r) => {
            store.save(&r)?;
            Ok(OneRun::Rendered(r))
        }
    }
}
