//! [`Merger`]: parts merged one at a time, in any order, into one running
//! sum (one film however many parts), then checked against the whole
//! render: into its image ([`Merger::finish`]) or, for a merge in a tree,
//! into one part of the range they tile ([`Merger::finish_part`]).

use super::merge::same_render;
use super::{Part, RenderJob, Session, SessionError};
use crate::checkpoint::Checkpoint;
use crate::integrator::driver::min_bad;
use crate::integrator::{RayCounts, RenderOutcome, RenderState};
use std::ops::Range;
use std::path::PathBuf;
use std::time::Duration;

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
    /// an overlap. See [`merge`](super::merge).
    pub fn finish(
        self,
        outputs: Option<Vec<PathBuf>>,
    ) -> Result<(Session, RenderOutcome), SessionError> {
        let (session, sum) = self.checked(outputs, true)?;
        let out = RenderOutcome {
            film: sum.state.film,
            spp: sum.state.spp_done,
            elapsed: sum.state.elapsed,
            rays: sum.state.rays,
            ray_counts: RayCounts::default(),
            bad_samples: sum.state.bad_samples,
            first_bad: sum.state.first_bad,
            interrupted: false,
            photon_stats: None,
            integrator: sum.state.integrator,
            total_rays: sum.state.rays,
            total_elapsed: sum.state.elapsed,
        };
        Ok((session, out))
    }

    /// The parts, which must be finished and tile a range of passes
    /// `A..B` without a gap or an overlap, as one part of `A..B`: a part
    /// of their render like any other, so parts can be merged in a tree
    /// (e.g. on the machines that rendered them) and the sum of sums is
    /// the same exact sum. Loads the scene, as [`Merger::finish`] does.
    pub fn finish_part(self) -> Result<Part, SessionError> {
        let (_, sum) = self.checked(None, false)?;
        let mut job = sum.job;
        job.passes = Some(sum.passes.clone());
        let checkpoint = Checkpoint {
            lumis_version: env!("CARGO_PKG_VERSION").into(),
            scene_hash: sum.hash,
            job: job.to_json(),
            state: sum.state,
        };
        Ok(Part {
            name: format!("passes {}..{}", sum.passes.start, sum.passes.end),
            job,
            checkpoint,
        })
    }

    /// The parts' sum, checked against the whole render's session (loaded
    /// again): the same scene hash, and ranges that are finished and tile
    /// `0..N` (`whole`) or some `A..B`.
    fn checked(
        self,
        outputs: Option<Vec<PathBuf>>,
        whole: bool,
    ) -> Result<(Session, Sum), SessionError> {
        let err = |m: String| Err(SessionError::Other(m));
        let (Some((name, job, hash)), Some(film), Some(last)) = (self.first, self.film, self.last)
        else {
            return err("nothing to merge: give the parts of a render".into());
        };
        let session = whole_session(&job, outputs)?;
        if session.hash != hash {
            return err(format!(
                "{name}: the scene or a file it reads has changed since the parts were rendered \
                 (scene hash {hash:016x}, now {:016x})",
                session.hash
            ));
        }
        let passes = check_ranges(&session, self.seen, whole)?;
        let state = RenderState {
            film,
            spp_done: last.1,
            integrator: last.2,
            bad_samples: self.bad,
            first_bad: self.first_bad,
            rays: self.rays,
            elapsed: self.elapsed,
        };
        let sum = Sum {
            job,
            hash,
            passes,
            state,
        };
        Ok((session, sum))
    }
}

/// The image of a merge of `parts` parts (the session's image, recording
/// the number of parts).
pub fn merged_image(
    session: &Session,
    out: &RenderOutcome,
    parts: usize,
    command: Option<&str>,
) -> crate::image_io::RgbImage {
    let mut img = session.image(out, command);
    img.metadata.push(("lumis:parts".into(), parts.to_string()));
    img
}

/// The parts' sum and what it is of.
struct Sum {
    job: RenderJob,
    hash: u64,
    passes: Range<u32>,
    state: RenderState,
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

/// Refuses unfinished parts, and ranges that overlap or leave a gap in
/// `0..N` (`whole`) or in the range from the first part's start to the
/// last part's end, which it returns.
fn check_ranges(
    session: &Session,
    mut seen: Vec<Seen>,
    whole: bool,
) -> Result<Range<u32>, SessionError> {
    let err = |m: String| Err(SessionError::Other(m));
    let s = &session.settings;
    let Some(total) = s.pass_count() else {
        return err("a render with only a time budget has no passes to merge".into());
    };
    // A whole render's checkpoint is the part `0..total`.
    let range = |p: &Seen| p.passes.clone().unwrap_or(0..total);
    seen.sort_by_key(|p| range(p).start);
    let first = match whole {
        true => 0,
        false => seen.first().map_or(0, |p| range(p).start),
    };
    let mut next = first;
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
    if whole && next != total {
        return err(format!(
            "passes {next}..{total} are missing (the render has {total})"
        ));
    }
    Ok(first..next)
}
