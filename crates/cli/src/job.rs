//! Command-line arguments → a [`RenderJob`]: clap's arguments as the
//! library's [`RenderFlags`], which make the job (`session::flags`, shared
//! with study runs from Python), and `--resume`'s job.

use crate::args::RenderArgs;
use anyhow::{bail, Result};
use lumis_render::session::{CheckpointSpec, RenderFlags, RenderJob};

/// The job `a` describes (made in the current folder).
pub fn job_from_args(a: &RenderArgs) -> Result<RenderJob> {
    flags(a).job().map_err(anyhow::Error::msg)
}

/// The flags of `a` that make its job.
fn flags(a: &RenderArgs) -> RenderFlags {
    RenderFlags {
        scene: a.scene.clone(),
        output: a.output.clone(),
        spp: a.spp,
        time: a.time,
        threads: a.threads,
        seed: a.seed,
        integrator: a.integrator.clone(),
        maxdepth: a.maxdepth,
        resolution: a.resolution,
        crop: a.crop,
        exposure: a.exposure,
        sampler: a.sampler.clone(),
        clamp: a.clamp,
        filter_splat: a.filter_splat,
        accel: a.accel.clone(),
        params: a.params.values.clone(),
        checkpoint: a.checkpoint.clone(),
        checkpoint_every: a.checkpoint_every,
        passes: a.passes.clone(),
        partial: a.partial.clone(),
        inject_nan: a.inject_nan,
    }
}

/// `--resume FILE` without a scene: the saved job, with this run's own
/// options on top (outputs, threads, time budget, checkpointing); any other
/// render flag is refused rather than silently dropped. (With a scene, the
/// arguments make the job and the checkpoint must match it.)
pub fn resumed_job(a: &RenderArgs, mut job: RenderJob) -> Result<RenderJob> {
    let changed = a.spp.is_some()
        || a.seed != 0
        || a.integrator.is_some()
        || a.maxdepth.is_some()
        || a.resolution.is_some()
        || a.crop.is_some()
        || a.sampler.is_some()
        || a.clamp.is_some()
        || a.filter_splat.is_some()
        || a.accel.is_some()
        || a.exposure != 0.0
        || !a.params.values.is_empty()
        || a.inject_nan.is_some()
        || a.passes.is_some();
    if changed {
        bail!(
            "--resume continues the saved render as it was set up: only -o, --threads, --time, \
             --checkpoint, --checkpoint-every, --display-server, -q, -v and --stats may be given with it"
        );
    }
    if let Some(o) = &a.output {
        job.outputs = vec![std::path::absolute(o).unwrap_or(o.clone())];
    }
    if let Some(t) = a.threads {
        job.threads = t;
    }
    // The budget is this run's own: a time-only render needs a new one.
    if job.budget.time.is_some() && job.budget.spp.is_none() && a.time.is_none() {
        bail!("this render had only a time budget: give --time SECONDS to resume it");
    }
    job.budget.time = a.time;
    let file = a.resume.clone().expect("a resume file");
    let path = a.checkpoint.clone().unwrap_or(file);
    job.checkpoint = Some(CheckpointSpec {
        path: std::path::absolute(&path).unwrap_or(path),
        every: a.checkpoint_every,
    });
    Ok(job)
}
