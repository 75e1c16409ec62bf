//! What a render (or a merge of parts) gives back, and its conversion to
//! the tuple `Task.result()` returns.

use lumis_render::integrator::photon::PhotonStats;
use lumis_render::integrator::RenderOutcome;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyBytes, PyDict, PyTuple};
use std::path::PathBuf;

/// What a render gives back.
pub struct Rendered {
    pub width: u32,
    pub height: u32,
    pub data: Vec<f32>,
    pub metadata: Vec<(String, String)>,
    pub stats: Stats,
    pub written: Vec<PathBuf>,
    pub write_error: Option<String>,
    /// A partial render's part (`Checkpoint::encode`).
    pub part: Option<Vec<u8>>,
}

impl Rendered {
    /// `img` of `out`, written to the session's outputs if it has any (a
    /// failed write is reported with the image, which stays returned).
    pub fn from_session(
        s: &lumis_render::session::Session,
        out: &RenderOutcome,
        img: lumis_render::image_io::RgbImage,
        part: Option<Vec<u8>>,
    ) -> Rendered {
        let (written, write_error) = match s.outputs.is_empty() {
            true => (Vec::new(), None),
            false => match s.write(&img) {
                Ok(w) => (w, None),
                Err(e) => (Vec::new(), Some(e.to_string())),
            },
        };
        Rendered {
            width: img.width,
            height: img.height,
            stats: stats(out, s.loaded.options.integrator.name()),
            data: img.data,
            metadata: img.metadata,
            written,
            write_error,
            part,
        }
    }
}

/// The render's figures, for `Image.stats`.
pub struct Stats {
    spp: u32,
    seconds: f64,
    rays: u64,
    interrupted: bool,
    bad_samples: u64,
    first_bad: Option<(u32, u32, u32)>,
    integrator: String,
    photons: Option<PhotonStats>,
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

/// A render's result as `Task.result` gives it.
pub fn rendered_tuple<'py>(py: Python<'py>, r: Rendered) -> PyResult<Bound<'py, PyTuple>> {
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
    let part = r.part.map(|b| PyBytes::new(py, &b));
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
            part.into_pyobject(py)?.into_any(),
        ],
    )
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
