//! The integrators' own parameters as keyword arguments, from the tables
//! the integrators declare (the library's `session::integrator_params`,
//! which the CLI makes its flags from):
//! `caustic_photons=` for the flag `--caustic-photons`, i.e. for the scene
//! file's `"integer causticphotons"`. The scene-file name is accepted too.

use lumis_render::session::{integrator_params, param_text};
use lumis_scene::ParamSpec;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// Each parameter once (a name two integrators share is one keyword), in
/// table order.
pub fn all() -> Vec<&'static ParamSpec> {
    integrator_params().into_iter().map(|p| p.spec).collect()
}

/// The keyword of `s`: its command-line words with underscores.
pub fn keyword(s: &ParamSpec) -> String {
    s.words.replace('-', "_")
}

/// The parameter `key` names (its keyword or its scene-file name).
pub fn find(key: &str) -> Option<&'static ParamSpec> {
    all()
        .into_iter()
        .find(|s| keyword(s) == key || s.name == key)
}

/// `value` as scene text for a parameter of type `ty`: `True` → `true`,
/// numbers as written, a string quoted for a `string` parameter (as is
/// otherwise, so `"2,3"` works as on the command line), a list or tuple
/// as its items. The library's readers check the result and report a bad
/// value at its keyword.
pub fn scene_text(value: &Bound<'_, PyAny>, ty: &str) -> PyResult<String> {
    if value.is_instance_of::<PyBool>() {
        return Ok(if value.extract::<bool>()? {
            "true"
        } else {
            "false"
        }
        .into());
    }
    if value.is_instance_of::<PyInt>() {
        return Ok(value.str()?.to_string());
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(format!("{:?}", value.extract::<f64>()?));
    }
    if value.is_instance_of::<PyString>() {
        let s: String = value.extract()?;
        if ty == "string" && s.contains('"') {
            return Err(PyTypeError::new_err(format!(
                "a string parameter cannot contain a double quote: {s:?}"
            )));
        }
        // As typed after a flag: `strategy="2,3"` as `--strategy 2,3`.
        return Ok(param_text(ty, &s));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items: PyResult<Vec<String>> = value.try_iter()?.map(|v| scene_text(&v?, ty)).collect();
        return Ok(items?.join(" "));
    }
    // numpy scalars and other numbers.
    if let Ok(i) = value.extract::<i64>() {
        return Ok(i.to_string());
    }
    if let Ok(f) = value.extract::<f64>() {
        return Ok(format!("{f:?}"));
    }
    Err(PyTypeError::new_err(format!(
        "expected a bool, number, string or list, found {}",
        value.get_type().name()?
    )))
}

/// The integrators' parameters: keyword → (scene-file type and name, the
/// values it takes, what it means to each integrator that reads it).
#[pyfunction]
pub fn parameters(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for p in integrator_params() {
        let s = p.spec;
        let entry = PyDict::new(py);
        entry.set_item("type", s.ty)?;
        entry.set_item("name", s.name)?;
        entry.set_item("flag", format!("--{}", s.words))?;
        entry.set_item("value", s.value)?;
        entry.set_item("help", p.help)?;
        out.set_item(keyword(s), entry)?;
    }
    Ok(out)
}
