//! `lumis render` flags → a [`RenderJob`], in one place for every front
//! end: the CLI (its clap arguments as [`RenderFlags`]), the CLI's and
//! Python's study runs (argument strings: [`job_from_flags`]) and Python's
//! parameter list. Each flag becomes a field of the job or a parameter
//! layered over the scene file's, labelled with the flag so the library's
//! errors and warnings point at it; the overrides go in one order (so the
//! scene hash, and the image, are the same whoever made the job).

mod params;
mod parse;

use params::add_param;
pub use params::{integrator_params, param_text, IntegratorParam, PARAM_TABLES};

use super::{Accel, Budget, CheckpointSpec, RenderJob};
use lumis_scene::{Overrides, ParamSpec};
use std::ops::Range;
use std::path::PathBuf;

/// Seconds between checkpoints unless `--checkpoint-every` says otherwise.
pub const DEFAULT_CHECKPOINT_EVERY: f64 = 60.0;

/// The values of `lumis render`'s flags that make its job, parsed (the
/// output-only flags, `-q`, `-v`, `--stats`, `--display-server`, and
/// `--resume` are the front end's own).
#[derive(Clone, Debug, PartialEq)]
pub struct RenderFlags {
    pub scene: Option<PathBuf>,
    /// `-o`, `--output`.
    pub output: Option<PathBuf>,
    pub spp: Option<u32>,
    pub time: Option<f64>,
    pub threads: Option<usize>,
    pub seed: u64,
    pub integrator: Option<String>,
    pub maxdepth: Option<u32>,
    pub resolution: Option<(u32, u32)>,
    pub crop: Option<[f32; 4]>,
    pub exposure: f32,
    pub sampler: Option<String>,
    pub clamp: Option<f32>,
    /// `--filter-splat`: PixelFilter's `splat`.
    pub filter_splat: Option<bool>,
    /// `bvh` or `embree` (checked when the job is made).
    pub accel: Option<String>,
    /// The integrators' parameters given, with their values as typed; they
    /// are applied in table order ([`integrator_params`]), a later value
    /// of the same parameter winning.
    pub params: Vec<(&'static ParamSpec, String)>,
    pub checkpoint: Option<PathBuf>,
    pub checkpoint_every: f64,
    pub passes: Option<Range<u32>>,
    pub partial: Option<PathBuf>,
    pub inject_nan: Option<(u32, u32, u32)>,
}

impl Default for RenderFlags {
    fn default() -> Self {
        RenderFlags {
            scene: None,
            output: None,
            spp: None,
            time: None,
            threads: None,
            seed: 0,
            integrator: None,
            maxdepth: None,
            resolution: None,
            crop: None,
            exposure: 0.0,
            sampler: None,
            clamp: None,
            filter_splat: None,
            accel: None,
            params: Vec::new(),
            checkpoint: None,
            checkpoint_every: DEFAULT_CHECKPOINT_EVERY,
            passes: None,
            partial: None,
            inject_nan: None,
        }
    }
}

/// The job the arguments `args` of `lumis render` describe (made in the
/// current folder), as a study run's flags become its job. Output-only
/// flags are ignored; errors start with `bad flags:`.
pub fn job_from_flags(args: &[String]) -> Result<RenderJob, String> {
    RenderFlags::parse(args)?.job()
}

impl RenderFlags {
    /// The job these flags describe (made in the current folder).
    pub fn job(&self) -> Result<RenderJob, String> {
        let mut job = RenderJob::new(self.scene.clone());
        job.overrides = self.overrides();
        job.seed = self.seed;
        job.budget = Budget {
            spp: self.spp,
            time: self.time,
        };
        job.threads = self.threads.unwrap_or(0);
        job.clamp = self.clamp;
        job.accel = accel(self.accel.as_deref())?;
        job.outputs = self.output.iter().cloned().collect();
        job.exposure = self.exposure;
        job.checkpoint = self.checkpoint.as_ref().map(|p| CheckpointSpec {
            path: job.resolve(p),
            every: self.checkpoint_every,
        });
        job.inject_nan = self.inject_nan;
        if let Some(p) = &self.partial {
            job.passes = self.passes.clone();
            job.checkpoint = Some(CheckpointSpec {
                path: job.resolve(p),
                every: self.checkpoint_every,
            });
        }
        Ok(job)
    }

    /// The flags that override the scene file, in this order: resolution,
    /// crop, sampler, filter, integrator, maxdepth, then the integrators'
    /// parameters in table order.
    fn overrides(&self) -> Overrides {
        let mut o = Overrides::default();
        if let Some((w, h)) = self.resolution {
            o.resolution_from(w, h, "--resolution");
        }
        if let Some(c) = self.crop {
            o.crop_from(c, "--crop");
        }
        if let Some(s) = &self.sampler {
            o.sampler_from(s, "--sampler");
        }
        if let Some(b) = self.filter_splat {
            o.filter_splat_from(b, "--filter-splat");
        }
        if let Some(i) = &self.integrator {
            o.integrator_from(i, "--integrator");
        }
        if let Some(d) = self.maxdepth {
            o.max_depth_from(d, "--maxdepth");
        }
        for p in integrator_params() {
            let given = self
                .params
                .iter()
                .rev()
                .find(|(s, _)| s.name == p.spec.name);
            if let Some((_, v)) = given {
                add_param(&mut o, p.spec, v, &p.flag());
            }
        }
        o
    }
}

fn accel(name: Option<&str>) -> Result<Accel, String> {
    Ok(match name.unwrap_or("bvh") {
        "bvh" => Accel::Bvh,
        "embree" => Accel::Embree,
        other => {
            return Err(format!(
                "unknown --accel `{other}`: expected `bvh` or `embree`"
            ))
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(words: &str) -> &'static ParamSpec {
        integrator_params()
            .into_iter()
            .find(|p| p.spec.words == words)
            .unwrap()
            .spec
    }

    #[test]
    fn overrides_go_in_one_order_labelled_with_their_flags() {
        let f = RenderFlags {
            maxdepth: Some(4),
            integrator: Some("bdpt".into()),
            resolution: Some((8, 6)),
            // Given against table order, twice for one parameter.
            params: vec![
                (spec("strategy"), "1,2".into()),
                (spec("photons"), "10".into()),
                (spec("strategy"), "2,3".into()),
            ],
            ..RenderFlags::default()
        };
        let job = f.job().unwrap();
        let items: Vec<(&str, &str)> = job
            .overrides
            .items
            .iter()
            .map(|o| (o.origin.as_str(), o.params.as_str()))
            .collect();
        assert_eq!(
            items,
            [
                ("--resolution", "\"integer xresolution\" [ 8 ]"),
                ("--resolution", "\"integer yresolution\" [ 6 ]"),
                ("--integrator", ""),
                ("--maxdepth", "\"integer maxdepth\" [ 4 ]"),
                ("--photons", "\"integer photons\" [ 10 ]"),
                ("--strategy", "\"integer strategy\" [ 2 3 ]"),
            ]
        );
    }

    #[test]
    fn fields_and_parts() {
        let f = RenderFlags {
            spp: Some(4),
            threads: Some(2),
            accel: Some("embree".into()),
            output: Some("a.exr".into()),
            checkpoint_every: 5.0,
            passes: Some(2..4),
            partial: Some("p.lpart".into()),
            ..RenderFlags::default()
        };
        let job = f.job().unwrap();
        assert_eq!((job.budget.spp, job.threads), (Some(4), 2));
        assert_eq!(job.accel, Accel::Embree);
        assert_eq!(job.outputs, [PathBuf::from("a.exr")]);
        assert_eq!(job.passes, Some(2..4));
        let c = job.checkpoint.unwrap();
        assert_eq!((c.path, c.every), (job.dir.join("p.lpart"), 5.0));
        let bad = RenderFlags {
            accel: Some("optix".into()),
            ..RenderFlags::default()
        };
        assert_eq!(
            bad.job().unwrap_err(),
            "unknown --accel `optix`: expected `bvh` or `embree`"
        );
    }
}
