//! Partial renders merged: the parts of one render (each a checkpoint of a
//! pass range, `RenderJob::passes`), rendered anywhere and in any split,
//! combine into the bits of the whole render, because every sample depends
//! only on (seed, pixel, index), each integrator's state at a pass follows
//! from the pass number, and the film's sums are exact integers
//! (`film/exact.rs`). Parts of other scenes, settings or lumis versions, an
//! unfinished part, and ranges that overlap or leave a gap are refused.

use super::{RenderJob, Session, SessionError};
use crate::checkpoint::Checkpoint;
use crate::integrator::driver::min_bad;
use crate::integrator::{RayCounts, RenderOutcome};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Duration;

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

    /// Its passes; a whole render's checkpoint is the part `0..total`.
    fn range(&self, total: u32) -> Range<u32> {
        self.job.passes.clone().unwrap_or(0..total)
    }
}

/// What must be equal in the jobs of one render's parts (the scene hash
/// checks the scene's content and the settings derived from the rest;
/// this adds what the hash leaves to the job: the ray-tracing backend,
/// whose rays may differ in their last bits). Overrides are compared
/// without their origin, a label for diagnostics (`--resolution` from the
/// CLI, `resolution=` from Python: parts of both merge).
fn same_render(a: &RenderJob, b: &RenderJob) -> bool {
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
    let err = |m: String| Err(SessionError::Other(m));
    let Some(first) = parts.first() else {
        return err("nothing to merge: give the parts of a render".into());
    };
    for p in &parts[1..] {
        if p.checkpoint.scene_hash != first.checkpoint.scene_hash
            || !same_render(&p.job, &first.job)
        {
            return err(format!(
                "{} and {} are parts of different renders (another scene, other settings, or \
                 a scene file changed between them)",
                first.name, p.name
            ));
        }
    }
    // The whole render's job, made here: outputs in this folder.
    let mut job = first.job.clone();
    job.scene = job.scene.as_ref().map(|p| job.resolve(p));
    job.dir = std::env::current_dir().unwrap_or_default();
    job.passes = None;
    job.checkpoint = None;
    job.outputs = outputs.clone().unwrap_or_default();
    let session = match outputs {
        Some(_) => Session::new(job)?,
        None => Session::without_outputs(job)?,
    };
    if session.hash != first.checkpoint.scene_hash {
        return err(format!(
            "{}: the scene or a file it reads has changed since the parts were rendered \
             (scene hash {:016x}, now {:016x})",
            first.name, first.checkpoint.scene_hash, session.hash
        ));
    }
    let s = &session.settings;
    let Some(total) = s.pass_count() else {
        return err("a render with only a time budget has no passes to merge".into());
    };
    let mut order: Vec<&Part> = parts.iter().collect();
    order.sort_by_key(|p| p.range(total).start);
    let mut next = 0;
    for p in &order {
        let r = p.range(total);
        let done = p.checkpoint.state.spp_done;
        if done != s.spp_before(r.end) {
            return err(format!(
                "{} is unfinished: passes {}..{} stopped at {done} of {} samples per pixel \
                 (finish it with `lumis render --resume {}`)",
                p.name,
                r.start,
                r.end,
                s.spp_before(r.end),
                p.name
            ));
        }
        if r.start < next {
            return err(format!(
                "{} (passes {}..{}) overlaps another part, which ends at pass {next}",
                p.name, r.start, r.end
            ));
        }
        if r.start > next {
            return err(format!("passes {next}..{} are missing", r.start));
        }
        next = r.end;
    }
    if next != total {
        return err(format!(
            "passes {next}..{total} are missing (the render has {total})"
        ));
    }
    let mut film = order[0].checkpoint.state.film.clone();
    let (mut bad, mut first_bad, mut rays, mut elapsed) = (0, None, 0, Duration::ZERO);
    for (i, p) in order.iter().enumerate() {
        let st = &p.checkpoint.state;
        if i > 0 {
            film.merge(&st.film)
                .map_err(|e| SessionError::Other(format!("{}: {e}", p.name)))?;
        }
        bad += st.bad_samples;
        first_bad = min_bad(first_bad, st.first_bad);
        rays += st.rays;
        elapsed += st.elapsed;
    }
    let last = &order[order.len() - 1].checkpoint.state;
    let out = RenderOutcome {
        film,
        spp: last.spp_done,
        elapsed,
        rays,
        ray_counts: RayCounts::default(),
        bad_samples: bad,
        first_bad,
        interrupted: false,
        photon_stats: None,
        integrator: last.integrator.clone(),
        total_rays: rays,
        total_elapsed: elapsed,
    };
    Ok((session, out))
}
