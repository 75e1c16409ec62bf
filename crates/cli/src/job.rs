//! Command-line arguments → a [`RenderJob`]: each flag becomes a field of
//! the job or a parameter layered over the scene file's, labelled with the
//! flag so the library's errors and warnings point at it.

use crate::args::RenderArgs;
use anyhow::{bail, Result};
use lumis_render::session::{Accel, Budget, CheckpointSpec, RenderJob};
use lumis_scene::Overrides;

/// The job `a` describes (made in the current folder).
pub fn job_from_args(a: &RenderArgs) -> Result<RenderJob> {
    let mut job = RenderJob::new(a.scene.clone());
    job.overrides = overrides(a);
    job.seed = a.seed;
    job.budget = Budget {
        spp: a.spp,
        time: a.time,
    };
    job.threads = a.threads.unwrap_or(0);
    job.clamp = a.clamp;
    job.accel = accel(a.accel.as_deref())?;
    job.outputs = a.output.iter().cloned().collect();
    job.exposure = a.exposure;
    job.checkpoint = a.checkpoint.as_ref().map(|p| CheckpointSpec {
        path: job.resolve(p),
        every: a.checkpoint_every,
    });
    job.inject_nan = a.inject_nan;
    if let Some(p) = &a.partial {
        job.passes = a.passes.clone();
        job.checkpoint = Some(CheckpointSpec {
            path: job.resolve(p),
            every: a.checkpoint_every,
        });
    }
    Ok(job)
}

/// The flags that override the scene file, as parameter overrides.
fn overrides(a: &RenderArgs) -> Overrides {
    let mut o = Overrides::default();
    if let Some((w, h)) = a.resolution {
        o.resolution_from(w, h, "--resolution");
    }
    if let Some(c) = a.crop {
        o.crop_from(c, "--crop");
    }
    if let Some(s) = &a.sampler {
        o.sampler_from(s, "--sampler");
    }
    if let Some(i) = &a.integrator {
        o.integrator_from(i, "--integrator");
    }
    if let Some(d) = a.maxdepth {
        o.max_depth_from(d, "--maxdepth");
    }
    for (s, v) in &a.params.values {
        let value = match s.ty {
            "string" => format!("\"{v}\""),
            // `--strategy 2,3`: a list of integers.
            "integer" => v.replace(',', " "),
            _ => v.clone(),
        };
        o.param(
            "Integrator",
            &format!("{} {}", s.ty, s.name),
            &value,
            &format!("--{}", s.words),
        );
    }
    o
}

fn accel(name: Option<&str>) -> Result<Accel> {
    Ok(match name.unwrap_or("bvh") {
        "bvh" => Accel::Bvh,
        "embree" => Accel::Embree,
        other => bail!("unknown --accel `{other}`: expected `bvh` or `embree`"),
    })
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
