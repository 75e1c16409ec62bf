//! pbrt-v3 files load through pbrt-v4's upgrade rules: the pbrt-v3 and
//! pbrt-v4 versions of the pbrt book's caustic-glass scene give the same
//! geometry and the same spot light.

use crate::common;

use common::*;
use lumis_render::light::Light;
use lumis_render::load::{load_path, LoadedScene, Overrides};

fn triangles(l: &LoadedScene) -> usize {
    l.scene.world.prims.len()
}

#[test]
fn caustic_glass_v3_and_v4_agree() {
    let (Some(v3), Some(v4)) = (
        shared_scene("pbrt-caustic-glass/pbrt-v3/f16-9a.pbrt"),
        shared_scene("pbrt-caustic-glass/pbrt-v4-w3ntao/caustic-glass-v4.pbrt"),
    ) else {
        return;
    };
    let ov = Overrides::default();
    let a = load_path(&v3, &ov).unwrap_or_else(|e| panic!("{e}"));
    let b = load_path(&v4, &ov).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(triangles(&a), 88_064 + 2);
    assert_eq!(triangles(&a), triangles(&b));
    let (ba, bb) = (a.scene.bounds, b.scene.bounds);
    assert!(
        (ba.min - bb.min).abs().max_element() < 1e-5,
        "{ba:?} {bb:?}"
    );
    assert!(
        (ba.max - bb.max).abs().max_element() < 1e-5,
        "{ba:?} {bb:?}"
    );
    // Film "image" with "scale" 1.5 became Film "rgb" with iso 150.
    assert_eq!(a.options.resolution, b.options.resolution);
    assert_eq!(a.options.imaging_scale, 1.5);
    assert_eq!(a.options.imaging_scale, b.options.imaging_scale);
    // The spot light: pbrt-v3's `blackbody I [5500 125]` and pbrt-v4's
    // `blackbody I 5500` + `scale 125` carry the same power. (The v4
    // conversion leaves out the v3 file's dim infinite light.)
    let spot = |l: &LoadedScene| {
        let s: Vec<_> = l
            .scene
            .lights
            .iter()
            .filter(|x| matches!(x, Light::Spot(_)))
            .map(|x| x.power(&l.scene.shapes))
            .collect();
        assert_eq!(s.len(), 1);
        s[0]
    };
    let (pa, pb) = (spot(&a), spot(&b));
    assert!(pa.luminance() > 0.0);
    for c in 0..3 {
        assert!((pa[c] / pb[c] - 1.0).abs() < 1e-5, "{pa:?} vs {pb:?}");
    }
    let infinite = a.scene.lights.iter().filter(|l| l.is_infinite()).count();
    assert_eq!(infinite, 1, "the v3 file's `color L` infinite light");
    // Only the upgrade's own report remains: uber's non-zero Ks is dropped
    // converting to coateddiffuse (pbrt-v4's --upgrade warns the same).
    let msgs: Vec<String> = a.warnings.iter().map(|w| w.to_string()).collect();
    eprintln!("{}", msgs.join("\n"));
    assert!(msgs.iter().any(|m| m.contains("`Ks` is dropped")));
}
