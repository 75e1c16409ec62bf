//! Results on disk: one JSON record per finished run (written atomically,
//! after its images), and a manifest of the study; a rerun skips every run
//! whose record exists with the same render arguments.

use super::calibrate::Calibration;
use super::error::{Context, Result};
use super::fit::Slope;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// What one finished run measured.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct RunResult {
    pub id: String,
    pub scene: String,
    pub setting: String,
    pub budget: String,
    pub seed: u64,
    /// The `lumis render` arguments; a record with other arguments is stale.
    pub args: Vec<String>,
    pub spp: u32,
    /// Wall-clock seconds of the render, photon pass included (scene loading excluded).
    pub seconds: f64,
    /// Photon tracing + map building + radiance photons, seconds (photon only).
    pub photon_seconds: Option<f64>,
    pub mse: f64,
    pub rmse: f64,
    pub relmse: f64,
    pub mae: f64,
    pub ratio: [f64; 3],
    /// Files, relative to the report folder.
    pub exr: String,
    pub png: String,
    pub heatmap: String,
}

impl RunResult {
    pub fn metric(&self, name: &str) -> f64 {
        match name {
            "mse" => self.mse,
            "relmse" => self.relmse,
            "mae" => self.mae,
            _ => self.rmse,
        }
    }
}

/// Writes `bytes` to `path` through a temporary file and a rename. The
/// temporary name holds the process id, so that studies of the same config
/// run side by side (one per seed) into one folder do not take each other's
/// temporary files.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let name = path.file_name().map(|n| n.to_string_lossy().to_string());
    let tmp = path.with_file_name(format!(
        ".{}.{}.tmp",
        name.unwrap_or_default(),
        std::process::id()
    ));
    std::fs::write(&tmp, bytes).with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("writing {}", path.display()))
}

/// What a study found beyond its runs.
#[derive(Debug, Default, Serialize)]
pub struct Summary {
    /// Log-log slopes of error against seconds, per scene and setting.
    pub slopes: Vec<Slope>,
    /// The calibrations of external settings' time budgets.
    pub calibrations: Vec<Calibration>,
    /// Settings whose program is missing, a sentence each.
    pub skipped: Vec<String>,
}

pub struct Store {
    pub dir: PathBuf,
}

impl Store {
    pub fn new(dir: &Path) -> Result<Store> {
        std::fs::create_dir_all(dir.join("runs"))
            .with_context(|| format!("creating {}", dir.display()))?;
        Ok(Store {
            dir: dir.to_path_buf(),
        })
    }

    fn record_path(&self, id: &str) -> PathBuf {
        self.dir.join("runs").join(format!("{id}.json"))
    }

    /// The finished result of `id`, if its record exists, parses, has the same
    /// arguments and its files are all there.
    pub fn finished(&self, id: &str, args: &[String]) -> Option<RunResult> {
        let text = std::fs::read_to_string(self.record_path(id)).ok()?;
        let r: RunResult = serde_json::from_str(&text).ok()?;
        let files_ok = [&r.exr, &r.png, &r.heatmap]
            .iter()
            .all(|f| self.dir.join(f).is_file());
        (r.args == args && files_ok).then_some(r)
    }

    pub fn save(&self, r: &RunResult) -> Result<()> {
        write_atomic(
            &self.record_path(&r.id),
            serde_json::to_string_pretty(r)?.as_bytes(),
        )
    }

    /// `manifest.json`: every planned run and whether it is finished.
    pub fn write_manifest(&self, title: &str, planned: &[(String, bool)]) -> Result<()> {
        #[derive(Serialize)]
        struct Entry<'a> {
            id: &'a str,
            finished: bool,
        }
        #[derive(Serialize)]
        struct Manifest<'a> {
            title: &'a str,
            finished: usize,
            planned: usize,
            runs: Vec<Entry<'a>>,
        }
        let m = Manifest {
            title,
            finished: planned.iter().filter(|p| p.1).count(),
            planned: planned.len(),
            runs: planned
                .iter()
                .map(|(id, f)| Entry { id, finished: *f })
                .collect(),
        };
        write_atomic(
            &self.dir.join("manifest.json"),
            serde_json::to_string_pretty(&m)?.as_bytes(),
        )
    }

    /// `metrics.csv` over the finished runs, and `metrics.json`: the runs
    /// with the slopes, calibrations and skipped settings.
    pub fn write_tables(&self, results: &[RunResult], summary: &Summary) -> Result<()> {
        let mut csv = String::from(
            "scene,setting,budget,seed,spp,seconds,photon_seconds,mse,rmse,relmse,mae,ratio_r,ratio_g,ratio_b\n",
        );
        for r in results {
            csv += &format!(
                "{},{},{},{},{},{:.4},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.5},{:.5},{:.5}\n",
                r.scene,
                r.setting,
                r.budget,
                r.seed,
                r.spp,
                r.seconds,
                r.photon_seconds
                    .map(|s| format!("{s:.4}"))
                    .unwrap_or_default(),
                r.mse,
                r.rmse,
                r.relmse,
                r.mae,
                r.ratio[0],
                r.ratio[1],
                r.ratio[2]
            );
        }
        write_atomic(&self.dir.join("metrics.csv"), csv.as_bytes())?;
        #[derive(Serialize)]
        struct Json<'a> {
            runs: &'a [RunResult],
            #[serde(flatten)]
            summary: &'a Summary,
        }
        let json = Json {
            runs: results,
            summary,
        };
        write_atomic(
            &self.dir.join("metrics.json"),
            serde_json::to_string_pretty(&json)?.as_bytes(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_round_trip_and_stale_ones_are_not_finished() {
        let dir = std::env::temp_dir().join(format!("lumis-store-{}", std::process::id()));
        let s = Store::new(&dir).unwrap();
        let r = RunResult {
            id: "a__b__t1s__s1".into(),
            scene: "a".into(),
            setting: "b".into(),
            budget: "t1s".into(),
            seed: 1,
            args: vec!["x.pbrt".into()],
            spp: 3,
            seconds: 1.0,
            photon_seconds: None,
            mse: 1.0,
            rmse: 1.0,
            relmse: 2.0,
            mae: 0.5,
            ratio: [1.0; 3],
            exr: "i.exr".into(),
            png: "i.png".into(),
            heatmap: "h.png".into(),
        };
        s.save(&r).unwrap();
        // Missing image files: not finished.
        assert!(s.finished(&r.id, &r.args).is_none());
        for f in ["i.exr", "i.png", "h.png"] {
            std::fs::write(dir.join(f), b"x").unwrap();
        }
        assert_eq!(s.finished(&r.id, &r.args), Some(r.clone()));
        // Other arguments: stale.
        assert!(s.finished(&r.id, &["y.pbrt".to_string()]).is_none());
        s.write_tables(std::slice::from_ref(&r), &Summary::default())
            .unwrap();
        let csv = std::fs::read_to_string(dir.join("metrics.csv")).unwrap();
        assert_eq!(csv.lines().count(), 2);
        let json = std::fs::read_to_string(dir.join("metrics.json")).unwrap();
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert_eq!(v["runs"][0]["id"], r.id.as_str());
        assert!(v["slopes"].as_array().unwrap().is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
