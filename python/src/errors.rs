//! Library errors as Python exceptions: scene diagnostics become
//! `SceneError` (a `ValueError`) with their location as attributes.

use lumis_render::image_io::ImageError;
use lumis_render::session::SessionError;
use lumis_scene::Diagnostic;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    lumis,
    SceneError,
    PyValueError,
    "A scene could not be read or built.\n\n\
     `str(e)` is the full diagnostic (file:line:column, the line, a caret, a hint);\n\
     `e.message` the message alone, `e.file`, `e.line` and `e.column` where it is\n\
     (None when it has no location, e.g. a missing file or an unknown integrator),\n\
     and `e.help` the hint, if any. A keyword argument's value is located in a\n\
     \"file\" named after the keyword, e.g. `caustic_photons=`."
);

/// `d` as a [`SceneError`].
pub fn scene_error(d: &Diagnostic) -> PyErr {
    Python::attach(|py| {
        let err = SceneError::new_err(d.to_string());
        let v = err.value(py);
        let loc = d.loc.as_ref();
        let set = || -> PyResult<()> {
            v.setattr("message", &d.message)?;
            v.setattr("file", loc.map(|l| l.file.path.clone()))?;
            v.setattr("line", loc.map(|l| l.line))?;
            v.setattr("column", loc.map(|l| l.col))?;
            v.setattr("help", d.help.clone())?;
            Ok(())
        };
        match set() {
            Ok(()) => err,
            Err(e) => e,
        }
    })
}

/// A session's error: a located scene error, or a `RuntimeError`.
pub fn session_error(e: SessionError) -> PyErr {
    match e {
        SessionError::Scene(d) => scene_error(&d),
        SessionError::Other(m) => PyRuntimeError::new_err(m),
    }
}

/// An image file's error: `OSError` when the file could not be read or
/// written, `ValueError` for a bad extension or contents.
pub fn image_error(e: ImageError) -> PyErr {
    match e {
        ImageError::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}
