//! Studies from Python: the list of a study's runs, and a study (all its
//! runs and the report, as `lumis study`) or one of its runs, on a Rust
//! thread that Python waits for in slices (Ctrl-C stops it after the
//! current run; finished runs are kept). A run's flags become a job as the
//! CLI's flags do (the library's `session::job_from_flags`).

use crate::errors::session_error;
use crate::thread::{spawn, wait_detached, Slot};
use lumis_render::session::{self as lib, SessionError};
use lumis_render::study::{self, Config, OneRun, StudyRun};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

fn load(config: &Path) -> Result<Config, SessionError> {
    Config::load(config).map_err(|e| SessionError::Other(e.to_string()))
}

/// The runs of the study `config`: `(id, render arguments, external)`
/// each, in the order the study runs them.
#[pyfunction]
pub fn study_runs(py: Python<'_>, config: PathBuf) -> PyResult<Vec<(String, Vec<String>, bool)>> {
    let c = py.detach(|| load(&config)).map_err(session_error)?;
    Ok(study::plan(&c)
        .into_iter()
        .map(|r| (r.id, r.args, r.external))
        .collect())
}

/// The job that the `lumis render` arguments `args` describe (as a study
/// run's flags become its job); `ValueError` for flags it does not know.
#[pyfunction]
pub fn job_from_flags(args: Vec<String>) -> PyResult<crate::job::Job> {
    let job = lib::job_from_flags(&args).map_err(PyValueError::new_err)?;
    Ok(crate::job::Job { job })
}

/// What a study task gives back.
enum Done {
    Study(study::StudyOutcome),
    One(String, Box<OneRun>),
}

/// Starts the study `config` writing to `out` (None: its default folder),
/// or with `run`, only that run of it. `quiet`: no progress lines.
#[pyfunction]
#[pyo3(signature = (config, out = None, command = String::new(), run = None, quiet = false))]
pub fn start_study(
    config: PathBuf,
    out: Option<PathBuf>,
    command: String,
    run: Option<String>,
    quiet: bool,
) -> PyResult<StudyTask> {
    let cancel = Arc::new(AtomicBool::new(false));
    let c2 = cancel.clone();
    let slot = spawn("study", move || {
        let c = load(&config)?;
        let out = out.unwrap_or_else(|| study::default_out(&config));
        let out = std::path::absolute(&out).unwrap_or(out);
        let log = |m: &str| {
            if !quiet || !m.ends_with("skipped") {
                eprintln!("{m}");
            }
        };
        let a = StudyRun {
            out,
            command,
            job_for: &lib::job_from_flags,
            cancel: &c2,
            log: &log,
        };
        let err = |e: study::StudyError| SessionError::Other(e.to_string());
        match run {
            None => study::run(&c, &a).map(Done::Study).map_err(err),
            Some(id) => study::run_one(&c, &a, &id)
                .map(|r| Done::One(id, Box::new(r)))
                .map_err(err),
        }
    })?;
    Ok(StudyTask { slot, cancel })
}

/// A study (or one run of it) running on a thread of its own.
#[pyclass(module = "lumis._lumis", frozen)]
pub struct StudyTask {
    slot: Arc<Slot<Result<Done, SessionError>>>,
    cancel: Arc<AtomicBool>,
}

#[pymethods]
impl StudyTask {
    /// Waits (without the GIL) at most `timeout` seconds; whether it ended.
    #[pyo3(signature = (timeout = None))]
    fn wait(&self, py: Python<'_>, timeout: Option<f64>) -> bool {
        wait_detached(py, &self.slot, timeout)
    }

    /// Stops after the current run (finished runs are kept).
    fn cancel(&self) {
        self.cancel.store(true, Ordering::SeqCst);
    }

    /// A study: `{finished, planned, interrupted, report}`; one run:
    /// `{id, status}` (`"rendered"`, `"finished"` before, or
    /// `"interrupted"`) with `spp`, `seconds`, `relmse`, `mse` when done.
    fn result<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        match self.slot.take() {
            None => {
                return Err(PyRuntimeError::new_err(
                    "the study has not ended (or was taken)",
                ))
            }
            Some(Err(e)) => return Err(session_error(e)),
            Some(Ok(Done::Study(s))) => {
                d.set_item("finished", s.finished)?;
                d.set_item("planned", s.planned)?;
                d.set_item("interrupted", s.interrupted)?;
                d.set_item("report", s.report)?;
            }
            Some(Ok(Done::One(id, r))) => {
                d.set_item("id", id)?;
                let (status, rec) = match *r {
                    OneRun::Rendered(r) => ("rendered", Some(r)),
                    OneRun::Finished(r) => ("finished", Some(r)),
                    OneRun::Interrupted => ("interrupted", None),
                };
                d.set_item("status", status)?;
                if let Some(r) = rec {
                    d.set_item("spp", r.spp)?;
                    d.set_item("seconds", r.seconds)?;
                    d.set_item("relmse", r.relmse)?;
                    d.set_item("mse", r.mse)?;
                }
            }
        }
        Ok(d)
    }
}

impl Drop for StudyTask {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::SeqCst);
    }
}
