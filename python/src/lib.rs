//! `lumis._lumis`: the native half of the `lumis` Python package.
//!
//! Thin on purpose: each function or class here maps onto the library
//! (`lumis_render::session` for renders, `image_io` and `metrics` for
//! images), and the public API, its defaults and its documentation live in
//! the pure-Python `lumis/__init__.py`. To add a binding, add a function to
//! one of the modules below and register it in [`_lumis`].
//!
//! - `job`: [`job::Job`], a `RenderJob` built from keyword arguments the
//!   way the CLI builds one from its flags;
//! - `session`: a loaded scene ([`session::Session`]) and renders running
//!   on a Rust thread ([`session::Task`]) that Python polls, so Ctrl-C
//!   reaches Python while the GIL is released;
//! - `parts`: merging partial renders (parts) into the whole image;
//! - `rendered`: a render's result as Python values;
//! - `study`: studies (`lumis study`), whole or one run at a time, with
//!   run flags made into jobs as the CLI makes them
//!   (`lumis_render::session::job_from_flags`);
//! - `thread`: work on a Rust thread, waited for without the GIL;
//! - `images`: reading, writing and comparing images;
//! - `errors`: library errors as Python exceptions.

mod errors;
mod images;
mod job;
mod params;
mod parts;
mod rendered;
mod session;
mod study;
mod thread;

use pyo3::prelude::*;

#[pymodule]
fn _lumis(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add_class::<job::Job>()?;
    m.add_class::<session::Session>()?;
    m.add_class::<session::Loading>()?;
    m.add_class::<session::Task>()?;
    m.add_function(wrap_pyfunction!(session::load, m)?)?;
    m.add_function(wrap_pyfunction!(params::parameters, m)?)?;
    m.add_class::<parts::Merger>()?;
    m.add_class::<study::StudyTask>()?;
    m.add_function(wrap_pyfunction!(study::study_runs, m)?)?;
    m.add_function(wrap_pyfunction!(study::job_from_flags, m)?)?;
    m.add_function(wrap_pyfunction!(study::start_study, m)?)?;
    m.add_function(wrap_pyfunction!(images::read_image, m)?)?;
    m.add_function(wrap_pyfunction!(images::write_image, m)?)?;
    m.add_function(wrap_pyfunction!(images::compare, m)?)?;
    Ok(())
}
