//! The render session through the binary: outputs checked before any time
//! is spent, `--resume` honouring `-o` and refusing flags it would drop,
//! and command-line parameters read (and reported) like the file's.

use crate::common;

use common::*;
use std::time::Instant;

#[test]
fn an_unwritable_output_is_an_error_before_rendering() {
    let d = temp_dir("session", "unwritable");
    let t = Instant::now();
    // 10^6 spp of 64x64 would take minutes: the error must come first.
    let o = lumis(
        &d,
        &[
            "render",
            "--resolution",
            "64x64",
            "--spp",
            "1000000",
            "-o",
            "/no/such/dir/x.exr",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("/no/such/dir"), "{}", stderr(&o));
    assert!(t.elapsed().as_secs() < 60, "rendered before failing");
}

#[test]
fn resume_honours_o_and_refuses_other_render_flags() {
    let d = temp_dir("session", "resume-o");
    let args = [
        "render",
        "--integrator",
        "path",
        "--resolution",
        "16x12",
        "--spp",
        "3",
        "--seed",
        "2",
        "-q",
        "-o",
        "a.exr",
        "--checkpoint",
        "ck",
    ];
    let o = lumis(&d, &args);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = lumis(&d, &["render", "--resume", "ck", "-o", "b.pfm"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let a = lumis_render::image_io::read_image(&d.join("a.exr")).unwrap();
    let b = lumis_render::image_io::read_image(&d.join("b.pfm")).unwrap();
    assert_eq!(a.data, b.data, "the resumed image, written where -o says");
    let o = lumis(&d, &["render", "--resume", "ck", "--spp", "9"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("only -o"), "{}", stderr(&o));
}

#[test]
fn command_line_parameters_are_located_and_reported_like_the_files() {
    let d = temp_dir("session", "params");
    let o = lumis(
        &d,
        &[
            "render",
            "--resolution",
            "8x8",
            "--spp",
            "1",
            "-o",
            "x.pfm",
            "--integrator",
            "photon",
            "--caustics",
            "sideways",
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("--caustics:1:") && e.contains("unknown caustics mode `sideways`"),
        "{e}"
    );
    // A photon parameter with a path tracer: the unused-parameter warning, at the flag.
    let o = lumis(
        &d,
        &[
            "render",
            "--resolution",
            "8x8",
            "--spp",
            "1",
            "-o",
            "x.pfm",
            "--integrator",
            "path",
            "--photons",
            "1000",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--photons:1:1: warning: unknown parameter `photons`"),
        "{}",
        stderr(&o)
    );
    // A progressive-only parameter without the progressive mode: said, not dropped.
    let o = lumis(
        &d,
        &[
            "render",
            "--resolution",
            "8x8",
            "--spp",
            "1",
            "-o",
            "x.pfm",
            "--integrator",
            "photon",
            "--photons",
            "1000",
            "--caustic-photons",
            "1000",
            "--progressive",
            "false",
            "--iteration-spp",
            "4",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("`iterationspp` has no effect with"),
        "{}",
        stderr(&o)
    );
    let o = lumis(&d, &["render", "--integrator", "pathh", "-o", "x.pfm"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("unknown integrator `pathh`"),
        "{}",
        stderr(&o)
    );
}
