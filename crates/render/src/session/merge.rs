//! Partial renders merged: the parts of one render (each a checkpoint of a
//! pass range, `RenderJob::passes`), rendered anywhere and in any split,
//! combine into the bits of the whole render, because every sample depends
//! only on (seed, pixel, index), each integrator's state at a pass follows
//! from the pass number, and the film's sums are exact integers
//! (`film/exact.rs`). Parts of other scenes, settings or lumis versions, an
//! unfinished part, and ranges that overlap or leave a gap are refused.

use super::{RenderJob, Session, SessionError};
use crate::checkpoint::Checkpoint;
use crate::integrator::RenderOutcome;
use std::path::{Path, PathBuf};

/// One partial render's result, as read from its file or bytes.
#[derive(Clone, Debug)]
pub struct Part {
    /// Its file name (or a label), for errors.
    pub name: String,
    pub job: RenderJob,
    pub checkpoint: Checkpoint,
}

impl Part {
    pub fn read(path: &Path) -> Result<Part, SessionError> {
        let bytes = std::fs::read(path)
            .map_err(|e| SessionError::Other(format!("{}: {e}", path.display())))?;
        Part::decode(&bytes, &path.display().to_string())
    }

    /// A part from the bytes of its file (`Checkpoint::encode`).
    pub fn decode(bytes: &[u8], name: &str) -> Result<Part, SessionError> {
        let checkpoint =
            Checkpoint::decode(bytes, name).map_err(|e| SessionError::Other(e.to_string()))?;
        let job = RenderJob::from_json(&checkpoint.job)
            .map_err(|e| SessionError::Other(format!("{name}: {e}")))?;
        Ok(Part {
            name: name.to_string(),
            job,
            checkpoint,
        })
    }
}

/// What must be equal in the jobs of one render's parts (the scene hash
/// checks the scene's content and the settings derived from the rest;
/// this adds what the hash leaves to the job: the ray-tracing backend,
/// whose rays may differ in their last bits). Overrides are compared
/// without their origin, a label for diagnostics (`--resolution` from the
/// CLI, `resolution=` from Python: parts of both merge).
pub(super) fn same_render(a: &RenderJob, b: &RenderJob) -> bool {
    let overrides = |j: &RenderJob| -> Vec<(String, Option<String>, String)> {
        j.overrides
            .items
            .iter()
            .map(|o| (o.directive.clone(), o.ty.clone(), o.params.clone()))
            .collect()
    };
    (
        overrides(a),
        a.seed,
        a.budget.spp,
        a.clamp,
        a.accel,
        a.inject_nan,
    ) == (
        overrides(b),
        b.seed,
        b.budget.spp,
        b.clamp,
        b.accel,
        b.inject_nan,
    )
}

/// Merges `parts` into the whole render's outcome, with the session of the
/// whole job (loaded again from the first part's job, so the scene must be
/// reachable where the merge runs). `outputs`: the images the session will
/// write (empty: the scene's default names); `None`: none.
pub fn merge(
    parts: &[Part],
    outputs: Option<Vec<PathBuf>>,
) -> Result<(Session, RenderOutcome), SessionError> {
    let mut m = super::Merger::default();
    for p in parts {
        m.add(p)?;
    }
    m.finish(outputs)
}
