//! Loading and rendering off the Python thread. A library `Session` is
//! built (parse, load, acceleration) and rendered on a Rust thread of its
//! own; Python waits for it in short slices with the GIL released
//! ([`Task::wait`]), so its signal handlers run in between: Ctrl-C raises
//! `KeyboardInterrupt` in the caller, which sets the render's cancel flag
//! ([`Task::cancel`]); the driver stops after the current pass and the
//! image so far is the result.

use crate::errors::session_error;
use crate::job::Job;
use crate::rendered::{rendered_tuple, Rendered};
use crate::thread::{spawn, wait_detached, Slot};
use lumis_render::integrator::{Progress, RenderHooks};
use lumis_render::session::{check_writable, RenderJob, Session as LibSession, SessionError};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

/// Starts loading `job`'s scene on a thread of its own.
#[pyfunction]
pub fn load(job: PyRef<'_, Job>) -> PyResult<Loading> {
    let job = job.job.clone();
    let slot = spawn("load", move || LibSession::new(job))?;
    Ok(Loading { slot })
}

/// A scene being loaded: `wait()` until it is, then `result()`.
#[pyclass(module = "lumis._lumis", frozen)]
pub struct Loading {
    slot: Arc<Slot<Result<LibSession, SessionError>>>,
}

#[pymethods]
impl Loading {
    /// Waits (without the GIL) at most `timeout` seconds (None: until
    /// loaded); whether it is done.
    #[pyo3(signature = (timeout = None))]
    fn wait(&self, py: Python<'_>, timeout: Option<f64>) -> bool {
        wait_detached(py, &self.slot, timeout)
    }

    /// The loaded session, or the scene's error (`SceneError`).
    fn result(&self) -> PyResult<Session> {
        match self.slot.take() {
            None => Err(PyRuntimeError::new_err("not loaded yet (or taken)")),
            Some(Err(e)) => Err(session_error(e)),
            Some(Ok(s)) => Ok(Session::new(s)),
        }
    }
}

/// A loaded scene: parsed and built once for a job, rendered any number
/// of times with other seeds, time budgets, threads or clamps.
#[pyclass(module = "lumis._lumis", frozen)]
pub struct Session {
    inner: Arc<Mutex<LibSession>>,
    /// The job it was loaded for.
    job: RenderJob,
    warnings: Vec<String>,
    resolution: (u32, u32),
    size: (u32, u32),
    integrator: String,
    spp: u32,
    /// The passes of the loaded job's whole render (None: a time budget alone).
    pass_count: Option<u32>,
    /// Progressive photon mapping: passes per iteration (else 1).
    iteration_passes: u32,
}

impl Session {
    fn new(s: LibSession) -> Session {
        let o = &s.loaded.options;
        Session {
            job: s.job.clone(),
            warnings: s.loaded.warnings.iter().map(|w| w.to_string()).collect(),
            resolution: o.resolution,
            size: (o.crop.width(), o.crop.height()),
            integrator: o.integrator.name().to_string(),
            spp: o.spp,
            pass_count: s.settings.pass_count(),
            iteration_passes: iteration_passes(&s),
            inner: Arc::new(Mutex::new(s)),
        }
    }
}

/// Passes per progressive photon iteration (an iteration renders
/// `iterationspp` samples per pixel in whole passes), 1 otherwise: a part
/// starting mid-iteration traces that iteration's photons again.
fn iteration_passes(s: &LibSession) -> u32 {
    let per_pass = s.settings.spp_per_pass.max(1);
    s.loaded
        .options
        .integrator
        .photon()
        .and_then(|p| p.progressive)
        .map_or(1, |p| p.iteration_spp.max(1).div_ceil(per_pass))
}

/// Whether `job` renders the scene `loaded` was built for, as built: the
/// same scene, parameters, sample count and backend; only the seed, time
/// budget, threads, clamp and outputs may differ.
fn same_build(loaded: &RenderJob, job: &RenderJob) -> bool {
    loaded.scene == job.scene
        && loaded.dir == job.dir
        && loaded.overrides == job.overrides
        && loaded.budget.spp == job.budget.spp
        && loaded.accel == job.accel
        && loaded.inject_nan == job.inject_nan
}

#[pymethods]
impl Session {
    /// The job this scene was loaded for.
    #[getter]
    fn job(&self) -> Job {
        Job {
            job: self.job.clone(),
        }
    }

    /// The scene's warnings (unused parameters, unsupported features...).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// The film's full resolution (width, height).
    #[getter]
    fn resolution(&self) -> (u32, u32) {
        self.resolution
    }

    /// The rendered image's size (width, height): the crop window's.
    #[getter]
    fn size(&self) -> (u32, u32) {
        self.size
    }

    #[getter]
    fn integrator(&self) -> String {
        self.integrator.clone()
    }

    /// Samples per pixel of the scene as loaded.
    #[getter]
    fn spp(&self) -> u32 {
        self.spp
    }

    /// The passes of the whole render as loaded (one sample per pixel
    /// each; None with a time budget alone): a part renders a range of them.
    #[getter]
    fn pass_count(&self) -> Option<u32> {
        self.pass_count
    }

    /// Passes per progressive photon iteration (1 for other integrators):
    /// parts that start on a multiple of it trace no iteration twice.
    #[getter]
    fn iteration_passes(&self) -> u32 {
        self.iteration_passes
    }

    /// Whether `job` can be rendered with this scene as built (see `start`).
    fn can_render(&self, job: PyRef<'_, Job>) -> bool {
        same_build(&self.job, &job.job)
    }

    /// Starts rendering `job` on a thread of its own. The job must be the
    /// loaded one up to its seed, time budget, threads, clamp and outputs
    /// (`can_render`); the settings follow from it as `Session::new` makes
    /// them. Renders of one scene run one at a time.
    fn start(&self, job: PyRef<'_, Job>) -> PyResult<Task> {
        if !same_build(&self.job, &job.job) {
            return Err(PyValueError::new_err(
                "this job changes how the scene is built: load it again",
            ));
        }
        let job = job.job.clone();
        let inner = self.inner.clone();
        let cancel = Arc::new(AtomicBool::new(false));
        let progress = Arc::new(Mutex::new(None::<Progress>));
        let (c, p) = (cancel.clone(), progress.clone());
        let slot = spawn("render", move || {
            let mut s = inner.lock().unwrap_or_else(PoisonError::into_inner);
            run(&mut s, job, &c, &p)
        })?;
        Ok(Task {
            slot,
            cancel,
            progress,
        })
    }
}

/// Renders `job` with the session `s` was loaded for: the job's run
/// settings in place of the loaded ones, then the image, then its outputs
/// if it names any.
fn run(
    s: &mut LibSession,
    job: RenderJob,
    cancel: &AtomicBool,
    progress: &Mutex<Option<Progress>>,
) -> Result<Rendered, SessionError> {
    let outputs: Vec<_> = job.outputs.iter().map(|p| job.resolve(p)).collect();
    for o in &outputs {
        check_writable(o)?;
    }
    s.set_job(job)?;
    s.outputs = outputs;
    let report = |p: &Progress| {
        *progress.lock().unwrap_or_else(PoisonError::into_inner) = Some(*p);
    };
    let out = s.render(RenderHooks {
        progress: &report,
        cancel,
        after_pass: None,
        resume: None,
    });
    let part = s.job.passes.is_some().then(|| s.part(&out).encode());
    let img = s.image(&out, None);
    Ok(Rendered::from_session(s, &out, img, part))
}

/// A render running on a thread of its own: `wait()` in slices, read
/// `progress()`, `cancel()` to stop it after the current pass, then
/// `result()`. Dropping it cancels the render.
#[pyclass(module = "lumis._lumis", frozen)]
pub struct Task {
    slot: Arc<Slot<Result<Rendered, SessionError>>>,
    cancel: Arc<AtomicBool>,
    progress: Arc<Mutex<Option<Progress>>>,
}

impl Drop for Task {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::SeqCst);
    }
}

#[pymethods]
impl Task {
    /// Waits (without the GIL) at most `timeout` seconds (None: until the
    /// render ends); whether it has ended.
    #[pyo3(signature = (timeout = None))]
    fn wait(&self, py: Python<'_>, timeout: Option<f64>) -> bool {
        wait_detached(py, &self.slot, timeout)
    }

    /// Asks the render to stop after its current pass.
    fn cancel(&self) {
        self.cancel.store(true, Ordering::SeqCst);
    }

    #[getter]
    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::SeqCst)
    }

    #[getter]
    fn done(&self) -> bool {
        self.slot.done.load(Ordering::SeqCst)
    }

    /// The latest progress, `(fraction, spp_done, seconds)`, or None
    /// before the first report.
    fn progress(&self) -> Option<(f64, u32, f64)> {
        let p = *self.progress.lock().unwrap_or_else(PoisonError::into_inner);
        p.map(|p| (p.fraction, p.spp_done, p.elapsed.as_secs_f64()))
    }

    /// `(pixels, width, height, metadata, stats, written, write_error,
    /// part)`: the image as a bytearray of float32 RGB (row-major, top row
    /// first), the metadata its EXR would carry, the render's figures, the
    /// files written and the error writing them, if any, and a partial
    /// render's part as bytes (else None).
    fn result<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        match self.slot.take() {
            None => Err(PyRuntimeError::new_err(
                "the render has not ended (or was taken)",
            )),
            Some(Err(e)) => Err(session_error(e)),
            Some(Ok(r)) => rendered_tuple(py, r),
        }
    }
}
