//! Every scene in ../shared/scenes loads and renders at a tiny resolution
//! with `path`, and warns about nothing the scene-loading issue says must
//! work: every warning must be one of the explained exceptions below.

use crate::common;

use common::*;
use lumis_render::load::{load_path, Overrides};

const SCENES: &[&str] = &[
    "bitterli-cornell-box/scene-v4.pbrt",
    "bitterli-cornell-box/pbrt/scene-v4.gonsolo-modified.pbrt",
    "bitterli-veach-mis/scene-v4.pbrt",
    "pbrt-v4-killeroos/killeroo-simple.pbrt",
    "pbrt-v4-killeroos/killeroo-gold.pbrt",
    "pbrt-v4-killeroos/killeroo-coated-gold.pbrt",
    "pbrt-v4-killeroos/killeroo-moving.pbrt",
    "pbrt-caustic-glass/pbrt-v4-w3ntao/caustic-glass-v4.pbrt",
    "pbrt-caustic-glass/pbrt-v3/f16-9a.pbrt",
    "pbrt-caustic-glass/pbrt-v3/f16-9b.pbrt",
    "pbrt-caustic-glass/pbrt-v3/f16-9c.pbrt",
    "pbrt-caustic-glass/pbrt-v3/f16-11a.pbrt",
    "pbrt-caustic-glass/pbrt-v3/f16-11b.pbrt",
    "pbrt-caustic-glass/pbrt-v3/glass.pbrt",
];

/// Files that are only `Include`d by the scenes above.
const INCLUDED: &[&str] = &[
    "pbrt-v4-killeroos/geometry/killeroo.pbrt",
    "pbrt-v4-killeroos/geometry/killeroo3.pbrt",
];

/// Warnings these scenes may give, and why each is not a failure.
const EXPECTED: &[(&str, &str)] = &[
    // Outside the scene-loading issue: other samplers and integrators, motion blur.
    (
        "sampler `halton` is not available",
        "halton is not implemented",
    ),
    (
        "integrator `sppm` is not available; using `photon`",
        "the SPPM scenes render with lumis' photon method",
    ),
    (
        "`Accelerator` is ignored",
        "lumis always builds its own BVH (or Embree's)",
    ),
    ("motion blur is not supported", "no motion blur"),
    // pbrt-v4's own --upgrade reports these losses too.
    (
        "`Ks` is dropped converting",
        "pbrt-v4 --upgrade warns the same",
    ),
    (
        "has no \"numiterations\"",
        "pbrt-v4 --upgrade warns the same",
    ),
];

#[test]
fn shared_scenes_load_and_render_tiny() {
    for rel in SCENES {
        let Some(path) = shared_scene(rel) else {
            return;
        };
        let mut ov = Overrides::default();
        ov.resolution(16, 12).spp(1).integrator("path").max_depth(3);
        let l = load_path(&path, &ov).unwrap_or_else(|e| panic!("{rel}: {e}"));
        let out = render_loaded(&l, 1, 0, 0);
        assert_eq!(out.bad_samples, 0, "{rel}: NaN/inf samples");
        let mean = image_mean(&out.film, None);
        eprintln!(
            "{rel}: {} warnings, {} lights, mean {mean:.4}",
            l.warnings.len(),
            l.scene.lights.len()
        );
        for w in &l.warnings {
            eprintln!("  {}", w.message);
            assert!(
                EXPECTED.iter().any(|(m, _)| w.message.contains(m)),
                "{rel}: unexpected warning:\n{w}"
            );
        }
        assert!(mean.is_finite());
        assert!(!l.scene.lights.is_empty(), "{rel}: no lights built");
    }
}

/// No scene in ../shared/scenes escapes the test above: every pbrt file is
/// rendered or included by one that is.
#[test]
fn every_shared_scene_is_listed() {
    let Some(root) = shared_scene("") else {
        return;
    };
    fn walk(dir: &std::path::Path, root: &std::path::Path, out: &mut Vec<String>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, root, out);
            } else if p.to_string_lossy().ends_with(".pbrt")
                || p.to_string_lossy().ends_with(".pbrt.gz")
            {
                out.push(p.strip_prefix(root).unwrap().to_string_lossy().into_owned());
            }
        }
    }
    let mut files = Vec::new();
    walk(&root, &root, &mut files);
    assert!(files.len() >= SCENES.len());
    for f in files {
        assert!(
            SCENES.contains(&f.as_str()) || INCLUDED.contains(&f.as_str()),
            "{f} is in ../shared/scenes but not in SCENES (or INCLUDED)"
        );
    }
}
