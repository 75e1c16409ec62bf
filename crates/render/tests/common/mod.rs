//! Helpers shared by the integration tests of lumis-render: scene text,
//! loading and rendering, image statistics; chi-square tests of sampling
//! routines (`chi2`), environment maps written to disk (`envmap`) and the
//! checks the bidirectional integrators share (`bidir`).
#![allow(dead_code)]

pub mod bidir;
pub mod chi2;
pub mod envmap;
pub mod media;

use lumis_render::film::Film;
use lumis_render::integrator::{
    render, render_with, RenderHooks, RenderOutcome, RenderSettings, RenderState,
};
use lumis_render::load::{load_text, LoadedScene, Overrides};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

pub fn load(text: &str, ov: &Overrides) -> LoadedScene {
    load_text(text, "test.pbrt", Path::new("."), ov)
        .unwrap_or_else(|e| panic!("scene failed to load:\n{e}"))
}

/// A point light over a sphere of `material` (scene lines 5 and on), as
/// `s.pbrt`: errors come back as text, for checking their locations.
pub fn load_material(material: &str) -> Result<LoadedScene, String> {
    let text = format!(
        "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n\
         Camera \"perspective\"\nWorldBegin\nLightSource \"point\" \"rgb I\" [1 1 1]\n\
         {material}\nShape \"sphere\"\n"
    );
    load_text(&text, "s.pbrt", Path::new("."), &Overrides::default()).map_err(|e| e.to_string())
}

pub fn settings(l: &LoadedScene, spp: u32, seed: u64, threads: usize) -> RenderSettings {
    l.options.render_settings(spp, seed, threads)
}

pub fn render_loaded(l: &LoadedScene, spp: u32, seed: u64, threads: usize) -> RenderOutcome {
    render(
        &l.scene,
        &l.options.integrator,
        &settings(l, spp, seed, threads),
        &|_| {},
        &AtomicBool::new(false),
    )
}

/// The preamble of the small analytic scenes: an independent sampler at 4
/// spp, a box filter and a `res` x `res` RGB film (no final newline).
pub fn header(res: u32) -> String {
    format!(
        r#"Sampler "independent" "integer pixelsamples" [ 4 ]
PixelFilter "box"
Film "rgb" "integer xresolution" [ {res} ] "integer yresolution" [ {res} ]"#
    )
}

/// Inside a closed, two-sided emitting diffuse sphere (radius 3, albedo
/// `albedo`, `Le` = `le`) at 24x24: radiance `le sum_{k<=d} albedo^k` with
/// `d` = `maxdepth` scattering events, `le / (1 - albedo)` without a limit.
pub fn emitting_furnace(albedo: f32, le: f32, integrator: &str, maxdepth: u32) -> String {
    format!(
        r#"Integrator "{integrator}" "integer maxdepth" [ {maxdepth} ]
{}
LookAt 0.1 0.2 0.3  1 0.5 -0.2  0 1 0
Camera "perspective" "float fov" [ 80 ]
WorldBegin
AreaLightSource "diffuse" "rgb L" [ {le} {le} {le} ] "bool twosided" true
Material "diffuse" "rgb reflectance" [ {albedo} {albedo} {albedo} ]
Shape "sphere" "float radius" [ 3 ]
"#,
        header(24)
    )
}

/// A white furnace: a unit sphere of `material` in a uniform environment of
/// radiance 1, rendered by `integrator` (maxdepth 300) at 24x24. A closed
/// lossless object looks exactly like the environment: radiance 1 everywhere.
pub fn white_furnace(integrator: &str, material: &str) -> String {
    format!(
        r#"Integrator "{integrator}" "integer maxdepth" [ 300 ]
{}
LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
{material}
Shape "sphere" "float radius" [ 1 ]
"#,
        header(24)
    )
}

/// Mean of `vals` and its standard error from their spread (the values are
/// independent estimates).
pub fn sample_mean_and_se(vals: &[f64]) -> (f64, f64) {
    let n = vals.len() as f64;
    let mean = vals.iter().sum::<f64>() / n;
    let var = vals.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Mean over all pixels and channels, and its standard error estimated from
/// the spread of per-pixel means (pixels are independent estimates).
pub fn mean_and_se(film: &Film, channel: Option<usize>) -> (f64, f64) {
    assert_unsplatted(film);
    sample_mean_and_se(&pixel_values(film, channel))
}

/// Each pixel's value of `channel`, or its channels' average.
fn pixel_values(film: &Film, channel: Option<usize>) -> Vec<f64> {
    image_means(film)
        .into_iter()
        .map(|m| match channel {
            Some(c) => m[c],
            None => m.iter().sum::<f64>() / 3.0,
        })
        .collect()
}

/// The standard errors above take pixels as independent estimates, which
/// a splatting filter's are not (neighbours share samples), and read a
/// pixel's variance as its samples' (a splatted pixel's samples are
/// weighted sums over its weight).
fn assert_unsplatted(film: &Film) {
    assert!(
        film.weights.is_empty(),
        "this statistic needs the filter sampled: `PixelFilter ... \"bool splat\" false` (`--filter-splat false`)"
    );
}

/// Mean over all pixels (of `channel`, or of the channel average), of any
/// film, splatted or not.
pub fn image_mean(film: &Film, channel: Option<usize>) -> f64 {
    let vals = pixel_values(film, channel);
    vals.iter().sum::<f64>() / vals.len() as f64
}

/// Each pixel's estimate: its samples' mean plus its splats (light paths
/// connected to the camera) over the samples per pixel.
pub fn image_means(film: &Film) -> Vec<[f64; 3]> {
    film.mean_image()
        .chunks_exact(3)
        .map(|c| [c[0] as f64, c[1] as f64, c[2] as f64])
        .collect()
}

/// Mean over the film's pixels (of `channel`, or of the channel average)
/// and the variance of that mean from the pixels' own variances of their
/// means: the square of its standard error. Splats count in the mean but
/// not in the variance (the film keeps no spread of them).
pub fn region_mean_and_var(film: &Film, channel: Option<usize>) -> (f64, f64) {
    assert_unsplatted(film);
    let n = film.pixels.len() as f64;
    let (mut sum, mut var) = (0.0, 0.0);
    for (p, mean) in film.pixels.iter().zip(image_means(film)) {
        let v = p.variance_of_mean();
        let (m, v) = match channel {
            Some(c) => (mean[c], v[c] as f64),
            None => (mean.iter().sum::<f64>() / 3.0, v.average() as f64),
        };
        sum += m;
        var += v;
    }
    (sum / n, var / (n * n))
}

/// [`region_mean_and_var`] with the standard error.
pub fn region_mean_and_se(film: &Film, channel: Option<usize>) -> (f64, f64) {
    let (mean, var) = region_mean_and_var(film, channel);
    (mean, var.sqrt())
}

pub fn independent() -> Overrides {
    let mut o = Overrides::default();
    o.sampler("independent");
    o
}

/// `../shared/scenes/<rel>` if present. Absent: prints a notice and returns
/// None, unless LUMIS_REQUIRE_SHARED=1, which makes it a failure.
pub fn shared_scene(rel: &str) -> Option<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    let p = root.join(rel);
    if p.exists() {
        return Some(p);
    }
    if std::env::var("LUMIS_REQUIRE_SHARED").as_deref() == Ok("1") {
        panic!("LUMIS_REQUIRE_SHARED=1 but {} is missing", p.display());
    }
    eprintln!("skipping: ../shared/scenes not found ({})", p.display());
    None
}

/// Renders `settings`, stopping (as SIGINT would) once `stop_at` spp are
/// done; `resume` continues a saved state.
pub fn render_until(
    l: &LoadedScene,
    settings: &RenderSettings,
    stop_at: Option<u32>,
    resume: Option<RenderState>,
) -> RenderOutcome {
    let cancel = AtomicBool::new(false);
    let mut after = |s: &RenderState| {
        if Some(s.spp_done) == stop_at {
            cancel.store(true, Ordering::Relaxed);
        }
    };
    render_with(
        &l.scene,
        &l.options.integrator,
        settings,
        RenderHooks {
            progress: &|_| {},
            cancel: &cancel,
            after_pass: Some(&mut after),
            resume,
        },
    )
}

/// Renders a library session's job, stopping (as SIGINT would) after
/// `stop_after` passes if given.
pub fn render_session(
    s: &lumis_render::session::Session,
    stop_after: Option<u32>,
) -> RenderOutcome {
    let cancel = AtomicBool::new(false);
    let mut passes = 0;
    let mut after = |_: &RenderState| {
        passes += 1;
        if Some(passes) == stop_after {
            cancel.store(true, Ordering::Relaxed);
        }
    };
    s.render(RenderHooks {
        progress: &|_| {},
        cancel: &cancel,
        after_pass: Some(&mut after),
        resume: None,
    })
}

/// Whether two films hold the same per-pixel statistics, bit for bit.
pub fn same_bits(a: &Film, b: &Film) -> bool {
    a.pixels == b.pixels && a.splats == b.splats && a.weights == b.weights
}

/// `scenes/test/<name>.pbrt`.
pub fn test_scene(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/test")
        .join(format!("{name}.pbrt"))
}

/// `scenes/caustics/<name>.pbrt` (the caustic study's scenes).
pub fn caustic_scene(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/caustics")
        .join(format!("{name}.pbrt"))
}

/// The committed 32k-spp light-tracer reference of
/// `scenes/caustics/ring-point.pbrt` and the indices of its pixels where it
/// is a full estimate (lit, as `lumis compare --lit`: not where the ring or
/// its edge shows the camera).
pub fn ring_lit_reference() -> (lumis_render::image_io::RgbImage, Vec<usize>) {
    let path = caustic_scene("ring-point").with_file_name("ref/ring-point-lt.exr");
    let r = lumis_render::image_io::read_image(&path).expect("committed reference");
    let lit: Vec<usize> = (0..r.height)
        .flat_map(|y| (0..r.width).map(move |x| (x, y)))
        .filter(|&(x, y)| lumis_render::metrics::lit_interior(&r, x, y))
        .map(|(x, y)| (y * r.width + x) as usize)
        .collect();
    assert!(lit.len() > 10_000, "{} lit pixels", lit.len());
    (r, lit)
}

/// `scenes/caustics/ring-point.pbrt` (the silver ring's caustic of a
/// point light, 128 x 128) by `integrator`: the mean over seeds of each
/// render's mean over the pixels where the committed 32k-spp light-tracer
/// reference (`scenes/caustics/ref/ring-point-lt.exr`) is a full estimate
/// (lit, as `lumis compare --lit`: not where the ring or its edge shows),
/// with its standard error; and the reference's mean over the same
/// pixels.
pub fn ring_lit_means(
    integrator: &str,
    spp: u32,
    seeds: std::ops::Range<u64>,
) -> ((f64, f64), f64) {
    let (r, lit) = ring_lit_reference();
    let mean = |img: &[f32]| {
        let s: f64 = lit
            .iter()
            .map(|&i| (0..3).map(|c| img[3 * i + c] as f64).sum::<f64>())
            .sum();
        s / (3 * lit.len()) as f64
    };
    let mut ov = Overrides::default();
    ov.integrator(integrator);
    let l = lumis_render::load::load_path(&caustic_scene("ring-point"), &ov).unwrap();
    let v: Vec<f64> = seeds
        .map(|s| mean(&render_loaded(&l, spp, s, 0).film.mean_image()))
        .collect();
    (sample_mean_and_se(&v), mean(&r.data))
}

/// The spot light's focused caustic through the glass sphere of
/// `scenes/caustics/spot-glass.pbrt`: pixels 58..70 x 82..90 of 128 x 128.
pub const SPOT_CROP: [f32; 4] = [0.453125, 0.546875, 0.640625, 0.703125];

/// Mean squared difference of two channel-interleaved images over the
/// pixels `pixels` (all of them with `None`).
pub fn image_mse(img: &[f32], reference: &[f32], pixels: Option<&[usize]>) -> f64 {
    assert_eq!(img.len(), reference.len());
    let sq = |i: usize| (img[i] as f64 - reference[i] as f64).powi(2);
    match pixels {
        None => (0..img.len()).map(sq).sum::<f64>() / img.len() as f64,
        Some(p) => {
            let d: f64 = p.iter().flat_map(|&i| 3 * i..3 * i + 3).map(sq).sum();
            d / (3 * p.len()) as f64
        }
    }
}

/// The mean over pixels and channels of a committed reference image
/// (`tests/data/<name>`).
pub fn reference_mean(name: &str) -> f64 {
    let r = lumis_render::image_io::read_image(&test_data(name)).expect("committed reference");
    r.data.iter().map(|&v| v as f64).sum::<f64>() / r.data.len() as f64
}

/// `tests/data/<name>` (committed references).
pub fn test_data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// The caustic region of the 64x64 caustic test scenes (`caustic_sphere`,
/// `caustic_sphere_glossy`), as fractions x0, x1, y0, y1.
pub const CAUSTIC_CROP: [f32; 4] = [0.39, 0.62, 0.41, 0.53];

/// The committed `path` reference of a caustic test scene's region
/// (`tests/data/<name>_ref_{mean,var}.exr`): the region's mean over pixels
/// and channels, and its standard error.
pub fn caustic_reference(name: &str) -> (f64, f64) {
    let m = lumis_render::image_io::read_image(&test_data(&format!("{name}_ref_mean.exr")))
        .expect("committed reference");
    let v = lumis_render::image_io::read_image(&test_data(&format!("{name}_ref_var.exr")))
        .expect("committed reference variance");
    let n = (m.width * m.height) as f64;
    let mean = m.data.iter().map(|&x| x as f64).sum::<f64>() / (3.0 * n);
    let var = v.data.iter().map(|&x| x as f64).sum::<f64>() / (3.0 * n * n);
    (mean, var.sqrt())
}

/// Mean over pixels and channels of a render's image (splats included).
pub fn film_mean(l: &LoadedScene, spp: u32, seed: u64, threads: usize) -> f64 {
    let img = render_loaded(l, spp, seed, threads).film.mean_image();
    img.iter().map(|&v| v as f64).sum::<f64>() / img.len() as f64
}

/// Mean and standard error of the image mean over `seeds` independent
/// renders (for integrators whose pixels share paths: the spread over
/// seeds, not over pixels).
pub fn over_seeds(l: &LoadedScene, spp: u32, seeds: std::ops::Range<u64>) -> (f64, f64) {
    let v: Vec<f64> = seeds.map(|s| film_mean(l, spp, s, 0)).collect();
    sample_mean_and_se(&v)
}

/// `mean ± se` within 4.5 standard errors of `expected ± expected_se` (a
/// false alarm about once in 150k runs), with the test able to see a 1%
/// bias; an estimate without noise must be exact.
pub fn assert_close(label: &str, (mean, se): (f64, f64), expected: f64, expected_se: f64) {
    let se = (se * se + expected_se * expected_se).sqrt();
    if se == 0.0 {
        eprintln!("{label}: {mean:.6}, expected {expected:.6}");
        assert!((mean - expected).abs() < 1e-6 * expected, "{label}: {mean}");
        return;
    }
    let z = (mean - expected) / se;
    eprintln!("{label}: {mean:.5} ± {se:.5}, expected {expected:.5}, z {z:.2}");
    assert!(
        z.abs() < 4.5,
        "{label}: {mean} is {z:.1} standard errors from {expected}"
    );
    assert!(
        se < 0.01 * expected,
        "{label}: too noisy to see a 1% bias (se {se})"
    );
}

/// Bitterli's Cornell box (shared scene) at `res` x `res` by `integrator`
/// (seed 5); None, with a notice, where the shared scenes are absent.
pub fn cornell_box(integrator: &str, spp: u32, res: u32) -> Option<Vec<f32>> {
    let scene = shared_scene("bitterli-cornell-box/scene-v4.pbrt")?;
    let mut ov = Overrides::default();
    ov.resolution(res, res).integrator(integrator);
    let l = lumis_render::load::load_path(&scene, &ov).unwrap();
    Some(render_loaded(&l, spp, 5, 0).film.mean_image())
}

/// Per channel, the sum of image `a` over that of image `b`.
pub fn channel_ratios(a: &[f32], b: &[f32]) -> [f64; 3] {
    let sum = |img: &[f32], c: usize| {
        img.iter()
            .skip(c)
            .step_by(3)
            .map(|&v| v as f64)
            .sum::<f64>()
    };
    [0, 1, 2].map(|c| sum(a, c) / sum(b, c))
}

/// `integrator` renders the caustic test scene at 24x24 with the same bits
/// on one thread and on two.
pub fn assert_same_bits_on_one_and_two_threads(integrator: &str) {
    let l = lumis_render::load::load_path(&test_scene("caustic_sphere"), &{
        let mut ov = Overrides::default();
        ov.resolution(24, 24).integrator(integrator);
        ov
    })
    .unwrap();
    let bits = |threads| -> Vec<u32> {
        let img = render_loaded(&l, 4, 3, threads).film.mean_image();
        img.iter().map(|v| v.to_bits()).collect()
    };
    let one = bits(1);
    assert!(one.iter().any(|&b| b != 0), "nothing rendered");
    assert_eq!(one, bits(2));
}
