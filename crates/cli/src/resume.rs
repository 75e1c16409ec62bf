//! Periodic checkpoint saving during a render (`--checkpoint`).

use lumis_render::checkpoint::Checkpoint;
use lumis_render::integrator::RenderState;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Saves checkpoints: every `every`, and when asked.
pub struct Saver {
    pub path: PathBuf,
    pub every: Duration,
    pub last: Instant,
    /// The session's checkpoint, with an empty state (each save puts the
    /// render's state in).
    pub template: Checkpoint,
    warned: bool,
}

impl Saver {
    pub fn new(path: PathBuf, every: Duration, template: Checkpoint) -> Saver {
        Saver {
            path,
            every,
            last: Instant::now(),
            template,
            warned: false,
        }
    }

    pub fn maybe_save(&mut self, s: &RenderState) {
        if self.last.elapsed() >= self.every {
            self.save(s);
        }
    }

    /// Writes the final state (the film is moved out and back, not copied).
    pub fn save_outcome(&mut self, out: &mut lumis_render::integrator::RenderOutcome) -> bool {
        let placeholder = out.film.clone_header();
        let film = std::mem::replace(&mut out.film, placeholder);
        let st = RenderState {
            film,
            spp_done: out.spp,
            integrator: std::mem::take(&mut out.integrator),
            bad_samples: out.bad_samples,
            first_bad: out.first_bad,
            rays: out.total_rays,
            elapsed: out.total_elapsed,
        };
        let ok = self.save(&st);
        out.film = st.film;
        out.integrator = st.integrator;
        ok
    }

    /// Writes now; a failure is one warning (the render goes on).
    pub fn save(&mut self, s: &RenderState) -> bool {
        self.last = Instant::now();
        match self.template.save_with(s, &self.path) {
            Ok(()) => true,
            Err(e) => {
                if !self.warned {
                    eprintln!("lumis: warning: could not write the checkpoint: {e}");
                    self.warned = true;
                }
                false
            }
        }
    }
}
