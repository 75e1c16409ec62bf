//! [`RenderJob`]: everything that says what to render and where to, as plain
//! serializable data. The CLI, studies, checkpoints and future front ends
//! (Python, distributed workers) all describe a render this way and hand it
//! to a [`super::Session`].

use lumis_scene::Overrides;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Samples per pixel and a wall-clock budget. With only a time budget the
/// sample count is unbounded; with neither, the scene's `pixelsamples`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Budget {
    /// Samples per pixel (the scene's `Sampler "integer pixelsamples"` otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spp: Option<u32>,
    /// Seconds; the render stops after the last whole pass that fits.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<f64>,
}

/// Where to trace rays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Accel {
    /// The built-in BVH.
    #[default]
    Bvh,
    /// Embree 3 (builds with the `embree` feature).
    Embree,
}

/// Periodic saving of the render's state, for resuming.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CheckpointSpec {
    pub path: PathBuf,
    /// Seconds between saves (also saved on interrupt and at the end).
    pub every: f64,
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RenderJob {
    /// The scene file; `None`: the built-in default scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scene: Option<PathBuf>,
    /// Parameters layered over the scene file's (`Film`, `Sampler`,
    /// `PixelFilter`, `Integrator` and its settings).
    #[serde(default, skip_serializing_if = "Overrides::is_empty")]
    pub overrides: Overrides,
    #[serde(default)]
    pub seed: u64,
    #[serde(default)]
    pub budget: Budget,
    /// Worker threads (0: all cores); the image does not depend on it.
    #[serde(default)]
    pub threads: usize,
    /// Scale each sample down so no component exceeds this (biased).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clamp: Option<f32>,
    #[serde(default)]
    pub accel: Accel,
    /// Images to write (`.exr`, `.pfm`, `.png`); empty: `<name>.exr` and
    /// `<name>.png`, `<name>` from the Film's filename or `lumis`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub outputs: Vec<PathBuf>,
    /// Exposure in stops for PNG outputs.
    #[serde(default)]
    pub exposure: f32,
    /// The folder relative paths of this job resolve against.
    #[serde(default)]
    pub dir: PathBuf,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub checkpoint: Option<CheckpointSpec>,
    /// Test hook: the sample at pixel (x, y) with this index becomes NaN.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inject_nan: Option<(u32, u32, u32)>,
    /// A partial render: only these passes (one sample per pixel each) of
    /// the render the rest of the job describes. Its result is a part (a
    /// checkpoint of the range: [`super::Session::part`]) that merges with
    /// the other ranges' parts to the bits of the whole render
    /// (`session::merge`); it writes no image unless `outputs` names some.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub passes: Option<std::ops::Range<u32>>,
}

impl RenderJob {
    /// A job for `scene` (`None`: the default scene) made in the current folder.
    pub fn new(scene: Option<PathBuf>) -> RenderJob {
        RenderJob {
            scene,
            dir: std::env::current_dir().unwrap_or_default(),
            ..RenderJob::default()
        }
    }

    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a job serializes")
    }

    pub fn from_json(text: &str) -> Result<RenderJob, String> {
        serde_json::from_str(text).map_err(|e| format!("not a render job: {e}"))
    }

    /// `p` resolved against the job's folder.
    pub fn resolve(&self, p: &Path) -> PathBuf {
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.dir.join(p)
        }
    }

    /// The job's own mistakes, before anything is loaded.
    pub fn check(&self) -> Result<(), String> {
        if let Some(t) = self.budget.time {
            if !(t > 0.0 && t.is_finite()) {
                return Err(format!(
                    "the time budget must be a positive number of seconds, found {t}"
                ));
            }
        }
        if let Some(c) = &self.checkpoint {
            if !(c.every >= 0.0 && c.every.is_finite()) {
                return Err(format!(
                    "the checkpoint interval must be a number of seconds >= 0, found {}",
                    c.every
                ));
            }
        }
        if self.budget.spp == Some(0) {
            return Err("the sample count must be at least 1".into());
        }
        if let Some(r) = &self.passes {
            if r.start >= r.end {
                return Err(format!(
                    "the pass range {}..{} is empty: give A..B with A < B",
                    r.start, r.end
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_through_json() {
        let mut j = RenderJob::new(Some("a b.pbrt".into()));
        j.overrides
            .param("Integrator", "integer photons", "5", "--photons");
        j.budget = Budget {
            spp: Some(4),
            time: Some(2.5),
        };
        j.accel = Accel::Embree;
        j.outputs = vec!["x.exr".into()];
        j.checkpoint = Some(CheckpointSpec {
            path: "c.ckpt".into(),
            every: 3.0,
        });
        j.passes = Some(3..7);
        let back = RenderJob::from_json(&j.to_json()).unwrap();
        assert_eq!(back, j);
        assert!(RenderJob::from_json("{\"seed\": \"x\"}").is_err());
    }

    #[test]
    fn bad_budgets_are_refused() {
        let mut j = RenderJob::default();
        assert!(j.check().is_ok());
        j.budget.time = Some(-1.0);
        assert!(j.check().unwrap_err().contains("time budget"));
        j.budget.time = None;
        j.budget.spp = Some(0);
        assert!(j.check().is_err());
    }
}
