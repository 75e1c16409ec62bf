//! End-to-end tests of the `lumis` binary: outputs, summary, and bad input.

use crate::common;

use common::*;
use std::path::Path;
use std::time::Duration;

#[test]
fn default_scene_writes_exr_and_png_and_a_summary() {
    let d = temp_dir("cli", "default");
    let o = lumis(&d, &["render", "--resolution", "24x24", "--spp", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(d.join("lumis.exr").exists() && d.join("lumis.png").exists());
    let e = stderr(&o);
    assert!(
        e.contains("2 spp") && e.contains("Mrays/s"),
        "summary line missing: {e}"
    );
    let img = lumis_render::image_io::read_image(&d.join("lumis.exr")).unwrap();
    assert_eq!((img.width, img.height), (24, 24));
    assert_eq!(img.meta("lumis:spp"), Some("2"));
    assert!(img.channel_means()[0] > 0.0);
}

#[test]
fn output_format_follows_extension_and_crop_selects_pixels() {
    let d = temp_dir("cli", "pfm");
    let o = lumis(
        &d,
        &[
            "render",
            "--resolution",
            "20x10",
            "--spp",
            "1",
            "--crop",
            "0,0.5,0,1",
            "-o",
            "out.pfm",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let img = lumis_render::image_io::read_image(&d.join("out.pfm")).unwrap();
    assert_eq!((img.width, img.height), (10, 10));
    let o = lumis(&d, &["render", "--spp", "1", "-o", "out.jpg"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("unsupported image extension"));
}

#[test]
fn time_budget_stops_the_render() {
    let d = temp_dir("cli", "time");
    let o = lumis(
        &d,
        &[
            "render",
            "--resolution",
            "16x16",
            "--time",
            "0.3",
            "-o",
            "t.exr",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let img = lumis_render::image_io::read_image(&d.join("t.exr")).unwrap();
    let spp: u32 = img.meta("lumis:spp").unwrap().parse().unwrap();
    assert!(spp >= 1);
}

#[test]
fn syntax_error_has_location_and_caret_and_writes_nothing() {
    let d = temp_dir("cli", "syntax");
    // A wrong value type, and an unclosed bracket.
    let cases = [
        ("type.pbrt", "Film \"rgb\"\nCamera \"perspective\" \"float fov\" [ 45 ]\nWorldBegin\nShape \"sphere\" \"float radius\" [ \"big\" ]\n", "type.pbrt:4:33"),
        ("bracket.pbrt", "Film \"rgb\"\nCamera \"perspective\" \"float fov\" [ 45 \nWorldBegin\n", "bracket.pbrt:2:34"),
    ];
    for (name, text, loc) in cases {
        std::fs::write(d.join(name), text).unwrap();
        let o = lumis(&d, &["render", name, "-o", "out.exr"]);
        assert_eq!(o.status.code(), Some(1));
        let e = stderr(&o);
        assert!(e.contains(loc), "no {loc} in {e}");
        assert!(e.contains('^'), "no caret in {e}");
        assert!(!e.contains("panicked"));
        assert!(!d.join("out.exr").exists());
    }
}

#[test]
fn missing_scene_and_missing_include_are_named() {
    let d = temp_dir("cli", "missing");
    let o = lumis(&d, &["render", "nope.pbrt"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("nope.pbrt"));
    std::fs::write(
        d.join("inc.pbrt"),
        "WorldBegin\nInclude \"geometry/absent.pbrt\"\n",
    )
    .unwrap();
    let o = lumis(&d, &["render", "inc.pbrt"]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("absent.pbrt") && e.contains("inc.pbrt:2:"),
        "{e}"
    );
    assert!(!d.join("lumis.exr").exists());
}

#[test]
fn unknown_parameter_is_a_located_warning_with_suggestion() {
    let d = temp_dir("cli", "unknown");
    let scene = "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\nCamera \"perspective\"\nWorldBegin\nLightSource \"point\" \"rgb I\" [ 1 1 1 ]\nMaterial \"diffuse\" \"rgb reflectanse\" [ 0.5 0.5 0.5 ]\nShape \"sphere\"\n";
    std::fs::write(d.join("warn.pbrt"), scene).unwrap();
    let o = lumis(&d, &["render", "warn.pbrt", "--spp", "1", "-o", "w.exr"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("warn.pbrt:5:") && e.contains("reflectanse") && e.contains("reflectance"),
        "{e}"
    );
}

#[test]
fn bad_arguments_are_refused() {
    let d = temp_dir("cli", "args");
    for args in [
        &["render", "--resolution", "0x5"][..],
        &["render", "--integrator", "nope", "--spp", "1"],
        &["render", "--time", "-1"],
    ] {
        let o = lumis(&d, args);
        assert!(!o.status.success(), "{args:?} should fail");
        assert!(!stderr(&o).contains("panicked"));
    }
}

/// `bdpt`'s flags come from its parameter table: `--strategy S,T` renders
/// one strategy, and a malformed one is an error located at the flag.
#[test]
fn bdpt_strategy_flag_renders_one_strategy_or_is_a_located_error() {
    let d = temp_dir("cli", "bdpt");
    let base = [
        "render",
        "--integrator",
        "bdpt",
        "--resolution",
        "16x16",
        "--spp",
        "2",
    ];
    let o = lumis(
        &d,
        &[
            &base[..],
            &["--strategy", "2,1", "--mis", "false", "-o", "s.exr"],
        ]
        .concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(d.join("s.exr").exists());
    let o = lumis(
        &d,
        &[&base[..], &["--strategy", "2", "-o", "t.exr"]].concat(),
    );
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        e.contains("--strategy:1:") && e.contains("two integers"),
        "{e}"
    );
    assert!(!d.join("t.exr").exists());
}

/// `--initial-radius` and `--shrink` are one flag each for the two
/// integrators that read them (`photon`, `vcm`): both render with them,
/// and a bad value is an error at the flag.
#[test]
fn shared_radius_flags_reach_photon_and_vcm() {
    let d = temp_dir("cli", "vcm");
    for integrator in ["vcm", "photon"] {
        let out = format!("{integrator}.exr");
        let o = lumis(
            &d,
            &[
                "render",
                "--integrator",
                integrator,
                "--resolution",
                "16x16",
                "--spp",
                "2",
                "--initial-radius",
                "0.05",
                "--shrink",
                "0.6",
                "-o",
                &out,
            ],
        );
        assert!(o.status.success(), "{integrator}: {}", stderr(&o));
        assert!(!stderr(&o).contains("unknown parameter"), "{}", stderr(&o));
        assert!(d.join(&out).exists());
    }
    let o = lumis(
        &d,
        &[
            "render",
            "--integrator",
            "vcm",
            "--resolution",
            "16x16",
            "--spp",
            "2",
            "--shrink",
            "2",
            "-o",
            "bad.exr",
        ],
    );
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("--shrink:1:") && e.contains("(0, 1]"), "{e}");
    assert!(!d.join("bad.exr").exists());
}

#[test]
fn interrupt_writes_the_image_so_far_with_its_sample_count() {
    let d = temp_dir("cli", "sigint");
    // Let a few passes finish, then SIGINT.
    let out = lumis_interrupted(
        &d,
        &[
            "render",
            "--integrator",
            "path",
            "--resolution",
            "16x16",
            "--spp",
            "1000000",
            "-o",
            "int.exr",
            "-q",
        ],
        Duration::from_millis(1500),
    );
    let e = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{e}");
    let img = lumis_render::image_io::read_image(&d.join("int.exr")).unwrap();
    let spp: u32 = img.meta("lumis:spp").unwrap().parse().unwrap();
    assert!(spp > 0 && spp < 1_000_000, "spp {spp}");
    assert!(img.data.iter().all(|v| v.is_finite()));
}

/// An interrupt during a long photon pass ends the render promptly (the
/// pass gives up between chunks of photons) with a 0-spp image, instead of
/// tracing the whole budget first.
#[test]
fn interrupt_during_the_photon_pass_stops_it() {
    let d = temp_dir("cli", "sigint-photons");
    let start = std::time::Instant::now();
    // 200M caustic photons: 40 s or more of tracing.
    let out = lumis_interrupted(
        &d,
        &[
            "render",
            "--resolution",
            "16x16",
            "--spp",
            "4",
            "--caustic-photons",
            "200000000",
            "-o",
            "int.exr",
            "-q",
        ],
        Duration::from_millis(1500),
    );
    let e = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{e}");
    let took = start.elapsed();
    assert!(took < Duration::from_secs(15), "took {took:?}");
    let img = lumis_render::image_io::read_image(&d.join("int.exr")).unwrap();
    assert_eq!(img.meta("lumis:spp"), Some("0"));
}

#[test]
fn compare_prints_metrics_and_refuses_mismatched_sizes() {
    use lumis_render::image_io::{write_image, RgbImage};
    let d = temp_dir("cli", "compare");
    write_image(
        &d.join("r.pfm"),
        &RgbImage::new(2, 1, vec![1.0, 1.0, 1.0, 0.0, 0.0, 0.0]),
        0.0,
    )
    .unwrap();
    write_image(
        &d.join("t.pfm"),
        &RgbImage::new(2, 1, vec![2.0, 1.0, 1.0, 0.0, 0.0, 0.5]),
        0.0,
    )
    .unwrap();
    write_image(&d.join("big.pfm"), &RgbImage::new(3, 1, vec![0.0; 9]), 0.0).unwrap();
    let o = lumis(&d, &["compare", "t.pfm", "r.pfm"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    let rmse: f64 = text
        .lines()
        .find(|l| l.starts_with("RMSE"))
        .unwrap()
        .split_whitespace()
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    assert!((rmse - (1.25f64 / 6.0).sqrt()).abs() < 1e-6, "{text}");
    let o = lumis(&d, &["compare", "t.pfm", "big.pfm"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("sizes differ"));
}

#[test]
fn photon_budget_beyond_memory_is_refused_naming_the_parameter() {
    let d = temp_dir("cli", "photonmem");
    let o = lumis(
        &d,
        &[
            "render",
            "--integrator",
            "photon",
            "--caustic-photons",
            "2000000000",
            "--spp",
            "1",
            "-o",
            "m.exr",
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("caustic-photons") && e.contains("GiB"), "{e}");
    assert!(!d.join("m.exr").exists());
}

fn exr_bits(p: &Path) -> (u32, Vec<u32>) {
    let img = lumis_render::image_io::read_image(p).unwrap();
    let spp = img.meta("lumis:spp").unwrap().parse().unwrap();
    (spp, img.data.iter().map(|v| v.to_bits()).collect())
}

#[test]
fn checkpoint_then_resume_equals_an_uninterrupted_render() {
    let d = temp_dir("cli", "resume");
    let common = [
        "render",
        "--integrator",
        "path",
        "--resolution",
        "48x32",
        "--spp",
        "200",
        "--seed",
        "3",
        "-q",
    ];
    let run = |extra: &[&str]| lumis(&d, &[&common[..], extra].concat());
    let o = run(&["-o", "full.exr"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A time budget stops the render early; the checkpoint keeps its state.
    let o = run(&["-o", "part.exr", "--time", "0.2", "--checkpoint", "ck"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (part_spp, _) = exr_bits(&d.join("part.exr"));
    assert!(part_spp < 200, "budget should stop early ({part_spp} spp)");
    // Resume from another folder: the saved command runs in its own folder.
    let o = lumis(
        &std::env::temp_dir(),
        &[
            "render",
            "--resume",
            d.join("ck").to_str().unwrap(),
            "--threads",
            "1",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("resuming"), "{}", stderr(&o));
    let (spp, resumed) = exr_bits(&d.join("part.exr"));
    let (full_spp, full) = exr_bits(&d.join("full.exr"));
    assert_eq!((spp, full_spp), (200, 200));
    assert!(
        resumed == full,
        "resumed image differs from the uninterrupted one"
    );
    // Another scene (here: the same text with one comment added) is refused.
    let text = format!("{}\n# edited\n", lumis_render::load::DEFAULT_SCENE);
    std::fs::write(d.join("edited.pbrt"), text).unwrap();
    let o = lumis(
        &d,
        &[
            &common[..],
            &["edited.pbrt", "--resume", "ck", "-o", "e.exr"],
        ]
        .concat(),
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("another scene"), "{}", stderr(&o));
    assert!(!d.join("e.exr").exists());
    // Not a checkpoint at all.
    let o = lumis(&d, &["render", "--resume", "full.exr"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("not a lumis checkpoint"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn interrupt_writes_a_checkpoint_that_resumes() {
    let d = temp_dir("cli", "sigint-ck");
    let out = lumis_interrupted(
        &d,
        &[
            "render",
            "--integrator",
            "path",
            "--resolution",
            "16x16",
            "--spp",
            "1000000",
            "-o",
            "int.exr",
            "-q",
            "--checkpoint",
            "ck",
            "--checkpoint-every",
            "1000",
        ],
        Duration::from_millis(1000),
    );
    assert_eq!(out.status.code(), Some(130), "{}", stderr(&out));
    let (spp, _) = exr_bits(&d.join("int.exr"));
    let ck = lumis_render::checkpoint::Checkpoint::load(&d.join("ck")).unwrap();
    assert_eq!(ck.state.spp_done, spp);
    let job = lumis_render::session::RenderJob::from_json(&ck.job).unwrap();
    assert_eq!(job.budget.spp, Some(1_000_000));
    assert!(ck.state.film.pixels.iter().all(|p| p.n == spp as u64));
}

#[test]
fn nan_samples_are_dropped_counted_and_located_in_summary_and_exr() {
    let d = temp_dir("cli", "nan");
    let o = lumis(
        &d,
        &[
            "render",
            "--integrator",
            "path",
            "--resolution",
            "12x8",
            "--spp",
            "4",
            "--inject-nan",
            "3,2,1",
            "-o",
            "n.exr",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("dropped 1 NaN/infinite samples (first at pixel 3,2, sample 1)"),
        "{}",
        stderr(&o)
    );
    let img = lumis_render::image_io::read_image(&d.join("n.exr")).unwrap();
    assert_eq!(img.meta("lumis:bad_samples"), Some("1"));
    assert_eq!(
        img.meta("lumis:first_bad_sample"),
        Some("pixel 3,2 sample 1")
    );
    assert!(img.data.iter().all(|v| v.is_finite()));
}

/// The number after `label ` on the stats line starting with `line`.
fn stat(text: &str, line: &str, label: &str) -> f64 {
    let l = text
        .lines()
        .find(|l| l.trim_start().starts_with(line))
        .unwrap_or_else(|| panic!("no `{line}` line in {text}"));
    let rest = &l[l
        .find(&format!("{label} "))
        .unwrap_or_else(|| panic!("no {label} in {l}"))
        + label.len()
        + 1..];
    rest.split([' ', ',', ';'])
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("bad number after {label} in {l}"))
}

/// `lumis render --integrator path --resolution 24x16 --spp 3 --stats`
/// with `extra` flags, in `d`: its stderr.
fn path_stats(d: &std::path::Path, extra: &[&str]) -> String {
    let mut args = vec!["render", "--integrator", "path", "--resolution", "24x16"];
    args.extend(["--spp", "3", "--stats", "-q", "-o", "s.exr"]);
    args.extend(extra);
    let o = lumis(d, &args);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    e
}

#[test]
fn stats_report_rays_photons_memory_and_phases() {
    let d = temp_dir("cli", "stats");
    let e = path_stats(&d, &["--filter-splat", "false"]);
    // One camera ray per sample; light sampling traces shadow rays.
    assert_eq!(stat(&e, "rays", "camera"), (24 * 16 * 3) as f64, "{e}");
    assert!(stat(&e, "rays", "shadow") > 0.0 && stat(&e, "rays", "indirect") > 0.0);
    assert_eq!(stat(&e, "rays", "photon"), 0.0);
    // Per pixel: a count and six 128-bit fixed-point sums (16-byte aligned).
    assert_eq!(stat(&e, "memory", "film"), (24 * 16 * 112) as f64 / 1024.0);
    // The default scene's filter splats (radius 1.5: a sample counts in
    // the pixels next to its own): its samples cover a border of one pixel
    // too, and each pixel keeps a weight.
    let e = path_stats(&d, &[]);
    assert_eq!(stat(&e, "rays", "camera"), (26 * 18 * 3) as f64, "{e}");
    assert_eq!(stat(&e, "memory", "film"), (24 * 16 * 128) as f64 / 1024.0);
    assert!(stat(&e, "memory", "BVH") > 0.0);
    for phase in ["parse", "build", "rendering", "writing"] {
        assert!(stat(&e, "time", phase) >= 0.0);
    }
    let o = lumis(
        &d,
        &[
            "render",
            "--integrator",
            "photon",
            "--resolution",
            "24x16",
            "--spp",
            "1",
            "--stats",
            "-v",
            "--photons",
            "4000",
            "--caustic-photons",
            "4000",
            "-o",
            "p.exr",
        ],
    );
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(stat(&e, "rays", "photon") >= 8000.0, "{e}");
    assert!(stat(&e, "rays", "gather") > 0.0, "{e}");
    assert!(stat(&e, "photons", "map") > 0.0, "{e}");
    assert!(stat(&e, "memory", "maps") > 0.0, "{e}");
    assert!(stat(&e, "time", "pass") > 0.0, "{e}");
    // -v: phase timings and settings before the render.
    assert!(
        e.contains("lumis: parsed in") && e.contains("triangles in"),
        "{e}"
    );
    assert!(
        e.contains("photon 24x16 (crop 24x16), 1 spp, seed 0"),
        "{e}"
    );
}

#[test]
fn checkpoint_of_an_edited_included_file_is_refused() {
    let d = temp_dir("cli", "resume-include");
    std::fs::write(
        d.join("main.pbrt"),
        "Film \"rgb\" \"integer xresolution\" [8] \"integer yresolution\" [8]\nLookAt 0 0 -3 0 0 0 0 1 0\nCamera \"perspective\"\nWorldBegin\nLightSource \"point\" \"rgb I\" [5 5 5] \"point3 from\" [0 0 -2]\nInclude \"geo.pbrt\"\n",
    )
    .unwrap();
    let geo = |x: &str| {
        format!("Shape \"trianglemesh\" \"point3 P\" [-1 -1 0 1 -1 0 {x} 1 0] \"integer indices\" [0 1 2]\n")
    };
    std::fs::write(d.join("geo.pbrt"), geo("0")).unwrap();
    let args = [
        "render",
        "main.pbrt",
        "--integrator",
        "path",
        "--spp",
        "2",
        "-q",
        "-o",
        "m.exr",
        "--checkpoint",
        "ck",
    ];
    let o = lumis(&d, &args);
    assert!(o.status.success(), "{}", stderr(&o));
    // Unchanged: resumes (nothing left to do, the image is written again).
    let o = lumis(&d, &[&args[..], &["--resume", "ck"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    // One vertex of the included mesh moved: refused.
    std::fs::write(d.join("geo.pbrt"), geo("0.5")).unwrap();
    let o = lumis(&d, &["render", "--resume", "ck"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("another scene"), "{}", stderr(&o));
}

#[test]
fn a_time_only_render_resumes_with_a_new_budget() {
    let d = temp_dir("cli", "resume-time");
    let base = [
        "render",
        "--integrator",
        "path",
        "--resolution",
        "16x16",
        "-q",
        "-o",
        "t.exr",
    ];
    let o = lumis(
        &d,
        &[&base[..], &["--time", "0.3", "--checkpoint", "ck"]].concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let (first, _) = exr_bits(&d.join("t.exr"));
    let ck = lumis_render::checkpoint::Checkpoint::load(&d.join("ck")).unwrap();
    let job = lumis_render::session::RenderJob::from_json(&ck.job).unwrap();
    assert_eq!((job.budget.spp, ck.state.spp_done), (None, first));
    // Without a budget there is no end: refused with the way out.
    let o = lumis(&d, &["render", "--resume", "ck"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("give --time"), "{}", stderr(&o));
    let o = lumis(&d, &["render", "--resume", "ck", "--time", "0.3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (more, _) = exr_bits(&d.join("t.exr"));
    assert!(more > first, "{first} -> {more}");
}
