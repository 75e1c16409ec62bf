//! Bitterli's Cornell box and Veach's MIS scene (pbrt-v4 files) against
//! Tungsten's converged renders.

use crate::common;

use common::*;
use lumis_render::image_io::read_image;
use lumis_render::load::{load_path, Overrides};

const BLOCK: u32 = 8;

#[test]
fn cornell_box_matches_tungsten() {
    let Some(scene) = shared_scene("bitterli-cornell-box/scene-v4.pbrt") else {
        return;
    };
    matches_tungsten(
        &scene,
        Overrides::default(),
        "bitterli-cornell-box/tungsten/TungstenRender.exr",
        (64, 64),
        256,
    );
}

/// Veach's MIS scene, as Tungsten rendered it. Bitterli's pbrt-v4 file
/// departs from the Tungsten scene behind the reference in three ways, each
/// visible in Bitterli's Mitsuba export of the same scene (plates
/// `roughconductor` with `distribution beckmann` and `specularReflectance
/// 0.3`) and each measured here (1280x720, lumis against the reference):
/// - the plates' distribution: pbrt-v4 has only Trowbridge-Reitz, whose
///   power-law tails light the gaps between the Glossy plate's highlights
///   (0.12-0.27 there against Tungsten's 2e-6);
/// - the plates' 0.3 reflectance factor, which pbrt-v4's conductor lacks:
///   every plate pixel was 3.33 times Tungsten's;
/// - the depth: the reference is direct light only (Veach's figure), not the
///   file's `maxdepth 3`: at `maxdepth` 1 the walls agree within 0.1%, at 2
///   and 3 their corners are 7-10% brighter than Tungsten's.
///
/// Together they made lumis 62% brighter in red. The test restores the
/// three (Beckmann through lumis' `"string distribution"` extension, the 0.3
/// as pbrt-v4's `mix` of each plate with black at `amount` 0.3, `maxdepth`
/// 1 as an override); everything else is the shared file.
///
/// Bound: the 2% on channel means. Measured at 80x45: -0.1% to -0.3%
/// at 4096 spp over three seeds; 2048 spp (used here) spreads -0.3% to +0.7%
/// over four seeds and 256 spp -2.6% to +1.5%: a quarter of the image's
/// mean is the 0.05-radius light seen directly (L = 3040 on ~50 of 1280x720
/// pixels), whose coverage noise needs the samples.
#[test]
fn veach_mis_matches_tungsten() {
    let Some(scene) = shared_scene("bitterli-veach-mis/scene-v4.pbrt") else {
        return;
    };
    let mut text = std::fs::read_to_string(&scene).unwrap();
    let plates = ["Smooth", "Glossy", "Rough", "SuperRough"];
    for n in plates {
        let def = format!("MakeNamedMaterial \"{n}\"\n    \"string type\" [ \"conductor\" ]");
        assert_eq!(text.matches(&def).count(), 1, "plate material {n}");
        text = text.replace(
            &def,
            &format!(
                "MakeNamedMaterial \"{n}-metal\"\n    \"string type\" [ \"conductor\" ]\n    \
                 \"string distribution\" [ \"beckmann\" ]"
            ),
        );
    }
    // The mixes go after the last plate metal, before the first plate.
    let first_use = text.find("NamedMaterial \"Smooth\"\nShape").unwrap();
    let mut mixes = String::from(
        "MakeNamedMaterial \"lumis-black\" \"string type\" [ \"diffuse\" ] \"rgb reflectance\" [ 0 0 0 ]\n",
    );
    for n in plates {
        mixes += &format!(
            "MakeNamedMaterial \"{n}\" \"string type\" [ \"mix\" ] \
             \"string materials\" [ \"lumis-black\" \"{n}-metal\" ] \"float amount\" [ 0.3 ]\n"
        );
    }
    text.insert_str(first_use, &mixes);
    let dir = std::env::temp_dir().join(format!("lumis-veach-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene-v4-as-tungsten.pbrt");
    std::fs::write(&path, text).unwrap();
    let mut ov = Overrides::default();
    ov.max_depth(1);
    matches_tungsten(
        &path,
        ov,
        "bitterli-veach-mis/TungstenRender.exr",
        (80, 45),
        2048,
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Renders `scene` at `res` and compares it with Tungsten's render
/// box-downsampled to `res`: channel means within 2% and 8x8-block errors.
fn matches_tungsten(
    scene: &std::path::Path,
    ov: Overrides,
    reference: &str,
    res: (u32, u32),
    spp: u32,
) {
    let Some(reference) = shared_scene(reference) else {
        return;
    };
    let (rx, ry) = res;
    let mut ov = ov;
    ov.resolution(res.0, res.1);
    // One pixel per sample: the block noise below adds pixels' own
    // variances as independent, which a splatting filter's are not.
    ov.filter_splat(false);
    let l = load_path(scene, &ov).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        l.warnings
            .iter()
            .all(|w| !w.message.contains("not supported")),
        "unexpected warnings: {:?}",
        l.warnings
    );
    let out = render_loaded(&l, spp, 1, 0);
    let r = read_image(&reference).unwrap();
    assert_eq!(r.width % rx, 0);
    let f = (r.width / rx) as usize;
    let n = (rx * ry) as usize;
    // Box-downsample the reference to our resolution.
    let mut refd = vec![[0f64; 3]; n];
    for y in 0..r.height as usize {
        if y / f >= ry as usize {
            break;
        }
        for x in 0..r.width as usize {
            let p = r.pixel(x as u32, y as u32);
            let d = &mut refd[(y / f) * rx as usize + x / f];
            for c in 0..3 {
                d[c] += p[c] as f64 / (f * f) as f64;
            }
        }
    }
    // 1. Mean per channel within 2%.
    for c in 0..3 {
        // With our Monte Carlo standard error of the image mean.
        let (ours, se) = region_mean_and_se(&out.film, Some(c));
        let theirs: f64 = refd.iter().map(|p| p[c]).sum::<f64>() / n as f64;
        let rel = ours / theirs - 1.0;
        eprintln!(
            "channel {c}: lumis {ours:.5} tungsten {theirs:.5} ({:+.2}%, independent-sample standard error {:.2}%, an overestimate for sobol)",
            rel * 100.0,
            se / theirs * 100.0
        );
        assert!(
            rel.abs() < 0.02,
            "channel {c} mean differs by {:.2}%",
            rel * 100.0
        );
    }
    // 2. Block RMSE: 8x8-pixel blocks, relative error of the block mean (luminance-like average).
    let (nbx, nby) = ((rx / BLOCK) as usize, (ry / BLOCK) as usize);
    let (mut sq, mut noise_sq) = (0.0f64, 0.0f64);
    for by in 0..nby {
        for bx in 0..nbx {
            let (mut a, mut b, mut var) = (0.0f64, 0.0f64, 0.0f64);
            for y in by * BLOCK as usize..(by + 1) * BLOCK as usize {
                for x in bx * BLOCK as usize..(bx + 1) * BLOCK as usize {
                    let i = y * rx as usize + x;
                    let p = &out.film.pixels[i];
                    a += p.mean().iter().sum::<f64>() / 3.0;
                    b += (refd[i][0] + refd[i][1] + refd[i][2]) / 3.0;
                    let v = p.variance_of_mean();
                    var += (v.r + v.g + v.b) as f64 / 9.0;
                }
            }
            let e = (a - b) / b.max(1e-3);
            sq += e * e;
            noise_sq += var / (b * b).max(1e-6);
        }
    }
    let rmse = (sq / (nbx * nby) as f64).sqrt();
    let noise = (noise_sq / (nbx * nby) as f64).sqrt();
    eprintln!("block relative RMSE {rmse:.4} (our noise alone {noise:.4})");
    // Bound: three times our Monte Carlo noise plus 1.5% systematic per block.
    // Tungsten's render is converged but made with its own filter (and 1024^2
    // pixels box-averaged here), so block means may differ slightly at edges;
    // measured 1.3% RMSE with 0.8% of it noise. A wrong camera, flipped image or
    // mis-oriented light gives block errors of 20% and more.
    assert!(
        rmse < 0.015 + 3.0 * noise,
        "block RMSE {rmse:.4} too large (noise {noise:.4})"
    );
}
