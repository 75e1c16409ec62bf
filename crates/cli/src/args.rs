//! Command-line arguments as typed (first stage); `run.rs` turns them into settings.

use clap::{Arg, ArgAction, ArgMatches, Args, FromArgMatches, Parser, Subcommand};
use lumis_render::session::{integrator_params, DEFAULT_CHECKPOINT_EVERY};
use lumis_scene::ParamSpec;
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "lumis",
    version,
    about = "A physically based renderer for caustics (pbrt-v4 scenes in, HDR images out)"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a pbrt-v4 scene (the built-in default scene if none is given).
    Render(Box<RenderArgs>),
    /// Measure BVH, path-tracing and photon-mapping speed on this machine.
    Bench(BenchArgs),
    /// Compare an image with a reference: MSE, RMSE, relMSE, MAE, channel means.
    Compare(CompareArgs),
    /// Run an equal-time study (scenes x settings x budgets x seeds) and write an HTML report.
    Study(StudyArgs),
    /// Merge the parts of a render (`render --passes A..B --partial FILE`) into
    /// its image: bit-identical to rendering it whole.
    Merge(MergeArgs),
}

#[derive(Args, Debug, Clone)]
pub struct MergeArgs {
    /// Part files, in any order; together their pass ranges must cover the
    /// render once.
    #[arg(required = true, num_args = 1..)]
    pub parts: Vec<PathBuf>,
    /// Output image (.exr, .pfm or .png). Without it, `<name>.exr` and
    /// `<name>.png` in the current folder, as `render` names them.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

#[derive(Args, Debug, Clone)]
pub struct CompareArgs {
    /// Test image (.exr, .pfm or .png).
    pub test: PathBuf,
    /// Reference image, same size.
    pub reference: PathBuf,
    /// Restrict to a region, as fractions x0,x1,y0,y1 (like --crop).
    #[arg(long, value_name = "x0,x1,y0,y1", value_parser = parse_crop)]
    pub mask: Option<[f32; 4]>,
    /// Only pixels where the test image and its eight neighbours are not
    /// black (a `lighttracer` image: black where only a specular bounce
    /// shows the camera).
    #[arg(long)]
    pub lit: bool,
    /// Write a false-colour per-pixel error map (log scale, viridis, colour bar) to this PNG.
    #[arg(long, value_name = "OUT.png")]
    pub heatmap: Option<PathBuf>,
    /// Heatmap error: `rel` (relMSE per pixel, (t-r)^2/(r^2+0.01)) or `abs` (|t-r|), channel mean.
    #[arg(long, value_name = "rel|abs", default_value = "rel")]
    pub heatmap_error: String,
    /// Heatmap range lo,hi (default: four decades below the largest error).
    #[arg(long, value_name = "lo,hi", value_parser = parse_range)]
    pub heatmap_range: Option<(f64, f64)>,
}

#[derive(Args, Debug, Clone)]
pub struct StudyArgs {
    /// Study configuration (TOML; see studies/caustics.toml).
    pub config: PathBuf,
    /// Report folder (default: `<config stem>-report` next to the config).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print one line per run only.
    #[arg(short, long)]
    pub quiet: bool,
}

#[derive(Args, Debug, Default, Clone)]
pub struct BenchArgs {
    /// Smaller sizes (100k triangles, 128x128 images) for a quick look.
    #[arg(long)]
    pub quick: bool,
    /// How cost grows instead: BVH build, memory and render time against
    /// triangles (10k to 10M), photon-map build and queries against photons
    /// (100k to 30M), and the speedup of all threads over one.
    #[arg(long)]
    pub scaling: bool,
    /// Folder for the --scaling plots (SVG) [default: lumis-bench-scaling].
    #[arg(long, value_name = "DIR")]
    pub plots: Option<std::path::PathBuf>,
    /// Instead: the rays of paths through this scene (every segment, and a
    /// shadow ray at each non-specular vertex), traced again by the
    /// built-in BVH (and by Embree in a build with the `embree` feature).
    #[arg(long, value_name = "SCENE", conflicts_with = "scaling")]
    pub rays: Option<std::path::PathBuf>,
}

#[derive(Args, Debug, Default, Clone)]
pub struct RenderArgs {
    /// Scene file (pbrt-v4). Without it, the built-in default scene.
    pub scene: Option<PathBuf>,
    /// Output image: .exr (32-bit float linear), .pfm or .png (sRGB). Without it,
    /// `<name>.exr` and `<name>.png` in the current folder, `<name>` from the Film's filename or `lumis`.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Samples per pixel (overrides the scene's Sampler).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Wall-clock budget in seconds; stops after the last whole pass that fits.
    #[arg(long, value_name = "SECONDS")]
    pub time: Option<f64>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Random seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Integrator: path, direct, photon, lighttracer or bdpt (overrides the scene's).
    #[arg(long)]
    pub integrator: Option<String>,
    /// Maximum path depth (overrides the scene's maxdepth).
    #[arg(long)]
    pub maxdepth: Option<u32>,
    /// Film resolution WxH (overrides the scene's).
    #[arg(long, value_name = "WxH", value_parser = parse_resolution)]
    pub resolution: Option<(u32, u32)>,
    /// Crop window as fractions of the image, x0,x1,y0,y1 (as pbrt's cropwindow).
    #[arg(long, value_name = "x0,x1,y0,y1", value_parser = parse_crop)]
    pub crop: Option<[f32; 4]>,
    /// Exposure in stops for PNG output.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f32,
    /// Sampler: sobol or independent (overrides the scene's).
    #[arg(long)]
    pub sampler: Option<String>,
    /// Scale each sample down so no component exceeds VALUE (biased; off by default).
    #[arg(long, value_name = "VALUE")]
    pub clamp: Option<f32>,
    /// true: splat each sample into every pixel the pixel filter reaches, weighted (Mitsuba's way; the default for filters wider than a pixel: less noise per sample); false: sample the filter, one pixel per sample (pbrt-v4's way); overrides PixelFilter's `splat`.
    #[arg(long, value_name = "true|false", num_args = 0..=1, default_missing_value = "true")]
    pub filter_splat: Option<bool>,
    /// Ray-tracing backend: the built-in BVH, or Embree 3 (builds with `--features embree`).
    #[arg(long, value_name = "bvh|embree")]
    pub accel: Option<String>,
    /// The integrators' own parameters (`--photons N`, `--caustics mis`, ...),
    /// one flag per parameter the integrators declare.
    #[command(flatten)]
    pub params: IntegratorParams,
    /// Print no progress, only warnings, errors and the summary.
    #[arg(short, long)]
    pub quiet: bool,
    /// More detail: phase timings, scene size and settings.
    #[arg(short, long, action = clap::ArgAction::Count)]
    pub verbose: u8,
    /// Print statistics at the end: rays by kind, photons, memory, time by phase.
    #[arg(long)]
    pub stats: bool,
    /// Save the render's state to FILE (atomically) every --checkpoint-every
    /// seconds, on interrupt and at the end, for --resume.
    #[arg(long, value_name = "FILE")]
    pub checkpoint: Option<PathBuf>,
    /// Seconds between checkpoints.
    #[arg(long, value_name = "SECONDS", default_value_t = DEFAULT_CHECKPOINT_EVERY)]
    pub checkpoint_every: f64,
    /// Continue the render saved in FILE, as it was set up (only -o, --threads,
    /// --time, --checkpoint*, --display-server, -q/-v and --stats may be given).
    #[arg(long, value_name = "FILE")]
    pub resume: Option<PathBuf>,
    /// Render only passes A..B of the render (0-based, B excluded; a pass is
    /// one sample per pixel, a progressive `photon` iteration `iterationspp`
    /// passes) and save them as a part to --partial FILE, for `lumis merge`.
    #[arg(long, value_name = "A..B", value_parser = parse_pass_range, requires = "partial")]
    pub passes: Option<std::ops::Range<u32>>,
    /// The part file of a --passes render (saved like a checkpoint: every
    /// --checkpoint-every seconds, on interrupt and at the end; an
    /// unfinished part continues with --resume FILE).
    #[arg(
        long,
        value_name = "FILE",
        requires = "passes",
        conflicts_with = "checkpoint"
    )]
    pub partial: Option<PathBuf>,
    /// Stream the image as it converges to a tev viewer at HOST:PORT (tev listens on 127.0.0.1:14158).
    #[arg(long, value_name = "HOST:PORT")]
    pub display_server: Option<String>,
    /// Test hook: make the sample at pixel X,Y with index S a NaN.
    #[arg(long, hide = true, value_name = "X,Y,S", value_parser = parse_triple)]
    pub inject_nan: Option<(u32, u32, u32)>,
}

/// Flags made from the integrators' parameter tables (the library's
/// `session::integrator_params`): `--caustic-photons N` for
/// `"integer causticphotons"`, so each parameter is declared once.
#[derive(Clone, Debug, Default)]
pub struct IntegratorParams {
    /// The parameters given, with their values as typed, in table order.
    pub values: Vec<(&'static ParamSpec, String)>,
}

impl FromArgMatches for IntegratorParams {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let values = integrator_params()
            .into_iter()
            .filter_map(|p| {
                m.get_one::<String>(p.spec.name)
                    .map(|v| (p.spec, v.clone()))
            })
            .collect();
        Ok(IntegratorParams { values })
    }
    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = IntegratorParams::from_arg_matches(m)?;
        Ok(())
    }
}

impl Args for IntegratorParams {
    fn augment_args(mut cmd: clap::Command) -> clap::Command {
        for p in integrator_params() {
            let s = p.spec;
            let mut a = Arg::new(s.name)
                .long(s.words)
                .value_name(s.value)
                .help(p.help)
                .action(ArgAction::Set);
            if s.ty == "bool" {
                // `--aim-caustics` alone means true.
                a = a.num_args(0..=1).default_missing_value("true");
            }
            cmd = cmd.arg(a);
        }
        cmd
    }
    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        IntegratorParams::augment_args(cmd)
    }
}

fn parse_triple(s: &str) -> Result<(u32, u32, u32), String> {
    let v: Result<Vec<u32>, _> = s.split(',').map(|t| t.trim().parse::<u32>()).collect();
    match v.as_deref() {
        Ok([a, b, c]) => Ok((*a, *b, *c)),
        _ => Err(format!("expected three integers X,Y,S, found `{s}`")),
    }
}

pub fn parse_range(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| format!("expected lo,hi, found `{s}`"))?;
    let (a, b): (f64, f64) = match (a.trim().parse(), b.trim().parse()) {
        (Ok(a), Ok(b)) => (a, b),
        _ => return Err(format!("expected two numbers lo,hi, found `{s}`")),
    };
    if !(a > 0.0 && b > a && b.is_finite()) {
        return Err(format!("need 0 < lo < hi (a log scale), found `{s}`"));
    }
    Ok((a, b))
}

fn parse_resolution(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WxH, e.g. 640x480, found `{s}`"))?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("bad width in `{s}`"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("bad height in `{s}`"))?;
    if w == 0 || h == 0 {
        return Err("resolution must be at least 1x1".into());
    }
    Ok((w, h))
}

fn parse_pass_range(s: &str) -> Result<std::ops::Range<u32>, String> {
    let bad = || format!("expected a pass range A..B (whole numbers, A < B), found `{s}`");
    let (a, b) = s.split_once("..").ok_or_else(bad)?;
    let (a, b) = (a.trim().parse::<u32>(), b.trim().parse::<u32>());
    match (a, b) {
        (Ok(a), Ok(b)) if a < b => Ok(a..b),
        _ => Err(bad()),
    }
}

fn parse_crop(s: &str) -> Result<[f32; 4], String> {
    let v: Result<Vec<f32>, _> = s.split(',').map(|t| t.trim().parse::<f32>()).collect();
    let v = v.map_err(|_| format!("expected four numbers x0,x1,y0,y1, found `{s}`"))?;
    if v.len() != 4 {
        return Err(format!(
            "expected four numbers x0,x1,y0,y1, found {}",
            v.len()
        ));
    }
    if v.iter().any(|x| !(0.0..=1.0).contains(x)) || v[0] >= v[1] || v[2] >= v[3] {
        return Err("crop values are fractions in [0,1] with x0 < x1 and y0 < y1".into());
    }
    Ok([v[0], v[1], v[2], v[3]])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_resolution_and_crop() {
        assert_eq!(parse_resolution("640x480"), Ok((640, 480)));
        assert!(parse_resolution("640").is_err());
        assert!(parse_resolution("0x5").is_err());
        assert_eq!(parse_crop("0,0.5,0.25,1"), Ok([0.0, 0.5, 0.25, 1.0]));
        assert!(parse_crop("0.5,0.2,0,1").is_err());
        assert_eq!(parse_range("1e-4,10"), Ok((1e-4, 10.0)));
        assert!(parse_range("0,1").is_err());
        assert!(parse_range("2,1").is_err());
    }
}
