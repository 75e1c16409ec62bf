//! Partial renders merged: the parts (`Checkpoint::encode` bytes, or
//! their files) of one render combined into the whole render's image, bit
//! for bit what one render of the whole job gives (`session::Merger`),
//! one part at a time, so a merge holds one film, not every part.

use crate::errors::session_error;
use crate::rendered::{rendered_tuple, Rendered};
use lumis_render::session::{merged_image, Merger as LibMerger, Part, SessionError};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyTuple};
use std::path::PathBuf;
use std::sync::{Mutex, PoisonError};

/// A part as given: its bytes or its file.
enum PartArg {
    Bytes(Vec<u8>),
    Path(PathBuf),
}

impl PartArg {
    fn from_py(p: &Bound<'_, PyAny>) -> PyResult<PartArg> {
        // Bytes are read as bytes, not as a sequence of integers.
        match p.cast::<PyBytes>() {
            Ok(b) => Ok(PartArg::Bytes(b.as_bytes().to_vec())),
            Err(_) => Ok(PartArg::Path(p.extract()?)),
        }
    }

    fn read(self, name: &str) -> Result<Part, SessionError> {
        match self {
            PartArg::Bytes(b) => Part::decode(&b, name),
            PartArg::Path(f) => Part::read(&f),
        }
    }
}

/// A merge of parts given one at a time (`add`), in any order, then
/// `finish(outputs)`: the tuple of `Task.result()`. Errors (parts of
/// different renders, a gap or an overlap, an unfinished part) are the
/// library's, as `RuntimeError`.
#[pyclass(module = "lumis._lumis", frozen)]
pub struct Merger {
    /// None once finished.
    inner: Mutex<Option<LibMerger>>,
}

#[pymethods]
impl Merger {
    #[new]
    fn new() -> Merger {
        Merger {
            inner: Mutex::new(Some(LibMerger::default())),
        }
    }

    /// Parts added so far.
    fn __len__(&self) -> usize {
        self.lock().as_ref().map_or(0, LibMerger::len)
    }

    /// Adds a part (bytes, or a path to its file); `name` labels it in
    /// errors (default: `part N`, or its path).
    #[pyo3(signature = (part, name = None))]
    fn add(&self, py: Python<'_>, part: &Bound<'_, PyAny>, name: Option<String>) -> PyResult<()> {
        let arg = PartArg::from_py(part)?;
        let mut guard = self.lock();
        let m = guard
            .as_mut()
            .ok_or_else(|| PyRuntimeError::new_err("this merge is finished"))?;
        let name = name.unwrap_or_else(|| format!("part {}", m.len() + 1));
        py.detach(|| m.add(&arg.read(&name)?))
            .map_err(session_error)
    }

    /// Loads the scene from the parts' job, checks the ranges and gives
    /// the whole render's result; `outputs`: images to write (None: none).
    #[pyo3(signature = (outputs = None))]
    fn finish<'py>(
        &self,
        py: Python<'py>,
        outputs: Option<Vec<PathBuf>>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let m = self
            .lock()
            .take()
            .ok_or_else(|| PyRuntimeError::new_err("this merge is finished"))?;
        let r = py
            .detach(move || merged(m, outputs))
            .map_err(session_error)?;
        rendered_tuple(py, r)
    }

    /// The parts, finished and tiling a range `A..B`, as one part of
    /// `A..B` (bytes), for merging in a tree; loads the scene.
    fn finish_part<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let m = self
            .lock()
            .take()
            .ok_or_else(|| PyRuntimeError::new_err("this merge is finished"))?;
        let bytes = py
            .detach(move || m.finish_part().map(|p| p.checkpoint.encode()))
            .map_err(session_error)?;
        Ok(PyBytes::new(py, &bytes))
    }
}

impl Merger {
    fn lock(&self) -> std::sync::MutexGuard<'_, Option<LibMerger>> {
        self.inner.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

fn merged(m: LibMerger, outputs: Option<Vec<PathBuf>>) -> Result<Rendered, SessionError> {
    let parts = m.len();
    let (session, out) = m.finish(outputs)?;
    let img = merged_image(&session, &out, parts, None);
    Ok(Rendered::from_session(&session, &out, img, None))
}
