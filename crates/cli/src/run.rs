//! Arguments → overrides → load → render → write.

use crate::args::{Cli, Command, RenderArgs};
use crate::progress::Reporter;
use crate::resume::template_state as resume_template_state;
use anyhow::{bail, Context, Result};
use lumis_math::SamplerKind;
use lumis_render::checkpoint::Checkpoint;
use lumis_render::image_io::{write_image, ImageFormat, RgbImage};
use lumis_render::integrator::{
    render_with, BadSample, RenderHooks, RenderOutcome, RenderSettings, RenderState,
};
use lumis_render::load::options::RenderOptions;
use lumis_render::load::photon::PhotonOverrides;
use lumis_render::load::{build_scene, BuildOverrides, LoadedScene, DEFAULT_SCENE};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Exit status of a render stopped by SIGINT/SIGTERM after writing its image (128 + SIGINT).
pub const EXIT_INTERRUPTED: u8 = 130;

/// Set by the first SIGINT/SIGTERM: no further passes start.
pub(crate) static CANCEL: AtomicBool = AtomicBool::new(false);

/// First Ctrl-C (or SIGTERM): finish the current pass, write the image, exit
/// with [`EXIT_INTERRUPTED`]. Second: exit at once.
pub(crate) fn install_interrupt_handler() {
    let _ = ctrlc::set_handler(|| {
        if CANCEL.swap(true, Ordering::SeqCst) {
            eprintln!("\nlumis: interrupted twice: exiting without writing");
            std::process::exit(EXIT_INTERRUPTED as i32);
        }
        eprintln!("\nlumis: interrupt: finishing this pass, then writing the image (Ctrl-C again to quit now)");
    });
}

pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        None => render_cmd(RenderArgs::default()),
        Some(Command::Render(a)) => render_cmd(*a),
        Some(Command::Bench(a)) => crate::bench::run(a).map(|_| ExitCode::SUCCESS),
        Some(Command::Compare(a)) => compare_cmd(a),
        Some(Command::Study(a)) => crate::study::run(a),
    }
}

fn compare_cmd(a: crate::args::CompareArgs) -> Result<ExitCode> {
    use lumis_render::image_io::read_image;
    use lumis_render::metrics::{compare, PixelError};
    let kind = PixelError::from_name(&a.heatmap_error).ok_or_else(|| {
        anyhow::anyhow!("unknown --heatmap-error `{}` (rel or abs)", a.heatmap_error)
    })?;
    let t = read_image(&a.test)?;
    let r = read_image(&a.reference)?;
    let region = a
        .mask
        .map(|m| lumis_render::load::options::crop_bounds((t.width, t.height), m));
    let m = compare(&t, &r, region).map_err(|e| anyhow::anyhow!("{}: {e}", a.test.display()))?;
    println!("pixels   {}", m.pixels);
    println!("MSE      {:.6e}", m.mse);
    println!("RMSE     {:.6e}", m.rmse);
    println!("relMSE   {:.6e}", m.rel_mse);
    println!("MAE      {:.6e}", m.mae);
    println!(
        "mean     test {:.6} {:.6} {:.6}  reference {:.6} {:.6} {:.6}",
        m.mean_test[0], m.mean_test[1], m.mean_test[2], m.mean_ref[0], m.mean_ref[1], m.mean_ref[2]
    );
    let q = m.ratio();
    println!("ratio    {:.4} {:.4} {:.4}", q[0], q[1], q[2]);
    if let Some(path) = &a.heatmap {
        let (lo, hi) = crate::heatmap::write_heatmap(path, &t, &r, kind, a.heatmap_range)?;
        println!(
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

pub(crate) fn overrides(a: &RenderArgs) -> Result<BuildOverrides> {
    let sampler = match a.sampler.as_deref() {
        None => None,
        Some("sobol") => Some(SamplerKind::Sobol),
        Some("independent") => Some(SamplerKind::Independent),
        Some(other) => bail!("unknown sampler `{other}` (available: sobol, independent)"),
    };
    Ok(BuildOverrides {
        resolution: a.resolution,
        crop: a.crop,
        spp: a.spp,
        integrator: a.integrator.clone(),
        max_depth: a.maxdepth,
        sampler,
        photon: PhotonOverrides {
            caustics: a.caustics.clone(),
            heuristic: a.heuristic.clone(),
            alpha: a.alpha.clone(),
            photons: a.photons,
            caustic_photons: a.caustic_photons,
            nearest: a.nearest,
            gather_rays: a.gather_rays,
            max_radius: a.max_radius,
            kernel: a.kernel.clone(),
            radiance_photons: None,
            aim_caustics: a.aim_caustics.then_some(true),
        },
    })
}

/// Output files: `-o` alone, or `<stem>.exr` and `<stem>.png` in the current folder.
fn outputs(a: &RenderArgs, film_name: Option<&str>) -> Result<Vec<PathBuf>> {
    if let Some(o) = &a.output {
        ImageFormat::from_path(o)?;
        return Ok(vec![o.clone()]);
    }
    let stem = film_name
        .and_then(|f| {
            Path::new(f)
                .file_stem()
                .map(|s| s.to_string_lossy().to_string())
        })
        .unwrap_or_else(|| "lumis".to_string());
    Ok(vec![
        PathBuf::from(format!("{stem}.exr")),
        PathBuf::from(format!("{stem}.png")),
    ])
}

fn render_cmd(a: RenderArgs) -> Result<ExitCode> {
    if let Some(t) = a.time {
        if !(t > 0.0 && t.is_finite()) {
            bail!("--time must be a positive number of seconds, found {t}");
        }
    }
    if !(a.checkpoint_every >= 0.0 && a.checkpoint_every.is_finite()) {
        bail!(
            "--checkpoint-every must be a number of seconds >= 0, found {}",
            a.checkpoint_every
        );
    }
    let (a, resumed) = crate::resume::prepare(a)?;
    let ov = overrides(&a)?;
    let scene_text: Vec<u8> = match &a.scene {
        Some(p) => std::fs::read(p).unwrap_or_default(),
        None => DEFAULT_SCENE.as_bytes().to_vec(),
    };
    let mut phases = crate::stats::Phases::default();
    let t = Instant::now();
    let desc = match &a.scene {
        Some(p) => lumis_scene::load_file(p),
        None => lumis_scene::load_str(DEFAULT_SCENE, "<built-in default scene>", Path::new(".")),
    }
    .map_err(|d| anyhow::anyhow!("{d}"))?;
    phases.parse = t.elapsed();
    let t = Instant::now();
    let mut loaded: LoadedScene = build_scene(&desc, &ov).map_err(|d| anyhow::anyhow!("{d}"))?;
    select_accel(&mut loaded.scene, a.accel.as_deref())?;
    phases.build = t.elapsed();
    drop(desc);
    for w in &loaded.warnings {
        eprintln!("{w}");
    }
    let o = &loaded.options;
    let files = outputs(&a, o.filename.as_deref())?;
    // With only a time budget, the sample count is unbounded.
    let spp = match &resumed {
        Some(ck) if ck.spp_target == 0 && a.spp.is_none() => {
            if a.time.is_none() {
                bail!("this render had only a time budget: give --time SECONDS to resume it");
            }
            0
        }
        Some(_) => o.spp,
        None if a.time.is_some() && a.spp.is_none() => 0,
        None => o.spp,
    };
    let settings = render_settings(&a, o, spp);
    if a.verbose > 0 {
        crate::stats::print_setup(&loaded, &settings, &phases);
    }
    let hash = crate::resume::scene_hash(&scene_text, &loaded.scene, o, &settings);
    let mut resume_state = None;
    let mut command: Vec<String> = std::env::args().skip(1).collect();
    let mut cwd = std::env::current_dir()
        .map(|d| d.display().to_string())
        .unwrap_or_default();
    if let (Some(ck), Some(file)) = (resumed, &a.resume) {
        crate::resume::check(&ck, file, hash)?;
        eprintln!(
            "lumis: resuming {} at {} spp of {}",
            file.display(),
            ck.state.spp_done,
            if ck.spp_target == 0 {
                "a time budget".to_string()
            } else {
                ck.spp_target.to_string()
            }
        );
        if !ck.command.is_empty() {
            command = ck.command;
            cwd = ck.cwd;
        }
        resume_state = Some(ck.state);
    }
    let mut saver = a.checkpoint.as_ref().map(|path| {
        let template = Checkpoint {
            lumis_version: env!("CARGO_PKG_VERSION").into(),
            scene_hash: hash,
            seed: a.seed,
            spp_target: settings.spp,
            command,
            cwd,
            state: resume_template_state(o.crop),
        };
        let path = std::path::absolute(path).unwrap_or(path.clone());
        crate::resume::Saver::new(path, Duration::from_secs_f64(a.checkpoint_every), template)
    });
    let reporter = Reporter::new(a.quiet);
    install_interrupt_handler();
    let (scale, wb) = (o.imaging_scale, o.white_balance);
    let scaled = move |film: &lumis_render::film::Film| scaled_mean(film, scale, wb);
    let mut display = a.display_server.as_ref().map(|addr| {
        let name = files[0]
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "lumis".into());
        crate::display::Display::start(addr, &name, o.crop.width(), o.crop.height())
    });
    let mut after_pass = |st: &RenderState| {
        if let Some(sv) = saver.as_mut() {
            sv.maybe_save(st);
        }
        if let Some(d) = display.as_mut() {
            d.offer(|| scaled(&st.film));
        }
    };
    let mut out = render_with(
        &loaded.scene,
        &o.integrator,
        &settings,
        RenderHooks {
            progress: &|p| reporter.update(p),
            cancel: &CANCEL,
            after_pass: Some(&mut after_pass),
            resume: resume_state,
        },
    );
    reporter.finish();
    if let Some(sv) = saver.as_mut() {
        if sv.save_outcome(&mut out) {
            eprintln!("lumis: checkpoint {} at {} spp", sv.path.display(), out.spp);
        }
    }
    let data = scaled(&out.film);
    if let Some(d) = display {
        d.finish(data.clone());
    }
    let mut img = RgbImage::new(out.film.width(), out.film.height(), data);
    let scene_name = a
        .scene
        .as_ref()
        .map(|p| p.display().to_string())
        .unwrap_or_else(|| "<default>".into());
    img.metadata = image_metadata(&out, o, a.seed, scene_name);
    img.metadata.extend([
        ("lumis:bad_samples".into(), out.bad_samples.to_string()),
        (
            "lumis:command".into(),
            std::env::args().collect::<Vec<_>>().join(" "),
        ),
    ]);
    if let Some(b) = out.first_bad {
        img.metadata.push((
            "lumis:first_bad_sample".into(),
            format!("pixel {},{} sample {}", b.x, b.y, b.sample),
        ));
    }
    let t = Instant::now();
    for f in &files {
        write_image(f, &img, a.exposure).with_context(|| format!("writing {}", f.display()))?;
    }
    phases.write = t.elapsed();
    let secs = out.elapsed.as_secs_f64();
    let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
    eprintln!(
        "lumis: {}x{} {} spp ({}) in {:.2} s, {:.2} Mrays/s -> {}",
        img.width,
        img.height,
        out.spp,
        o.integrator.kind.name(),
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
    }
    if a.stats {
        crate::stats::print(&loaded, &out, &phases);
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
        eprintln!(
            "lumis: interrupted: wrote the image so far ({} spp)",
            out.spp
        );
        return Ok(ExitCode::from(EXIT_INTERRUPTED));
    }
    Ok(ExitCode::SUCCESS)
}

/// The render settings `a` asks for on top of the scene's options, with `spp`
/// samples per pixel (0: until the time budget ends).
pub(crate) fn render_settings(a: &RenderArgs, o: &RenderOptions, spp: u32) -> RenderSettings {
    RenderSettings {
        time_limit: a.time.map(Duration::from_secs_f64),
        clamp: a.clamp,
        inject_nan: a.inject_nan,
        ..RenderSettings::from_options(o, spp, a.seed, a.threads.unwrap_or(0))
    }
}

/// The film's mean image times the scene's imaging scale.
pub(crate) fn scaled_mean(
    film: &lumis_render::film::Film,
    scale: f32,
    white_balance: Option<lumis_math::Mat3>,
) -> Vec<f32> {
    let mut d = film.mean_image();
    if scale != 1.0 || white_balance.is_some() {
        lumis_render::load::RenderOptions::to_output(scale, white_balance, &mut d);
    }
    d
}

/// What every written image records of how it was made.
pub(crate) fn image_metadata(
    out: &RenderOutcome,
    o: &RenderOptions,
    seed: u64,
    scene_name: String,
) -> Vec<(String, String)> {
    vec![
        ("lumis:spp".into(), out.spp.to_string()),
        ("lumis:integrator".into(), o.integrator.kind.name().into()),
        ("lumis:seed".into(), seed.to_string()),
        ("lumis:scene".into(), scene_name),
    ]
}

/// `--accel`: the built-in BVH (default) or Embree (feature `embree`).
fn select_accel(scene: &mut lumis_render::scene::Scene, accel: Option<&str>) -> Result<()> {
    match accel.unwrap_or("bvh") {
        "bvh" => {}
        #[cfg(feature = "embree")]
        "embree" => scene.use_embree(true),
        #[cfg(not(feature = "embree"))]
        "embree" => {
            let _ = scene;
            bail!("this lumis was built without Embree: build it with `--features embree` (needs libembree-dev)")
        }
        other => bail!("unknown --accel `{other}`: expected `bvh` or `embree`"),
    }
    Ok(())
}
