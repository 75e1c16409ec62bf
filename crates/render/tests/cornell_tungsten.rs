//! Bitterli's Cornell box and Veach's MIS scene (pbrt-v4 files) against
//! Tungsten's converged renders.

mod support;

use lumis_render::image_io::read_image;
use lumis_render::load::{load_path, BuildOverrides};
use support::*;

const BLOCK: u32 = 8;

#[test]
fn cornell_box_matches_tungsten() {
    matches_tungsten(
        "bitterli-cornell-box/scene-v4.pbrt",
        "bitterli-cornell-box/tungsten/TungstenRender.exr",
        (64, 64),
        256,
    );
}

/// Open (issue 3): at 80x45 and 256 spp lumis is 62% brighter than Tungsten
/// in the red channel (1.092 vs 0.673); not yet explained (the scene is only
/// diffuse, rough conductors and spherical area lights).
#[test]
#[ignore = "open: lumis is 62% brighter than Tungsten's veach-mis render"]
fn veach_mis_matches_tungsten() {
    matches_tungsten(
        "bitterli-veach-mis/scene-v4.pbrt",
        "bitterli-veach-mis/TungstenRender.exr",
        (80, 45),
        256,
    );
}

/// Renders `scene` at `res` and compares it with Tungsten's render
/// box-downsampled to `res`: channel means within 2% and 8x8-block errors.
fn matches_tungsten(scene: &str, reference: &str, res: (u32, u32), spp: u32) {
    let (Some(scene), Some(reference)) = (shared_scene(scene), shared_scene(reference)) else {
        return;
    };
    let (rx, ry) = res;
    let ov = BuildOverrides {
        resolution: Some(res),
        ..Default::default()
    };
    let l = load_path(&scene, &ov).unwrap_or_else(|e| panic!("{e}"));
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
        let ours: f64 = out.film.pixels.iter().map(|p| p.mean[c]).sum::<f64>() / n as f64;
        let theirs: f64 = refd.iter().map(|p| p[c]).sum::<f64>() / n as f64;
        let rel = ours / theirs - 1.0;
        eprintln!(
            "channel {c}: lumis {ours:.5} tungsten {theirs:.5} ({:+.2}%)",
            rel * 100.0
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
                    a += (p.mean[0] + p.mean[1] + p.mean[2]) / 3.0;
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
