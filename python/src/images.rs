//! Images: reading and writing through `lumis_render::image_io`, and the
//! metrics of `lumis compare` through `lumis_render::metrics`. Pixels cross
//! the boundary as native float32 bytes, RGB, row-major, top row first.

use crate::errors::image_error;
use crate::rendered::{bytes_to_floats, floats_to_bytearray};
use lumis_render::image_io::{read_image as read, write_image as write, RgbImage};
use lumis_render::load::options::crop_bounds;
use lumis_render::metrics::{compare_where, heatmap::write_heatmap, lit_interior, PixelError};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use std::path::PathBuf;

/// `(pixels, width, height, metadata)` of an .exr, .pfm or .png file (PNG
/// decoded from sRGB to linear; metadata: the EXR's text attributes).
#[pyfunction]
pub fn read_image<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyTuple>> {
    let img = py.detach(|| read(&path)).map_err(image_error)?;
    let metadata = PyDict::new(py);
    for (k, v) in &img.metadata {
        metadata.set_item(k, v)?;
    }
    PyTuple::new(
        py,
        [
            floats_to_bytearray(py, &img.data)?.into_any(),
            img.width.into_pyobject(py)?.into_any(),
            img.height.into_pyobject(py)?.into_any(),
            metadata.into_any(),
        ],
    )
}

/// Writes float32 RGB bytes as .exr (with `metadata` as text attributes),
/// .pfm or .png (sRGB, scaled by `2**exposure`), atomically.
#[pyfunction]
#[pyo3(signature = (path, pixels, width, height, metadata = Vec::new(), exposure = 0.0))]
pub fn write_image(
    py: Python<'_>,
    path: PathBuf,
    pixels: &[u8],
    width: u32,
    height: u32,
    metadata: Vec<(String, String)>,
    exposure: f32,
) -> PyResult<()> {
    let mut img = RgbImage::new(width, height, bytes_to_floats(pixels, width, height)?);
    img.metadata = metadata;
    py.detach(|| write(&path, &img, exposure))
        .map_err(image_error)
}

/// The metrics `lumis compare` prints, of `test` against `reference`
/// (each `(pixels, width, height)`), over the region `mask` (fractions
/// x0, x1, y0, y1) and, with `lit`, only where the test image and its
/// eight neighbours are not black; with `heatmap`, writes the per-pixel
/// error map there as `lumis compare --heatmap` does.
#[pyfunction]
#[pyo3(signature = (test, reference, mask = None, lit = false, heatmap = None, heatmap_error = "rel", heatmap_range = None))]
#[allow(clippy::too_many_arguments)]
pub fn compare<'py>(
    py: Python<'py>,
    test: (Bound<'py, PyBytes>, u32, u32),
    reference: (Bound<'py, PyBytes>, u32, u32),
    mask: Option<Bound<'py, PyAny>>,
    lit: bool,
    heatmap: Option<PathBuf>,
    heatmap_error: &str,
    heatmap_range: Option<(f64, f64)>,
) -> PyResult<Bound<'py, PyDict>> {
    let kind = PixelError::from_name(heatmap_error).ok_or_else(|| {
        PyValueError::new_err(format!(
            "unknown heatmap_error `{heatmap_error}` (rel or abs)"
        ))
    })?;
    if let Some((lo, hi)) = heatmap_range {
        if !(lo > 0.0 && hi > lo && hi.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "heatmap_range: need 0 < lo < hi (a log scale), found ({lo}, {hi})"
            )));
        }
    }
    let mask = mask.map(|m| crate::job::fractions(&m)).transpose()?;
    let t = RgbImage::new(
        test.1,
        test.2,
        bytes_to_floats(test.0.as_bytes(), test.1, test.2)?,
    );
    let r = RgbImage::new(
        reference.1,
        reference.2,
        bytes_to_floats(reference.0.as_bytes(), reference.1, reference.2)?,
    );
    let (m, range) = py
        .detach(|| {
            let region = mask.map(|m| crop_bounds((t.width, t.height), m));
            let m = compare_where(&t, &r, region, |x, y| !lit || lit_interior(&t, x, y))?;
            let range = match &heatmap {
                Some(path) => Some(write_heatmap(path, &t, &r, kind, heatmap_range)?),
                None => None,
            };
            Ok::<_, String>((m, range))
        })
        .map_err(PyValueError::new_err)?;
    let d = PyDict::new(py);
    d.set_item("pixels", m.pixels)?;
    d.set_item("mse", m.mse)?;
    d.set_item("rmse", m.rmse)?;
    d.set_item("relmse", m.rel_mse)?;
    d.set_item("mae", m.mae)?;
    d.set_item("mean_test", m.mean_test)?;
    d.set_item("mean_reference", m.mean_ref)?;
    d.set_item("ratio", m.ratio())?;
    if let Some(range) = range {
        d.set_item("heatmap_range", range)?;
    }
    Ok(d)
}
