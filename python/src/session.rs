//! Loading and rendering off the Python thread. A library `Session` is
//! built (parse, load, acceleration) and rendered on a Rust thread of its
//! own; Python waits for it in short slices with the GIL released
//! ([`Task::wait`]), so its signal handlers run in between: Ctrl-C raises
//! `KeyboardInterrupt` in the caller, which sets the render's cancel flag
//! ([`Task::cancel`]); the driver stops after the current pass and the
//! image so far is the result.

use crate::errors::session_error;
use crate::job::Job;
use lumis_render::integrator::photon::PhotonStats;
use lumis_render::integrator::{Progress, RenderHooks, RenderOutcome};
use lumis_render::session::{check_writable, RenderJob, Session as LibSession, SessionError};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyDict, PyTuple};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::time::Duration;

/// A value another thread puts once, and waiting for it.
struct Slot<T> {
    value: Mutex<Option<T>>,
    ready: Condvar,
    done: AtomicBool,
}

impl<T> Slot<T> {
    fn new() -> Arc<Slot<T>> {
        Arc::new(Slot {
            value: Mutex::new(None),
            ready: Condvar::new(),
            done: AtomicBool::new(false),
        })
    }

    fn lock(&self) -> MutexGuard<'_, Option<T>> {
        self.value.lock().unwrap_or_else(PoisonError::into_inner)
    }

    fn put(&self, v: T) {
        *self.lock() = Some(v);
        self.done.store(true, Ordering::SeqCst);
        self.ready.notify_all();
    }

    /// Whether the value is there, waiting at most `timeout` (None: until it is).
    fn wait(&self, timeout: Option<Duration>) -> bool {
        let guard = self.lock();
        let ready = |_: &mut Option<T>| !self.done.load(Ordering::SeqCst);
        match timeout {
            None => drop(self.ready.wait_while(guard, ready)),
            Some(t) => drop(self.ready.wait_timeout_while(guard, t, ready)),
        }
        self.done.load(Ordering::SeqCst)
    }

    fn take(&self) -> Option<T> {
        self.lock().take()
    }
}

/// Runs `f` on a new thread; its value (or its panic, as an error) goes
/// to the returned slot.
fn spawn<T: Send + 'static>(
    what: &'static str,
    f: impl FnOnce() -> Result<T, SessionError> + Send + 'static,
) -> PyResult<Arc<Slot<Result<T, SessionError>>>> {
    let slot = Slot::new();
    let out = slot.clone();
    std::thread::Builder::new()
        .name(format!("lumis-{what}"))
        .spawn(move || {
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
            out.put(r.unwrap_or_else(|p| {
                let msg = p
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| p.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                Err(SessionError::Other(format!(
                    "lumis: the {what} panicked: {msg}"
                )))
            }));
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a thread: {e}")))?;
    Ok(slot)
}

fn wait_detached<T: Send>(py: Python<'_>, slot: &Arc<Slot<T>>, timeout: Option<f64>) -> bool {
    let timeout = timeout.map(|t| Duration::from_secs_f64(t.max(0.0)));
    py.detach(|| slot.wait(timeout))
}

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
            inner: Arc::new(Mutex::new(s)),
        }
    }
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

/// What a render gives back.
struct Rendered {
    width: u32,
    height: u32,
    data: Vec<f32>,
    metadata: Vec<(String, String)>,
    stats: Stats,
    written: Vec<PathBuf>,
    write_error: Option<String>,
}

/// The render's figures, for `Image.stats`.
struct Stats {
    spp: u32,
    seconds: f64,
    rays: u64,
    interrupted: bool,
    bad_samples: u64,
    first_bad: Option<(u32, u32, u32)>,
    integrator: String,
    photons: Option<PhotonStats>,
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
    s.settings = lumis_render::session::run_settings(&job, &s.loaded.options);
    s.outputs = job.outputs.iter().map(|p| job.resolve(p)).collect();
    for o in &s.outputs {
        check_writable(o)?;
    }
    s.job = job;
    let report = |p: &Progress| {
        *progress.lock().unwrap_or_else(PoisonError::into_inner) = Some(*p);
    };
    let out = s.render(RenderHooks {
        progress: &report,
        cancel,
        after_pass: None,
        resume: None,
    });
    let img = s.image(&out, None);
    let (written, write_error) = match s.outputs.is_empty() {
        true => (Vec::new(), None),
        false => match s.write(&img) {
            Ok(w) => (w, None),
            Err(e) => (Vec::new(), Some(e.to_string())),
        },
    };
    Ok(Rendered {
        width: img.width,
        height: img.height,
        stats: stats(&out, s.loaded.options.integrator.name()),
        data: img.data,
        metadata: img.metadata,
        written,
        write_error,
    })
}

fn stats(out: &RenderOutcome, integrator: &str) -> Stats {
    Stats {
        spp: out.spp,
        seconds: out.elapsed.as_secs_f64(),
        rays: out.rays,
        interrupted: out.interrupted,
        bad_samples: out.bad_samples,
        first_bad: out.first_bad.map(|b| (b.x, b.y, b.sample)),
        integrator: integrator.to_string(),
        photons: out.photon_stats.clone(),
    }
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

    /// `(pixels, width, height, metadata, stats, written, write_error)`:
    /// the image as a bytearray of float32 RGB (row-major, top row first),
    /// the metadata its EXR would carry, the render's figures, the files
    /// written and the error writing them, if any.
    fn result<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let r = match self.slot.take() {
            None => {
                return Err(PyRuntimeError::new_err(
                    "the render has not ended (or was taken)",
                ))
            }
            Some(Err(e)) => return Err(session_error(e)),
            Some(Ok(r)) => r,
        };
        let pixels = floats_to_bytearray(py, &r.data)?;
        let metadata = PyDict::new(py);
        for (k, v) in &r.metadata {
            metadata.set_item(k, v)?;
        }
        let st = &r.stats;
        let stats = PyDict::new(py);
        stats.set_item("spp", st.spp)?;
        stats.set_item("seconds", st.seconds)?;
        stats.set_item("rays", st.rays)?;
        stats.set_item("interrupted", st.interrupted)?;
        stats.set_item("bad_samples", st.bad_samples)?;
        stats.set_item("first_bad_sample", st.first_bad)?;
        stats.set_item("integrator", &st.integrator)?;
        let photons = match &st.photons {
            None => None,
            Some(ps) => Some(photon_stats(py, ps)?),
        };
        stats.set_item("photons", photons)?;
        PyTuple::new(
            py,
            [
                pixels.into_any(),
                r.width.into_pyobject(py)?.into_any(),
                r.height.into_pyobject(py)?.into_any(),
                metadata.into_any(),
                stats.into_any(),
                r.written.into_pyobject(py)?.into_any(),
                r.write_error.into_pyobject(py)?.into_any(),
            ],
        )
    }
}

/// The photon passes' figures, as `lumis` prints them.
fn photon_stats<'py>(py: Python<'py>, ps: &PhotonStats) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("global_stored", ps.global_stored)?;
    d.set_item("caustic_stored", ps.caustic_stored)?;
    d.set_item("trace_seconds", ps.trace_time.as_secs_f64())?;
    d.set_item("build_seconds", ps.build_time.as_secs_f64())?;
    d.set_item("radiance_seconds", ps.radiance_time.as_secs_f64())?;
    d.set_item("memory_bytes", ps.memory_bytes)?;
    if ps.iterations > 0 {
        d.set_item("iterations", ps.render_iterations)?;
        d.set_item("iteration_photons", ps.iteration_photons.0)?;
        d.set_item("iteration_caustic_photons", ps.iteration_photons.1)?;
        d.set_item("caustic_radius", ps.caustic_radius)?;
        d.set_item("counts_chosen", ps.counts_chosen)?;
    }
    Ok(d)
}

/// `data` as the bytes of native float32s, in a bytearray (numpy views it
/// without a copy, writable).
pub fn floats_to_bytearray<'py>(
    py: Python<'py>,
    data: &[f32],
) -> PyResult<Bound<'py, PyByteArray>> {
    PyByteArray::new_with(py, data.len() * 4, |buf| {
        for (b, v) in buf.chunks_exact_mut(4).zip(data) {
            b.copy_from_slice(&v.to_ne_bytes());
        }
        Ok(())
    })
}

/// Native float32 bytes as floats (`ValueError` unless `w * h * 3` of them).
pub fn bytes_to_floats(bytes: &[u8], w: u32, h: u32) -> PyResult<Vec<f32>> {
    let n = w as usize * h as usize * 3;
    if bytes.len() != n * 4 {
        return Err(PyValueError::new_err(format!(
            "{} bytes for a {w}x{h} RGB float32 image (expected {})",
            bytes.len(),
            n * 4
        )));
    }
    Ok(bytes
        .chunks_exact(4)
        .map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]]))
        .collect())
}
