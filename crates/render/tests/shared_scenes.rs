//! Every scene in ../shared/scenes loads and renders at a tiny resolution
//! with `path` (what is not supported yet is a warning, never a failure).

mod support;

use lumis_render::load::{load_path, BuildOverrides};
use support::*;

const SCENES: &[&str] = &[
    "bitterli-cornell-box/scene-v4.pbrt",
    "bitterli-veach-mis/scene-v4.pbrt",
    "pbrt-v4-killeroos/killeroo-simple.pbrt",
    "pbrt-v4-killeroos/killeroo-gold.pbrt",
    "pbrt-v4-killeroos/killeroo-coated-gold.pbrt",
    "pbrt-v4-killeroos/killeroo-moving.pbrt",
    "pbrt-caustic-glass/pbrt-v4-w3ntao/caustic-glass-v4.pbrt",
];

#[test]
fn shared_scenes_load_and_render_tiny() {
    for rel in SCENES {
        let Some(path) = shared_scene(rel) else {
            return;
        };
        let ov = BuildOverrides {
            resolution: Some((16, 12)),
            spp: Some(1),
            integrator: Some("path".into()),
            max_depth: Some(3),
            ..Default::default()
        };
        let l = load_path(&path, &ov).unwrap_or_else(|e| panic!("{rel}: {e}"));
        let out = render_loaded(&l, 1, 0, 0);
        assert_eq!(out.bad_samples, 0, "{rel}: NaN/inf samples");
        let (mean, _) = mean_and_se(&out.film, None);
        eprintln!(
            "{rel}: {} warnings, {} lights, mean {mean:.4}",
            l.warnings.len(),
            l.scene.lights.len()
        );
        assert!(mean.is_finite());
        assert!(!l.scene.lights.is_empty(), "{rel}: no lights built");
    }
}
