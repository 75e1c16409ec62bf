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
    let mut m = Merger::default();
    for p in parts {
        m.add(p)?;
    }
    m.finish(outputs)
}

/// What a merge keeps of a part once its film is added.
struct Seen {
    name: String,
    passes: Option<Range<u32>>,
    spp_done: u32,
}

/// A merge that takes the parts one at a time, in any order, keeping one
/// film (the sum so far) and a few figures of each part: the memory of a
/// merge of many parts is one part's, not all of theirs.
#[derive(Default)]
pub struct Merger {
    /// The first part's job and scene hash, which the others must share.
    first: Option<(String, RenderJob, u64)>,
    film: Option<crate::film::Film>,
    seen: Vec<Seen>,
    /// The integrator's state of the part latest in the render.
    last: Option<(u32, u32, Vec<u8>)>,
    bad: u64,
    first_bad: Option<crate::integrator::BadSample>,
    rays: u64,
    elapsed: Duration,
}

impl Merger {
    /// Parts added so far.
    pub fn len(&self) -> usize {
        self.seen.len()
    }

    pub fn is_empty(&self) -> bool {
        self.seen.is_empty()
    }

    /// Adds `p`'s film and figures; a part of another render than the
    /// first one's is refused.
    pub fn add(&mut self, p: &Part) -> Result<(), SessionError> {
        let st = &p.checkpoint.state;
        match &self.first {
            None => {
                self.first = Some((p.name.clone(), p.job.clone(), p.checkpoint.scene_hash));
                self.film = Some(st.film.clone());
            }
            Some((name, job, hash)) => {
                if p.checkpoint.scene_hash != *hash || !same_render(&p.job, job) {
                    return Err(SessionError::Other(format!(
                        "{name} and {} are parts of different renders (another scene, other \
                         settings, or a scene file changed between them)",
                        p.name
                    )));
                }
                let film = self.film.as_mut().expect("a film with the first part");
                film.merge(&st.film)
                    .map_err(|e| SessionError::Other(format!("{}: {e}", p.name)))?;
            }
        }
        let start = p.job.passes.as_ref().map_or(0, |r| r.start);
        if self.last.as_ref().is_none_or(|(s, _, _)| start >= *s) {
            self.last = Some((start, st.spp_done, st.integrator.clone()));
        }
        self.bad += st.bad_samples;
        self.first_bad = min_bad(self.first_bad, st.first_bad);
        self.rays += st.rays;
        self.elapsed += st.elapsed;
        self.seen.push(Seen {
            name: p.name.clone(),
            passes: p.job.passes.clone(),
            spp_done: st.spp_done,
        });
        Ok(())
    }

    /// The whole render's session and outcome, once the parts' ranges are
    /// checked: finished, and tiling the render's passes without a gap or
    /// an overlap. See [`merge`].
    pub fn finish(
        self,
        outputs: Option<Vec<PathBuf>>,
    ) -> Result<(Session, RenderOutcome), SessionError> {
        let err = |m: String| Err(SessionError::Other(m));
        let (Some((name, first_job, hash)), Some(film), Some(last)) =
            (self.first, self.film, self.last)
        else {
            return err("nothing to merge: give the parts of a render".into());
        };
        let session = whole_session(&first_job, outputs)?;
        if session.hash != hash {
            return err(format!(
                "{name}: the scene or a file it reads has changed since the parts were rendered \
                 (scene hash {hash:016x}, now {:016x})",
                session.hash
            ));
        }
        check_ranges(&session, self.seen)?;
        let out = RenderOutcome {
            film,
            spp: last.1,
            elapsed: self.elapsed,
            rays: self.rays,
            ray_counts: RayCounts::default(),
            bad_samples: self.bad,
            first_bad: self.first_bad,
            interrupted: false,
            photon_stats: None,
            integrator: last.2,
            total_rays: self.rays,
            total_elapsed: self.elapsed,
        };
        Ok((session, out))
    }
}

/// The whole render's session, made here from a part's job: outputs in
/// this folder.
fn whole_session(
    first: &RenderJob,
    outputs: Option<Vec<PathBuf>>,
) -> Result<Session, SessionError> {
    let mut job = first.clone();
    job.scene = job.scene.as_ref().map(|p| job.resolve(p));
    job.dir = std::env::current_dir().unwrap_or_default();
    job.passes = None;
    job.checkpoint = None;
    job.outputs = outputs.clone().unwrap_or_default();
    match outputs {
        Some(_) => Session::new(job),
        None => Session::without_outputs(job),
    }
}

/// Refuses unfinished parts, and ranges that overlap or leave a gap.
fn check_ranges(session: &Session, mut seen: Vec<Seen>) -> Result<(), SessionError> {
    let err = |m: String| Err(SessionError::Other(m));
    let s = &session.settings;
    let Some(total) = s.pass_count() else {
        return err("a render with only a time budget has no passes to merge".into());
    };
    // A whole render's checkpoint is the part `0..total`.
    let range = |p: &Seen| p.passes.clone().unwrap_or(0..total);
    seen.sort_by_key(|p| range(p).start);
    let mut next = 0;
    for p in &seen {
        let r = range(p);
        let done = p.spp_done;
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
    Ok(())
}
