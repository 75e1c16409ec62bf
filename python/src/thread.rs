//! Work on a Rust thread of its own, waited for from Python in short
//! slices with the GIL released (so Ctrl-C reaches Python in between).

use lumis_render::session::SessionError;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::time::Duration;

/// A value another thread puts once, and waiting for it.
pub struct Slot<T> {
    value: Mutex<Option<T>>,
    ready: Condvar,
    pub done: AtomicBool,
}

impl<T> Slot<T> {
    pub fn new() -> Arc<Slot<T>> {
        Arc::new(Slot {
            value: Mutex::new(None),
            ready: Condvar::new(),
            done: AtomicBool::new(false),
        })
    }

    fn lock(&self) -> MutexGuard<'_, Option<T>> {
        self.value.lock().unwrap_or_else(PoisonError::into_inner)
    }

    pub fn put(&self, v: T) {
        *self.lock() = Some(v);
        self.done.store(true, Ordering::SeqCst);
        self.ready.notify_all();
    }

    /// Whether the value is there, waiting at most `timeout` (None: until it is).
    pub fn wait(&self, timeout: Option<Duration>) -> bool {
        let guard = self.lock();
        let ready = |_: &mut Option<T>| !self.done.load(Ordering::SeqCst);
        match timeout {
            None => drop(self.ready.wait_while(guard, ready)),
            Some(t) => drop(self.ready.wait_timeout_while(guard, t, ready)),
        }
        self.done.load(Ordering::SeqCst)
    }

    pub fn take(&self) -> Option<T> {
        self.lock().take()
    }
}

/// Runs `f` on a new thread; its value (or its panic, as an error) goes
/// to the returned slot.
pub fn spawn<T: Send + 'static>(
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

pub fn wait_detached<T: Send>(py: Python<'_>, slot: &Arc<Slot<T>>, timeout: Option<f64>) -> bool {
    let timeout = timeout.map(|t| Duration::from_secs_f64(t.max(0.0)));
    py.detach(|| slot.wait(timeout))
}
