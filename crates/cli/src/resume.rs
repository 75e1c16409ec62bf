//! `--checkpoint` and `--resume`: which command a checkpoint continues, the
//! hash that ties it to its scene and settings, and periodic saving.

use crate::args::{Cli, Command, RenderArgs};
use anyhow::{bail, Context, Result};
use clap::Parser;
use lumis_render::checkpoint::{Checkpoint, Fnv};
use lumis_render::integrator::{RenderSettings, RenderState};
use lumis_render::load::RenderOptions;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The arguments to run and the checkpoint to continue (if `--resume`).
/// `--resume FILE` alone reruns the saved command in its folder, keeping
/// this run's own options (threads, time budget, checkpointing, display,
/// verbosity); with a scene, the given command is used and the hash check
/// decides.
pub fn prepare(a: RenderArgs) -> Result<(RenderArgs, Option<Checkpoint>)> {
    let Some(file) = a.resume.clone() else {
        return Ok((a, None));
    };
    let file = std::path::absolute(&file).unwrap_or(file);
    let ck = Checkpoint::load(&file)?;
    if a.scene.is_some() {
        return Ok((a, Some(ck)));
    }
    let argv = std::iter::once("lumis".to_string()).chain(ck.command.iter().cloned());
    let saved = match Cli::try_parse_from(argv) {
        Ok(Cli {
            command: Some(Command::Render(r)),
        }) => *r,
        Ok(_) => RenderArgs::default(),
        Err(e) => bail!(
            "{}: the saved command no longer parses: {e}",
            file.display()
        ),
    };
    if !ck.cwd.is_empty() && Path::new(&ck.cwd) != std::env::current_dir()?.as_path() {
        std::env::set_current_dir(&ck.cwd)
            .with_context(|| format!("{}: the render's folder {}", file.display(), ck.cwd))?;
    }
    let own = a;
    let merged = RenderArgs {
        threads: own.threads.or(saved.threads),
        time: own.time,
        quiet: own.quiet,
        verbose: own.verbose,
        stats: own.stats,
        display_server: own.display_server,
        checkpoint: Some(own.checkpoint.unwrap_or_else(|| file.clone())),
        checkpoint_every: own.checkpoint_every,
        resume: Some(file),
        ..saved
    };
    Ok((merged, Some(ck)))
}

/// Ties a checkpoint to the scene and every setting that changes the image:
/// the main file's text, the built geometry (so edits of included files and
/// meshes count too), the lights and materials, and the render settings.
pub fn scene_hash(
    scene_text: &[u8],
    scene: &lumis_render::scene::Scene,
    o: &RenderOptions,
    s: &RenderSettings,
) -> u64 {
    let mut o = o.clone();
    o.integrator_entity = None;
    let mut h = Fnv::default();
    h.write(scene_text);
    for m in &scene.shapes.meshes {
        for p in &m.positions {
            for v in p.to_array() {
                h.write(&v.to_bits().to_le_bytes());
            }
        }
        for i in &m.indices {
            h.write(&i.to_le_bytes());
        }
    }
    h.write_str(&format!(
        "{:?} {:?} lights {} materials {}",
        scene.shapes.spheres,
        scene.shapes.disks,
        scene.lights.len(),
        scene.materials.len()
    ))
    .write_str(&format!("{o:?}"))
    .write_str(&format!(
        "spp {} seed {} clamp {:?} sampler {:?} nan {:?} pass {}",
        s.spp, s.seed, s.clamp, s.sampler, s.inject_nan, s.spp_per_pass
    ));
    h.0
}

/// Refuses a checkpoint of another scene or other settings.
pub fn check(ck: &Checkpoint, file: &Path, hash: u64) -> Result<()> {
    if ck.scene_hash != hash {
        bail!(
            "{}: this checkpoint belongs to another scene or other settings (scene hash {:016x}, this render {:016x}); \
             resume it with `lumis render --resume {}` alone, or with the same scene file, unchanged, and the same options",
            file.display(),
            ck.scene_hash,
            hash,
            file.display()
        );
    }
    Ok(())
}

/// Saves checkpoints: every `every`, and when asked.
pub struct Saver {
    pub path: PathBuf,
    pub every: Duration,
    pub last: Instant,
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
        let mut st = template_state(out.film.bounds);
        std::mem::swap(&mut st.film, &mut out.film);
        let st = RenderState {
            spp_done: out.spp,
            alpha: out.alpha,
            bad_samples: out.bad_samples,
            first_bad: out.first_bad,
            rays: out.total_rays,
            elapsed: out.total_elapsed,
            ..st
        };
        let ok = self.save(&st);
        out.film = st.film;
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

/// A placeholder state without pixels (the saver puts the real one in).
pub fn template_state(crop: lumis_render::film::PixelBounds) -> RenderState {
    RenderState {
        film: lumis_render::film::Film {
            full_resolution: (crop.x1, crop.y1),
            bounds: crop,
            pixels: Vec::new(),
        },
        spp_done: 0,
        alpha: 1.0,
        bad_samples: 0,
        first_bad: None,
        rays: 0,
        elapsed: Duration::ZERO,
    }
}
