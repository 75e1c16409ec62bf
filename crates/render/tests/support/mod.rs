//! Shared helpers for render tests: load scene text, render, summarise.
#![allow(dead_code)]

pub mod envmap;

use lumis_render::film::Film;
use lumis_render::integrator::{render, RenderOutcome, RenderSettings};
use lumis_render::load::{load_text, LoadedScene, Overrides};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

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

/// Mean over all pixels and channels, and its standard error estimated from
/// the spread of per-pixel means (pixels are independent estimates).
pub fn mean_and_se(film: &Film, channel: Option<usize>) -> (f64, f64) {
    let vals: Vec<f64> = film
        .pixels
        .iter()
        .map(|p| match channel {
            Some(c) => p.mean[c],
            None => (p.mean[0] + p.mean[1] + p.mean[2]) / 3.0,
        })
        .collect();
    let n = vals.len() as f64;
    let mean = vals.iter().sum::<f64>() / n;
    let var = vals.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
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
