//! A splatting pixel filter (the default for filters wider than a pixel;
//! `PixelFilter ... "bool splat" false` samples the filter instead): each
//! sample weighted into every pixel the filter reaches. A constant image
//! comes out exact; thread counts and crop windows do not change a pixel's
//! bits (the window's border is sampled as a larger window would); and the
//! image agrees with the filter's importance sampling in expectation.

use crate::common::{load, render_loaded, same_bits, sample_mean_and_se};
use lumis_render::film::Film;
use lumis_render::load::Overrides;

/// A diffuse sphere and a mirror sphere under a sky with a bright patch, a
/// Gaussian filter of radius 2 that splats, `res` x `res`.
fn scene(res: u32, splat: bool) -> String {
    format!(
        r#"Integrator "path" "integer maxdepth" [ 4 ]
Sampler "independent" "integer pixelsamples" [ 4 ]
PixelFilter "gaussian" "float xradius" [ 2 ] "float yradius" [ 2 ] "bool splat" [ {splat} ]
Film "rgb" "integer xresolution" [ {res} ] "integer yresolution" [ {res} ]
LookAt 0 0.3 4  0 0 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
WorldBegin
LightSource "infinite" "rgb L" [ 0.3 0.3 0.3 ]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 6 5 4 ]
  Translate -0.9 1.1 0
  Shape "sphere" "float radius" [ 0.35 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.7 0.4 0.2 ]
Translate 0.3 -0.2 0
Shape "sphere" "float radius" [ 0.8 ]
"#
    )
}

#[test]
fn a_constant_image_comes_out_exact_to_its_edges() {
    // Only a uniform sky: every pixel's weighted sum over its weights is
    // the sky's radiance, however few and wherever the samples.
    let text = r#"Integrator "path"
PixelFilter "gaussian" "float xradius" [ 2 ] "float yradius" [ 2 ] "bool splat" [ true ]
Film "rgb" "integer xresolution" [ 20 ] "integer yresolution" [ 13 ]
Camera "perspective" "float fov" [ 50 ]
WorldBegin
LightSource "infinite" "rgb L" [ 0.7 0.7 0.7 ]
"#;
    let l = load(text, &Overrides::default());
    assert!(l.options.filter.splat);
    let out = render_loaded(&l, 1, 3, 2);
    assert_eq!(out.film.weights.len(), out.film.pixels.len());
    for (i, v) in out.film.mean_image().iter().enumerate() {
        assert!((v - 0.7).abs() < 1e-5, "value {i}: {v}");
    }
}

/// The film of `text` rendered with `ov`, 2 spp.
fn film(text: &str, ov: &Overrides, threads: usize) -> Film {
    render_loaded(&load(text, ov), 2, 11, threads).film
}

#[test]
fn threads_and_crop_windows_keep_a_pixels_bits() {
    let text = scene(24, true);
    let whole = film(&text, &Overrides::default(), 1);
    assert!(same_bits(&whole, &film(&text, &Overrides::default(), 2)));
    // A crop window's pixels are the whole film's there: its border is
    // sampled (without it, its edge pixels would lose their outer samples).
    let mut ov = Overrides::default();
    ov.crop_from([0.25, 0.75, 0.5, 1.0], "test");
    let crop = film(&text, &ov, 2);
    let b = crop.bounds;
    assert_eq!((b.x0, b.x1, b.y0, b.y1), (6, 18, 12, 24));
    for y in b.y0..b.y1 {
        for x in b.x0..b.x1 {
            let c = ((y - b.y0) * b.width() + (x - b.x0)) as usize;
            let w = (y * 24 + x) as usize;
            assert_eq!(crop.pixels[c], whole.pixels[w], "pixel ({x}, {y})");
            assert_eq!(crop.weights[c], whole.weights[w], "weight ({x}, {y})");
        }
    }
}

#[test]
fn splatting_agrees_with_sampling_the_filter() {
    // 4x4-pixel blocks of a 16x16 image, over 8 seeds each way: the two
    // reconstructions estimate the same filtered image. The blocks along
    // the spheres' edges show a shifted or mis-weighted filter.
    let blocks = |splat: bool| -> Vec<Vec<f64>> {
        let l = load(&scene(16, splat), &Overrides::default());
        (0..6)
            .map(|seed| {
                let img = render_loaded(&l, 64, 100 + seed, 2).film.mean_image();
                (0..16)
                    .map(|b| {
                        let (bx, by) = (b % 4 * 4, b / 4 * 4);
                        let mut s = 0.0f64;
                        for y in by..by + 4 {
                            for x in bx..bx + 4 {
                                let i = 3 * (y * 16 + x);
                                s += (img[i] + img[i + 1] + img[i + 2]) as f64;
                            }
                        }
                        s / 48.0
                    })
                    .collect()
            })
            .collect()
    };
    let (fis, splat) = (blocks(false), blocks(true));
    let mut worst = 0.0f64;
    for b in 0..16 {
        let (mf, sf) = sample_mean_and_se(&fis.iter().map(|r| r[b]).collect::<Vec<_>>());
        let (ms, ss) = sample_mean_and_se(&splat.iter().map(|r| r[b]).collect::<Vec<_>>());
        // Rounding (the ratio of fixed-point sums) is far below 1e-5.
        let z = (mf - ms) / (sf * sf + ss * ss + (1e-5 * mf).powi(2)).sqrt();
        worst = worst.max(z.abs());
        assert!(
            z.abs() < 4.5,
            "block {b}: {mf} ± {sf} against {ms} ± {ss} (z {z})"
        );
    }
    // The blocks differ by noise, not by nothing.
    assert!(worst > 0.05, "{worst}");
    // And the splatted image is less noisy: its blocks' spread over seeds
    // is below the sampled filter's on most blocks that have any (those
    // that see only the sky have none either way).
    let spread = |r: &Vec<Vec<f64>>, b: usize| {
        sample_mean_and_se(&r.iter().map(|v| v[b]).collect::<Vec<_>>()).1
    };
    let noisy: Vec<usize> = (0..16).filter(|&b| spread(&fis, b) > 1e-6).collect();
    let calmer = noisy
        .iter()
        .filter(|&&b| spread(&splat, b) < spread(&fis, b))
        .count();
    assert!(
        noisy.len() >= 8 && 4 * calmer >= 3 * noisy.len(),
        "{calmer} of {} calmer",
        noisy.len()
    );
}

#[test]
fn a_splatting_filter_wider_than_its_limit_is_refused_where_given() {
    let text = "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n\
                PixelFilter \"gaussian\" \"float xradius\" [ 40 ] \"bool splat\" true\n\
                Camera \"perspective\"\nWorldBegin\n";
    let e = lumis_render::load::load_text(
        text,
        "s.pbrt",
        std::path::Path::new("."),
        &Overrides::default(),
    )
    .err()
    .expect("refused")
    .to_string();
    assert!(e.contains("s.pbrt:2:"), "{e}");
    assert!(
        e.contains("radius must be at most 16 pixels, not 40"),
        "{e}"
    );
    // Without splatting the same radius is fine.
    let plain = text.replace(" \"bool splat\" true", "");
    load(&plain, &Overrides::default());
}

#[test]
fn filters_wider_than_a_pixel_splat_unless_their_file_says_not() {
    let splats = |filter: &str, ov: &Overrides| -> bool {
        let text = format!(
            "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n\
             {filter}\nCamera \"perspective\"\nWorldBegin\n"
        );
        load(&text, ov).options.filter.splat
    };
    let none = Overrides::default();
    // pbrt-v4's default filter (a Gaussian of radius 1.5) and the others.
    assert!(splats("", &none));
    assert!(splats("PixelFilter \"gaussian\"", &none));
    assert!(splats(
        "PixelFilter \"triangle\" \"float xradius\" [ 1 ]",
        &none
    ));
    assert!(splats("PixelFilter \"box\" \"float xradius\" [ 1 ]", &none));
    // A box of one pixel gives the same image either way: sampled.
    assert!(!splats("PixelFilter \"box\"", &none));
    // Wider than a splat may reach: sampled, not refused.
    assert!(!splats(
        "PixelFilter \"gaussian\" \"float xradius\" [ 40 ]",
        &none
    ));
    // The file's word, and the command line's over it.
    assert!(!splats(
        "PixelFilter \"gaussian\" \"bool splat\" false",
        &none
    ));
    let mut sampled = Overrides::default();
    sampled.filter_splat(false);
    assert!(!splats("", &sampled));
    assert!(!splats("PixelFilter \"triangle\"", &sampled));
}

#[test]
fn every_integrator_renders_splatted_alike_on_any_thread_count() {
    // Samples beyond the film reach the integrators as their nearest film
    // pixel's: `vcm` keys its light subpaths by pixel, the test pass of
    // `splats.rs` computes with the coordinates.
    for integrator in ["path", "direct", "photon", "lighttracer", "bdpt", "vcm"] {
        let mut ov = Overrides::default();
        ov.integrator(integrator);
        if integrator == "photon" {
            ov.integrator_param("integer photons", "5000")
                .integrator_param("integer causticphotons", "5000");
        }
        let text = scene(10, true);
        let (a, b) = (film(&text, &ov, 1), film(&text, &ov, 2));
        assert!(same_bits(&a, &b), "{integrator}");
        assert!(
            a.mean_image().iter().all(|v| v.is_finite() && *v >= 0.0),
            "{integrator}"
        );
        assert!(a.mean_image().iter().any(|v| *v > 0.0), "{integrator}");
    }
}
