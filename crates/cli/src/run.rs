//! Subcommands: `render` maps its arguments to a job and drives a library
//! session, printing progress and the summary; the others are thin too.

use crate::args::{Cli, Command, RenderArgs};
use crate::interrupt::{install_interrupt_handler, CANCEL, EXIT_INTERRUPTED};
use crate::progress::Reporter;
use anyhow::Result;
use lumis_render::checkpoint::Checkpoint;
use lumis_render::film::{Film, PixelBounds};
use lumis_render::image_io::RgbImage;
use lumis_render::integrator::{BadSample, RenderHooks, RenderOutcome, RenderState};
use lumis_render::session::{load_checkpoint, Phases, RenderJob, Session};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        None => render_cmd(RenderArgs::default()),
        Some(Command::Render(a)) => render_cmd(*a),
        Some(Command::Bench(a)) if a.scaling => {
            crate::bench_scaling::run(&a).map(|_| ExitCode::SUCCESS)
        }
        Some(Command::Bench(a)) => match &a.rays {
            Some(scene) => crate::bench_rays::run(scene, a.quick),
            None => crate::bench::run(a),
        }
        .map(|_| ExitCode::SUCCESS),
        Some(Command::Compare(a)) => compare_cmd(a),
        Some(Command::Study(a)) => crate::study::run(a),
        Some(Command::Merge(a)) => merge_cmd(a),
    }
}

fn compare_cmd(a: crate::args::CompareArgs) -> Result<ExitCode> {
    use lumis_render::image_io::read_image;
    use lumis_render::metrics::{compare_where, lit_interior, PixelError};
    let kind = PixelError::from_name(&a.heatmap_error).ok_or_else(|| {
        anyhow::anyhow!("unknown --heatmap-error `{}` (rel or abs)", a.heatmap_error)
    })?;
    let t = read_image(&a.test)?;
    let r = read_image(&a.reference)?;
    let region = a
        .mask
        .map(|m| lumis_render::load::options::crop_bounds((t.width, t.height), m));
    let m = compare_where(&t, &r, region, |x, y| !a.lit || lit_interior(&t, x, y))
        .map_err(|e| anyhow::anyhow!("{}: {e}", a.test.display()))?;
    outln!("pixels   {}", m.pixels);
    outln!("MSE      {:.6e}", m.mse);
    outln!("RMSE     {:.6e}", m.rmse);
    outln!("relMSE   {:.6e}", m.rel_mse);
    outln!("MAE      {:.6e}", m.mae);
    outln!(
        "mean     test {:.6} {:.6} {:.6}  reference {:.6} {:.6} {:.6}",
        m.mean_test[0],
        m.mean_test[1],
        m.mean_test[2],
        m.mean_ref[0],
        m.mean_ref[1],
        m.mean_ref[2]
    );
    let q = m.ratio();
    outln!("ratio    {:.4} {:.4} {:.4}", q[0], q[1], q[2]);
    if let Some(path) = &a.heatmap {
        let (lo, hi) =
            lumis_render::metrics::heatmap::write_heatmap(path, &t, &r, kind, a.heatmap_range)
                .map_err(anyhow::Error::msg)?;
        outln!(
            "heatmap  {} ({} error per pixel, log scale {lo:.2e} .. {hi:.2e})",
            path.display(),
            match kind {
                PixelError::Relative => "relative squared",
                PixelError::Absolute => "absolute",
            }
        );
    }
    Ok(ExitCode::SUCCESS)
}

fn render_cmd(a: RenderArgs) -> Result<ExitCode> {
    let (job, resumed) = job_and_checkpoint(&a)?;
    let session = Session::new(job)?;
    for w in &session.loaded.warnings {
        eprintln!("{w}");
    }
    if a.verbose > 0 {
        crate::stats::print_setup(&session.loaded, &session.settings, &session.phases);
    }
    let mut resume_state = None;
    if let Some((file, ck)) = &resumed {
        let st = session.resume_state(ck, &file.display().to_string())?;
        let target = match session.settings.spp {
            0 => "a time budget".to_string(),
            n => n.to_string(),
        };
        eprintln!(
            "lumis: resuming {} at {} spp of {target}",
            file.display(),
            st.spp_done
        );
        resume_state = Some(st);
    }
    let job = &session.job;
    let mut saver = job.checkpoint.as_ref().map(|c| {
        // Each save puts the render's state in; the template holds no pixels.
        let none = PixelBounds {
            x0: 0,
            x1: 0,
            y0: 0,
            y1: 0,
        };
        let empty = RenderState::new(Film::new((0, 0), none));
        crate::resume::Saver::new(
            job.resolve(&c.path),
            Duration::from_secs_f64(c.every),
            session.checkpoint(empty),
        )
    });
    let reporter = Reporter::new(a.quiet);
    install_interrupt_handler();
    let crop = session.settings.crop;
    let mut display = a.display_server.as_ref().map(|addr| {
        let name = session.outputs[0]
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "lumis".into());
        crate::display::Display::start(addr, &name, crop.width(), crop.height())
    });
    let mut after_pass = |st: &RenderState| {
        if let Some(sv) = saver.as_mut() {
            sv.maybe_save(st);
        }
        if let Some(d) = display.as_mut() {
            d.offer(|| session.scaled(&st.film));
        }
    };
    let mut out = session.render(RenderHooks {
        progress: &|p| reporter.update(p),
        cancel: &CANCEL,
        after_pass: Some(&mut after_pass),
        resume: resume_state,
    });
    reporter.finish();
    let partial = session.job.passes.is_some();
    let mut part_file = None;
    if let Some(sv) = saver.as_mut() {
        let saved = sv.save_outcome(&mut out);
        match (saved, partial) {
            (true, false) => {
                eprintln!("lumis: checkpoint {} at {} spp", sv.path.display(), out.spp)
            }
            (true, true) => part_file = Some(sv.path.clone()),
            (false, true) => anyhow::bail!("the part was not saved: {}", sv.path.display()),
            (false, false) => {}
        }
    }
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let img = session.image(&out, Some(&command));
    if let Some(d) = display {
        d.finish(img.data.clone());
    }
    let t = Instant::now();
    let mut files = session.write(&img)?;
    let write_time = t.elapsed();
    files.extend(part_file);
    print_summary(&session, &out, &img, &files);
    if a.stats {
        let phases = Phases {
            write: write_time,
            ..session.phases
        };
        crate::stats::print(&session.loaded, &out, &phases);
    }
    if out.bad_samples > 0 {
        let b = out.first_bad.unwrap_or(BadSample {
            x: 0,
            y: 0,
            sample: 0,
        });
        eprintln!(
            "lumis: dropped {} NaN/infinite samples (first at pixel {},{}, sample {})",
            out.bad_samples, b.x, b.y, b.sample
        );
    }
    if out.interrupted {
        let what = match partial {
            true => "saved the part so far (finish it with --resume)",
            false => "wrote the image so far",
        };
        eprintln!("lumis: interrupted: {what} ({} spp)", out.spp);
        return Ok(ExitCode::from(EXIT_INTERRUPTED));
    }
    Ok(ExitCode::SUCCESS)
}

/// `lumis merge`: the parts' sums added, written as the whole render's image.
fn merge_cmd(a: crate::args::MergeArgs) -> Result<ExitCode> {
    use lumis_render::session::{merge, merged_image, Part};
    let t = Instant::now();
    let parts = a
        .parts
        .iter()
        .map(|p| Part::read(p))
        .collect::<Result<Vec<_>, _>>()?;
    // Relative outputs resolve against this folder (the merged job's).
    let (session, out) = merge(&parts, Some(a.output.into_iter().collect()))?;
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let img = merged_image(&session, &out, parts.len(), Some(&command));
    let files = session.write(&img)?;
    let names: Vec<String> = files.iter().map(|f| shown(f, &session.job.dir)).collect();
    eprintln!(
        "lumis: merged {} parts: {}x{} {} spp ({}) rendered in {:.2} s over all parts; merged in {:.2} s -> {}",
        parts.len(),
        img.width,
        img.height,
        out.spp,
        session.loaded.options.integrator.name(),
        out.elapsed.as_secs_f64(),
        t.elapsed().as_secs_f64(),
        names.join(", ")
    );
    if out.bad_samples > 0 {
        eprintln!(
            "lumis: the parts dropped {} NaN/infinite samples",
            out.bad_samples
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// The job the arguments describe and, with `--resume`, the checkpoint
/// (and its path) the render continues.
fn job_and_checkpoint(a: &RenderArgs) -> Result<(RenderJob, Option<(PathBuf, Checkpoint)>)> {
    let out = match &a.resume {
        None => (crate::job::job_from_args(a)?, None),
        Some(file) => {
            let file = std::path::absolute(file).unwrap_or(file.clone());
            let (saved, ck) = load_checkpoint(&file)?;
            let job = match &a.scene {
                // The arguments describe the render; the checkpoint must match.
                Some(_) => {
                    let mut job = crate::job::job_from_args(a)?;
                    job.checkpoint
                        .get_or_insert(lumis_render::session::CheckpointSpec {
                            path: file.clone(),
                            every: a.checkpoint_every,
                        });
                    job
                }
                None => crate::job::resumed_job(a, saved)?,
            };
            (job, Some((file, ck)))
        }
    };
    Ok(out)
}

/// The closing summary: size, samples, integrator, time, rays, files; the
/// photon pass for `photon`.
fn print_summary(session: &Session, out: &RenderOutcome, img: &RgbImage, files: &[PathBuf]) {
    let secs = out.elapsed.as_secs_f64();
    let names: Vec<String> = files.iter().map(|f| shown(f, &session.job.dir)).collect();
    let spp = match &session.job.passes {
        Some(r) => format!("passes {}..{} of {}", r.start, r.end, session.settings.spp),
        None => format!("{} spp", out.spp),
    };
    eprintln!(
        "lumis: {}x{} {spp} ({}) in {:.2} s, {:.2} Mrays/s -> {}",
        img.width,
        img.height,
        session.loaded.options.integrator.name(),
        secs,
        out.rays as f64 / secs.max(1e-9) / 1e6,
        names.join(", ")
    );
    if let Some(ps) = &out.photon_stats {
        eprintln!(
            "lumis: photons: {} global, {} caustic stored; tracing {:.2} s, maps {:.2} s, radiance photons {:.2} s, {:.1} MiB",
            ps.global_stored,
            ps.caustic_stored,
            ps.trace_time.as_secs_f64(),
            ps.build_time.as_secs_f64(),
            ps.radiance_time.as_secs_f64(),
            ps.memory_bytes as f64 / (1u64 << 20) as f64
        );
        if ps.iterations > 0 {
            let (g, c) = ps.iteration_photons;
            eprintln!(
                "lumis: progressive: {} iterations of {g} global and {c} caustic photons, last caustic radius {:.3e}",
                ps.render_iterations, ps.caustic_radius
            );
            if ps.counts_chosen {
                eprintln!(
                    "lumis: photon counts chosen for the time budget; the same image without it: --iterations {} --photons {g} --caustic-photons {c}",
                    ps.render_iterations
                );
            }
        }
    }
}

/// A written file as the user named it: relative to the job's folder when inside it.
fn shown(f: &Path, dir: &Path) -> String {
    f.strip_prefix(dir).unwrap_or(f).display().to_string()
}
