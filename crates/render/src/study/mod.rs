//! Equal-time studies: a matrix of scenes x settings x budgets x seeds, each
//! run a [`RenderJob`] rendered in-process by a [`Session`], compared with
//! its scene's reference; images, heatmaps, metrics and a self-contained
//! HTML report are written. Each finished run is recorded atomically; a
//! rerun skips finished runs. Front ends (`lumis study`) load a [`Config`]
//! and say how a run's flags become a job.

pub mod calibrate;
mod command;
pub mod config;
pub mod error;
mod external;
pub mod fit;
pub mod plot;
mod report;
mod runs;
mod scene_copy;
mod setting;
mod single;
pub mod store;
mod summary;

pub use config::Config;
pub use error::{Result, StudyError};
pub use single::{plan, run_one, OneRun, PlannedRun};

use crate::image_io::{read_image, write_image, RgbImage};
use crate::metrics::compare;
use crate::session::RenderJob;
use error::Context;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;
use store::{RunResult, Store};

/// How a study runs: where, how verbosely, and how a run's flags (its
/// setting's and scene's, with the budget, seed and threads the study
/// sets) become a job.
pub struct StudyRun<'a> {
    pub out: PathBuf,
    /// The command that started the study, for the report.
    pub command: String,
    pub job_for: &'a dyn Fn(&[String]) -> std::result::Result<RenderJob, String>,
    /// Set (e.g. by SIGINT) to stop after the current run.
    pub cancel: &'a AtomicBool,
    /// Progress lines and the scenes' warnings.
    pub log: &'a dyn Fn(&str),
}

/// What a study did.
pub struct StudyOutcome {
    pub finished: usize,
    pub planned: usize,
    pub interrupted: bool,
    pub report: PathBuf,
}

/// Exposure (stops) that maps the reference's 98th-percentile luminance to 1,
/// rounded to half stops.
fn auto_exposure(r: &RgbImage) -> f32 {
    let mut l: Vec<f32> = r
        .data
        .chunks_exact(3)
        .map(|p| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2])
        .collect();
    l.sort_by(f32::total_cmp);
    let p = l[((l.len() - 1) as f64 * 0.98) as usize];
    if p > 0.0 && p.is_finite() {
        ((-p.log2() * 2.0).round() / 2.0).clamp(-12.0, 12.0)
    } else {
        0.0
    }
}

/// `YYYY-MM-DD HH:MM:SS UTC` from the system clock (civil-from-days).
fn utc_now() -> String {
    let s = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    let (days, rem) = (s.div_euclid(86400), s.rem_euclid(86400));
    let z = days + 719468;
    let era = z.div_euclid(146097);
    let doe = z - era * 146097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}:{:02} UTC",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

fn loadavg() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{cpu}, {cores} hardware threads, {}", std::env::consts::OS)
}

fn rel(out: &Path, p: &Path) -> String {
    p.strip_prefix(out)
        .unwrap_or(p)
        .to_string_lossy()
        .replace('\\', "/")
}

/// The report folder a config's study writes to by default:
/// `<config stem>-report` beside it.
pub fn default_out(config: &Path) -> PathBuf {
    let stem = config.file_stem().unwrap_or_default().to_string_lossy();
    config
        .parent()
        .unwrap_or(Path::new("."))
        .join(format!("{stem}-report"))
}

/// A scene's reference, read and checked, and what the report shows of it
/// (`write_png`: its tone-mapped PNG written in the scene's folder).
fn reference(
    s: &config::SceneCfg,
    out: &Path,
    write_png: bool,
) -> Result<(RgbImage, report::SceneInfo)> {
    let r = read_image(&s.reference)
        .with_context(|| format!("scene `{}`: reading its reference", s.name))?;
    compare(&r, &r, None).with_context(|| format!("scene `{}`: reference", s.name))?;
    let exposure = s.exposure.unwrap_or_else(|| auto_exposure(&r));
    std::fs::create_dir_all(out.join(&s.name))?;
    let png = out.join(&s.name).join("reference.png");
    if write_png {
        write_image(&png, &r, exposure)?;
    }
    let info = report::SceneInfo {
        reference_png: rel(out, &png),
        reference_spp: r.meta("lumis:spp").map(str::to_string),
        reference_command: r.meta("lumis:command").map(str::to_string),
        exposure,
    };
    Ok((r, info))
}

/// Runs every unfinished run of `c` and writes the report.
pub fn run(c: &Config, a: &StudyRun) -> Result<StudyOutcome> {
    let out = a.out.clone();
    let store = Store::new(&out)?;
    // References: read, checked, tone-mapped once; every run of a scene uses its exposure.
    let mut refs = Vec::new();
    let mut infos = Vec::new();
    for s in &c.scenes {
        let (r, info) = reference(s, &out, true)?;
        refs.push(r);
        infos.push(info);
    }
    let ctx_start = (loadavg(), utc_now());
    let mut ext = external::Externals::new(c, &out, a.log, a.cancel);
    let runs = c.runs();
    let mut results: Vec<RunResult> = Vec::new();
    let mut planned: Vec<(String, bool)> = runs.iter().map(|r| (r.id(c), false)).collect();
    let (mut done_here, mut secs_here) = (0usize, 0.0f64);
    let mut interrupted = false;
    for (k, run) in runs.iter().enumerate() {
        let id = run.id(c);
        if ext.is_skipped(run.setting) {
            continue;
        }
        let tag = format!("[{}/{}] {id}", k + 1, runs.len());
        let plan = match &c.settings[run.setting].external {
            None => None,
            Some(_) => match ext.plan(run, &id).with_context(|| format!("run {id}"))? {
                Some(p) => Some(p),
                None => {
                    interrupted = true;
                    break;
                }
            },
        };
        let args = plan
            .as_ref()
            .map_or_else(|| c.render_args(run), |p| p.args.clone());
        if let Some(r) = store.finished(&id, &args) {
            (a.log)(&format!("{tag}: finished before, skipped"));
            results.push(r);
            planned[k].1 = true;
            continue;
        }
        if a.cancel.load(Ordering::SeqCst) {
            interrupted = true;
            break;
        }
        let t0 = Instant::now();
        let (sref, sinfo) = (&refs[run.scene], &infos[run.scene]);
        let r = match &plan {
            None => runs::lumis_run(c, a, run, &id, &args, sref, sinfo)
                .with_context(|| format!("run {id} (lumis render {})", args.join(" ")))?,
            Some(p) => runs::external_run(c, a, &ext, (run, &id), p, sref, sinfo)
                .with_context(|| format!("run {id} ({})", command::show(&args)))?,
        };
        let Some(r) = r else {
            interrupted = true;
            break;
        };
        store.save(&r)?;
        planned[k].1 = true;
        store.write_manifest(&c.title, &planned)?;
        done_here += 1;
        secs_here += t0.elapsed().as_secs_f64();
        let left = planned.iter().filter(|p| !p.1).count();
        (a.log)(&format!(
            "{tag}: {} spp in {:.2} s, relMSE {:.3e}, MSE {:.3e} (about {:.0} s left)",
            r.spp,
            r.seconds,
            r.relmse,
            r.mse,
            secs_here / done_here as f64 * left as f64
        ));
        results.push(r);
    }
    store.write_manifest(&c.title, &planned)?;
    let summary = store::Summary {
        slopes: fit::slopes(c, &results),
        calibrations: ext.calibrations(),
        skipped: ext.skipped(),
    };
    store.write_tables(&results, &summary)?;
    let ctx = report::Context {
        machine: machine(),
        load_before: ctx_start.0,
        load_after: loadavg(),
        started: ctx_start.1,
        finished: utc_now(),
        command: a.command.clone(),
        planned: runs.len(),
        summary,
    };
    let page = report::html(c, &results, &infos, &ctx);
    // The files the page shows (for copying a report without every run's images).
    let mut files = vec![
        "index.html".to_string(),
        "metrics.csv".into(),
        "metrics.json".into(),
    ];
    files.extend(infos.iter().map(|i| i.reference_png.clone()));
    files.extend(report::shown_files(c, &results));
    store::write_atomic(
        &out.join("report-files.txt"),
        (files.join("\n") + "\n").as_bytes(),
    )?;
    store::write_atomic(&out.join("index.html"), page.as_bytes())?;
    Ok(StudyOutcome {
        finished: results.len(),
        planned: runs.len(),
        interrupted,
        report: out.join("index.html"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exposure_maps_the_98th_percentile_to_one() {
        let mut d = vec![0.25f32; 300];
        d[297..].fill(100.0); // one bright pixel in 100: above the 98th percentile
        let img = RgbImage::new(100, 1, d);
        assert_eq!(auto_exposure(&img), 2.0);
        assert_eq!(auto_exposure(&RgbImage::new(1, 1, vec![0.0; 3])), 0.0);
    }

    #[test]
    fn utc_clock_format() {
        let s = utc_now();
        assert_eq!(s.len(), "2026-11-22 03:04:05 UTC".len());
        assert!(s.starts_with("20") && s.ends_with(" UTC"));
    }
}
