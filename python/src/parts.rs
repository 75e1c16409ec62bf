//! Partial renders merged: the parts (`Checkpoint::encode` bytes, or
//! their files) of one render combined into the whole render's image, bit
//! for bit what one render of the whole job gives (`session::merge`).

use crate::errors::session_error;
use crate::rendered::{rendered_tuple, stats, Rendered};
use lumis_render::session::{merge as merge_parts, Part, SessionError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyTuple};
use std::path::PathBuf;

/// A part as given: its bytes or its file.
#[derive(FromPyObject)]
pub enum PartArg {
    Bytes(Vec<u8>),
    Path(PathBuf),
}

/// Merges `parts` (bytes or paths, in any order) into the whole render;
/// `outputs`: images to write (None: none). Returns the tuple of
/// `Task.result()`. The scene is loaded again from the parts' job, so its
/// file must be reachable here; errors (parts of different renders, a gap
/// or an overlap, an unfinished part) are the library's, as `RuntimeError`.
#[pyfunction]
#[pyo3(signature = (parts, outputs = None))]
pub fn merge<'py>(
    py: Python<'py>,
    parts: Vec<Bound<'py, PyAny>>,
    outputs: Option<Vec<PathBuf>>,
) -> PyResult<Bound<'py, PyTuple>> {
    let mut given = Vec::with_capacity(parts.len());
    for (i, p) in parts.iter().enumerate() {
        // Bytes are read as bytes, not as a sequence of integers.
        let arg = match p.cast::<PyBytes>() {
            Ok(b) => PartArg::Bytes(b.as_bytes().to_vec()),
            Err(_) => p.extract::<PartArg>()?,
        };
        given.push((i, arg));
    }
    let r = py
        .detach(move || merged(given, outputs))
        .map_err(session_error)?;
    rendered_tuple(py, r)
}

fn merged(
    given: Vec<(usize, PartArg)>,
    outputs: Option<Vec<PathBuf>>,
) -> Result<Rendered, SessionError> {
    let parts = given
        .into_iter()
        .map(|(i, p)| match p {
            PartArg::Bytes(b) => Part::decode(&b, &format!("part {}", i + 1)),
            PartArg::Path(f) => Part::read(&f),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let outputs = outputs.map(|o| {
        o.iter()
            .map(|p| std::path::absolute(p).unwrap_or(p.clone()))
            .collect()
    });
    let (session, out) = merge_parts(&parts, outputs)?;
    let mut img = session.image(&out, None);
    img.metadata
        .push(("lumis:parts".into(), parts.len().to_string()));
    let (written, write_error) = match session.outputs.is_empty() {
        true => (Vec::new(), None),
        false => match session.write(&img) {
            Ok(w) => (w, None),
            Err(e) => (Vec::new(), Some(e.to_string())),
        },
    };
    Ok(Rendered {
        width: img.width,
        height: img.height,
        stats: stats(&out, session.loaded.options.integrator.name()),
        data: img.data,
        metadata: img.metadata,
        written,
        write_error,
        part: None,
    })
}
