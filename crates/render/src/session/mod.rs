//! A render session: a [`RenderJob`] taken through load → acceleration →
//! render → image with metadata → outputs. Every front end (the CLI,
//! studies, checkpoints and resumes, a future Python package, distributed
//! workers) builds a job and drives a session; none repeats these steps.

mod flags;
mod job;
mod merge;
mod merger;
mod output;

pub use flags::{
    integrator_params, job_from_flags, param_text, IntegratorParam, RenderFlags,
    DEFAULT_CHECKPOINT_EVERY, PARAM_TABLES,
};
pub use job::{Accel, Budget, CheckpointSpec, RenderJob};
pub use merge::{merge, Part};
pub use merger::{merged_image, Merger};
pub use output::{check_writable, default_outputs};

use crate::checkpoint::{Checkpoint, Fnv};
use crate::film::Film;
use crate::image_io::{write_image, RgbImage};
use crate::integrator::{render_with, RenderHooks, RenderOutcome, RenderSettings, RenderState};
use crate::load::{build_scene, LoadedScene, DEFAULT_SCENE};
use lumis_scene::Diagnostic;
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Why a session could not be made or finished.
#[derive(Debug)]
pub enum SessionError {
    /// The scene: located (file:line:column) where it can be.
    Scene(Diagnostic),
    Other(String),
}

impl fmt::Display for SessionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SessionError::Scene(d) => write!(f, "{d}"),
            SessionError::Other(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for SessionError {}

impl From<Diagnostic> for SessionError {
    fn from(d: Diagnostic) -> Self {
        SessionError::Scene(d)
    }
}

impl From<String> for SessionError {
    fn from(m: String) -> Self {
        SessionError::Other(m)
    }
}

/// Time by phase, for statistics.
#[derive(Clone, Copy, Debug, Default)]
pub struct Phases {
    pub parse: Duration,
    pub build: Duration,
    pub write: Duration,
}

/// A loaded job, ready to render.
pub struct Session {
    pub job: RenderJob,
    pub loaded: LoadedScene,
    pub settings: RenderSettings,
    /// The images to write, resolved against the job's folder and checked
    /// to be writable before rendering.
    pub outputs: Vec<PathBuf>,
    /// Ties checkpoints to every input file and every setting that changes
    /// the image.
    pub hash: u64,
    pub phases: Phases,
}

impl Session {
    /// Parses and builds the job's scene, checks its outputs.
    pub fn new(job: RenderJob) -> Result<Session, SessionError> {
        Session::build(job, true)
    }

    /// [`Session::new`] for a front end that takes the image itself: no
    /// outputs, not even the default ones (nothing is probed or written).
    pub fn without_outputs(job: RenderJob) -> Result<Session, SessionError> {
        Session::build(job, false)
    }

    fn build(job: RenderJob, write: bool) -> Result<Session, SessionError> {
        job.check()?;
        let mut phases = Phases::default();
        let t = Instant::now();
        let scene_path = job.scene.as_ref().map(|p| job.resolve(p));
        let desc = match &scene_path {
            Some(p) => lumis_scene::load_file(p),
            None => lumis_scene::load_str(DEFAULT_SCENE, "<built-in default scene>", &job.dir),
        }?;
        phases.parse = t.elapsed();
        let t = Instant::now();
        let mut overrides = job.overrides.clone();
        if let Some(n) = job.budget.spp {
            overrides.spp_from(n, "the sample count");
        }
        let mut loaded = build_scene(&desc, &overrides)?;
        drop(desc);
        select_accel(&mut loaded.scene, job.accel)?;
        phases.build = t.elapsed();
        let outputs: Vec<PathBuf> = match job.outputs.is_empty() {
            _ if !write => Vec::new(),
            // A part is saved as a part, not an image.
            true if job.passes.is_some() => Vec::new(),
            true => default_outputs(loaded.options.filename.as_deref())
                .into_iter()
                .map(|p| job.resolve(&p))
                .collect(),
            false => job.outputs.iter().map(|p| job.resolve(p)).collect(),
        };
        for o in &outputs {
            check_writable(o)?;
        }
        let (settings, hash) = settings_and_hash(&job, &loaded)?;
        Ok(Session {
            job,
            loaded,
            settings,
            outputs,
            hash,
            phases,
        })
    }

    /// Points this loaded session at `job`, which builds the same scene
    /// (only its seed, budget, threads, clamp, pass range or outputs
    /// differ): its settings and scene hash follow from it as
    /// [`Session::new`] makes them (so its checkpoints and parts are the
    /// job's). Outputs are the caller's to set.
    pub fn set_job(&mut self, job: RenderJob) -> Result<(), SessionError> {
        job.check()?;
        (self.settings, self.hash) = settings_and_hash(&job, &self.loaded)?;
        self.job = job;
        Ok(())
    }

    /// Renders with the job's integrator; `hooks.resume` continues a
    /// checkpoint's state (see [`Session::resume_state`]).
    pub fn render(&self, hooks: RenderHooks) -> RenderOutcome {
        render_with(
            &self.loaded.scene,
            &self.loaded.options.integrator,
            &self.settings,
            hooks,
        )
    }

    /// The film's mean image times the scene's imaging scale and white balance.
    pub fn scaled(&self, film: &Film) -> Vec<f32> {
        let o = &self.loaded.options;
        let mut d = film.mean_image();
        if o.imaging_scale != 1.0 || o.white_balance.is_some() {
            crate::load::RenderOptions::to_output(o.imaging_scale, o.white_balance, &mut d);
        }
        d
    }

    /// The image of `out` with what it records of how it was made
    /// (`command`: how the front end was invoked, if it has one).
    pub fn image(&self, out: &RenderOutcome, command: Option<&str>) -> RgbImage {
        let mut img = RgbImage::new(out.film.width(), out.film.height(), self.scaled(&out.film));
        img.metadata = self.metadata(out);
        img.metadata
            .push(("lumis:bad_samples".into(), out.bad_samples.to_string()));
        if let Some(c) = command {
            img.metadata.push(("lumis:command".into(), c.into()));
        }
        if let Some(b) = out.first_bad {
            img.metadata.push((
                "lumis:first_bad_sample".into(),
                format!("pixel {},{} sample {}", b.x, b.y, b.sample),
            ));
        }
        img
    }

    /// What every image of this session records: samples, integrator, seed, scene.
    pub fn metadata(&self, out: &RenderOutcome) -> Vec<(String, String)> {
        let scene = self
            .job
            .scene
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_else(|| "<default>".into());
        let mut m = vec![
            ("lumis:spp".into(), out.spp.to_string()),
            (
                "lumis:integrator".into(),
                self.loaded.options.integrator.name().into(),
            ),
            ("lumis:seed".into(), self.job.seed.to_string()),
            ("lumis:scene".into(), scene),
        ];
        // A progressive render's iterations and photon counts (chosen by
        // the time rule under a time budget) reproduce it without one.
        if let Some(ps) = out.photon_stats.as_ref().filter(|p| p.iterations > 0) {
            let (g, c) = ps.iteration_photons;
            m.push(("lumis:iterations".into(), ps.render_iterations.to_string()));
            m.push((
                "lumis:iteration-photons".into(),
                format!("{g} global, {c} caustic"),
            ));
        }
        m
    }

    /// Writes `img` to every output. If one cannot be written (its folder
    /// vanished or filled up during the render), the image is saved under
    /// the same name beside the checkpoint or in the job's folder instead,
    /// and the error says where. Returns the files written.
    pub fn write(&self, img: &RgbImage) -> Result<Vec<PathBuf>, SessionError> {
        let mut written = Vec::new();
        for f in &self.outputs {
            if let Err(e) = write_image(f, img, self.job.exposure) {
                let name = f.file_name().map(PathBuf::from).unwrap_or_default();
                let dir = match &self.job.checkpoint {
                    Some(c) => self.job.resolve(&c.path).parent().map(Path::to_path_buf),
                    None => None,
                }
                .unwrap_or_else(|| self.job.dir.clone());
                let rescue = dir.join(name);
                let saved =
                    match rescue != *f && write_image(&rescue, img, self.job.exposure).is_ok() {
                        true => format!("; the image was saved to {} instead", rescue.display()),
                        false => String::new(),
                    };
                return Err(SessionError::Other(format!(
                    "writing {}: {e}{saved}",
                    f.display()
                )));
            }
            written.push(f.clone());
        }
        Ok(written)
    }

    /// A checkpoint of this session at `state`.
    pub fn checkpoint(&self, state: RenderState) -> Checkpoint {
        Checkpoint {
            lumis_version: env!("CARGO_PKG_VERSION").into(),
            scene_hash: self.hash,
            job: self.job.to_json(),
            state,
        }
    }

    /// The part `out` is, when this session is a partial render (a
    /// checkpoint of its pass range, which `merge` combines).
    pub fn part(&self, out: &RenderOutcome) -> Checkpoint {
        self.checkpoint(out.state())
    }

    /// The state to continue from `ck`, refused if it belongs to another
    /// scene, other input files or other settings.
    pub fn resume_state(&self, ck: &Checkpoint, name: &str) -> Result<RenderState, SessionError> {
        if ck.scene_hash != self.hash {
            return Err(SessionError::Other(format!(
                "{name}: this checkpoint belongs to another scene or other settings, or a file \
                 the scene reads has changed since (scene hash {:016x}, this render {:016x})",
                ck.scene_hash, self.hash
            )));
        }
        let passes = RenderJob::from_json(&ck.job).map(|j| j.passes);
        if passes.as_ref().ok() != Some(&self.job.passes) {
            let range = |p: &Option<std::ops::Range<u32>>| match p {
                Some(r) => format!("passes {}..{}", r.start, r.end),
                None => "all passes".into(),
            };
            return Err(SessionError::Other(format!(
                "{name}: this checkpoint renders {}, this render {}",
                passes.map_or("?".into(), |p| range(&p)),
                range(&self.job.passes)
            )));
        }
        Ok(ck.state.clone())
    }
}

/// The render settings of `job` on a scene loaded with options `o` (a
/// loaded scene rendered again with another seed, budget or clamp takes
/// these too).
pub fn run_settings(job: &RenderJob, o: &crate::load::RenderOptions) -> RenderSettings {
    // With only a time budget, the sample count is unbounded.
    let spp = match (job.budget.time, job.budget.spp) {
        (Some(_), None) => 0,
        _ => o.spp,
    };
    RenderSettings {
        time_limit: job.budget.time.map(Duration::from_secs_f64),
        clamp: job.clamp,
        inject_nan: job.inject_nan,
        passes: job.passes.clone(),
        ..o.render_settings(spp, job.seed, job.threads)
    }
}

/// `job`'s checked render settings on `l` and the hash of both.
fn settings_and_hash(
    job: &RenderJob,
    l: &LoadedScene,
) -> Result<(RenderSettings, u64), SessionError> {
    let settings = run_settings(job, &l.options);
    settings.check_passes()?;
    let hash = scene_hash(l, &settings);
    Ok((settings, hash))
}

/// The job a checkpoint file continues, and the checkpoint.
pub fn load_checkpoint(path: &Path) -> Result<(RenderJob, Checkpoint), SessionError> {
    let ck = Checkpoint::load(path).map_err(|e| SessionError::Other(e.to_string()))?;
    let job = RenderJob::from_json(&ck.job)
        .map_err(|e| SessionError::Other(format!("{}: {e}", path.display())))?;
    Ok((job, ck))
}

/// Ties a checkpoint to the scene and every setting that changes the image:
/// the scene's inputs (its text and every file read to build it: included
/// files, meshes, images, spectra) and the render settings, but not a
/// partial render's pass range (the parts of one render share it).
fn scene_hash(l: &LoadedScene, s: &RenderSettings) -> u64 {
    let mut h = Fnv::default();
    h.write(&crate::load::inputs_hash(&l.inputs).to_le_bytes())
        .write_str(&format!("{:?}", l.options))
        .write_str(&format!(
            "spp {} seed {} clamp {:?} sampler {:?} nan {:?} pass {}",
            s.spp, s.seed, s.clamp, s.sampler, s.inject_nan, s.spp_per_pass
        ));
    h.0
}

/// The job's ray-tracing backend.
fn select_accel(scene: &mut crate::scene::Scene, accel: Accel) -> Result<(), SessionError> {
    match accel {
        Accel::Bvh => Ok(()),
        #[cfg(feature = "embree")]
        Accel::Embree => {
            scene.use_embree(true);
            Ok(())
        }
        #[cfg(not(feature = "embree"))]
        Accel::Embree => {
            let _ = scene;
            Err(SessionError::Other(
                "this lumis was built without Embree: build it with the `embree` feature \
                 (needs libembree-dev)"
                    .into(),
            ))
        }
    }
}
