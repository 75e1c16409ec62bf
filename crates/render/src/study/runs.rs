//! One run: rendered by lumis in-process, or by an external program whose
//! image is read back; both measured the same way against the reference.

use super::config::{Config, Run, SceneCfg};
use super::error::{Context, Result};
use super::external::{Externals, Planned};
use super::report::SceneInfo;
use super::store::RunResult;
use super::{rel, StudyRun};
use crate::image_io::{read_image, write_image, RgbImage};
use crate::integrator::RenderHooks;
use crate::load::options::crop_bounds;
use crate::metrics::heatmap::write_heatmap;
use crate::metrics::{compare_where, lit_interior, Metrics, PixelError};
use crate::session::Session;
use std::path::{Path, PathBuf};

/// A run's files: its image (EXR, or what an external program writes), PNG
/// and heatmap.
struct Files {
    image: PathBuf,
    png: PathBuf,
    heat: PathBuf,
}

impl Files {
    fn new(out: &Path, scene: &SceneCfg, id: &str, image: PathBuf) -> Files {
        let dir = out.join(&scene.name);
        Files {
            image,
            png: dir.join(format!("{id}.png")),
            heat: dir.join(format!("{id}.err.png")),
        }
    }
}

/// Compares `img` with the reference (over the scene's mask) and writes its
/// PNG and heatmap.
fn measure(
    c: &Config,
    scene: &SceneCfg,
    img: &RgbImage,
    reference: &RgbImage,
    info: &SceneInfo,
    f: &Files,
) -> Result<Metrics> {
    let region = scene.mask.map(|m| crop_bounds((img.width, img.height), m));
    let lit = scene.lit_only;
    let m = compare_where(img, reference, region, |x, y| {
        !lit || lit_interior(reference, x, y)
    })
    .with_context(|| "against the reference".into())?;
    write_image(&f.png, img, info.exposure)?;
    let kind = PixelError::from_name(&c.heatmap).expect("checked");
    let range = (c.heatmap_range[0], c.heatmap_range[1]);
    write_heatmap(&f.heat, img, reference, kind, Some(range))?;
    Ok(m)
}

/// The record of a finished run.
fn result(
    c: &Config,
    (run, id): (&Run, &str),
    out: &Path,
    (args, spp, seconds): (&[String], u32, f64),
    m: &Metrics,
    f: &Files,
) -> RunResult {
    RunResult {
        id: id.to_string(),
        scene: c.scenes[run.scene].name.clone(),
        setting: c.settings[run.setting].name.clone(),
        budget: run.budget.label(),
        seed: run.seed,
        args: args.to_vec(),
        spp,
        seconds,
        photon_seconds: None,
        mse: m.mse,
        rmse: m.rmse,
        relmse: m.rel_mse,
        mae: m.mae,
        ratio: m.ratio(),
        exr: rel(out, &f.image),
        png: rel(out, &f.png),
        heatmap: rel(out, &f.heat),
    }
}

/// Renders one run with lumis and writes its EXR, PNG and heatmap; None if
/// interrupted (nothing of the run is kept then).
pub fn lumis_run(
    c: &Config,
    a: &StudyRun,
    run: &Run,
    id: &str,
    args: &[String],
    reference: &RgbImage,
    info: &SceneInfo,
) -> Result<Option<RunResult>> {
    let out = a.out.as_path();
    let scene = &c.scenes[run.scene];
    let exr = out.join(&scene.name).join(format!("{id}.exr"));
    let files = Files::new(out, scene, id, exr.clone());
    std::fs::create_dir_all(out.join(&scene.name))?;
    // The run as a job: its flags, its scene, its image.
    let mut job = (a.job_for)(args)?;
    job.scene = Some(std::path::absolute(&scene.file)?);
    job.outputs = vec![exr];
    let session = Session::new(job)?;
    if run.seed == c.seeds[0] && run.budget == c.budgets()[0] {
        for w in &session.loaded.warnings {
            (a.log)(&w.to_string());
        }
    }
    let o = session.render(RenderHooks {
        progress: &|_| {},
        cancel: a.cancel,
        after_pass: None,
        resume: None,
    });
    if o.interrupted {
        return Ok(None);
    }
    let mut img = session.image(&o, None);
    img.metadata.push((
        "lumis:study-run".into(),
        format!("{id}: {}", args.join(" ")),
    ));
    let m = measure(c, scene, &img, reference, info, &files)?;
    session.write(&img)?;
    let secs = o.elapsed.as_secs_f64();
    let mut r = result(c, (run, id), out, (args, o.spp, secs), &m, &files);
    r.photon_seconds = o
        .photon_stats
        .map(|p| (p.trace_time + p.build_time + p.radiance_time).as_secs_f64());
    Ok(Some(r))
}

/// Runs an external setting's command in the scene's report folder, reads
/// its image back and writes the PNG and heatmap; None if interrupted.
pub fn external_run(
    c: &Config,
    a: &StudyRun,
    ext: &Externals,
    (run, id): (&Run, &str),
    p: &Planned,
    reference: &RgbImage,
    info: &SceneInfo,
) -> Result<Option<RunResult>> {
    let out = a.out.as_path();
    let scene = &c.scenes[run.scene];
    let dir = out.join(&scene.name);
    std::fs::create_dir_all(&dir)?;
    let Some(seconds) = ext.run(p, &dir, id)? else {
        return Ok(None);
    };
    let img = read_image(&p.image)
        .with_context(|| "the program finished, but its image cannot be read".into())?;
    let files = Files::new(out, scene, id, p.image.clone());
    let m = measure(c, scene, &img, reference, info, &files)?;
    let r = result(c, (run, id), out, (&p.args, p.spp, seconds), &m, &files);
    Ok(Some(r))
}
