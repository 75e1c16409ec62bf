//! End-to-end: `render --passes A..B --partial FILE` and `merge`. Parts
//! rendered on different thread counts, one of them interrupted and
//! continued with `--resume`, merge to the bits of the whole render; parts
//! that do not make one render are refused with the reason.

use crate::common;

use common::*;
use std::path::Path;
use std::time::Duration;

fn bits(p: &Path) -> Vec<u32> {
    let img = lumis_render::image_io::read_image(p).unwrap();
    img.data.iter().map(|v| v.to_bits()).collect()
}

const RENDER: [&str; 10] = [
    "render",
    "--integrator",
    "path",
    "--resolution",
    "32x32",
    "--spp",
    "3000",
    "--seed",
    "9",
    "-q",
];

#[test]
fn parts_interrupted_and_resumed_merge_to_the_whole_render() {
    let d = temp_dir("cli-parts", "merge");
    let run = |extra: &[&str]| lumis(&d, &[&RENDER[..], extra].concat());
    let o = run(&["-o", "whole.pfm"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = run(&[
        "--passes",
        "0..700",
        "--partial",
        "a.lpart",
        "--threads",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("passes 0..700 of 3000"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("a.lpart"), "{}", stderr(&o));
    // A part writes no image.
    assert!(!d.join("lumis.exr").exists());
    let o = run(&["--passes", "700..701", "--partial", "b.lpart"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Interrupted: the part so far is saved, and merge calls it unfinished.
    let args = [
        &RENDER[..],
        &["--passes", "701..3000", "--partial", "c.lpart"],
    ]
    .concat();
    let o = lumis_interrupted(&d, &args, Duration::from_millis(500));
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("saved the part so far"),
        "{}",
        stderr(&o)
    );
    let merge =
        |parts: &[&str], out: &str| lumis(&d, &[&["merge"][..], parts, &["-o", out]].concat());
    let o = merge(&["c.lpart", "a.lpart", "b.lpart"], "m.pfm");
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("unfinished"), "{}", stderr(&o));
    assert!(!d.join("m.pfm").exists());
    let o = lumis(
        &d,
        &["render", "--resume", "c.lpart", "--threads", "1", "-q"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = merge(&["c.lpart", "a.lpart", "b.lpart"], "m.pfm");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("merged 3 parts"), "{}", stderr(&o));
    assert!(bits(&d.join("m.pfm")) == bits(&d.join("whole.pfm")));
    // Missing and foreign parts.
    let o = merge(&["a.lpart", "c.lpart"], "x.pfm");
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("passes 700..701 are missing"),
        "{}",
        stderr(&o)
    );
    let mut other = RENDER;
    other[8] = "10";
    let o = lumis(
        &d,
        &[
            &other[..],
            &["--passes", "700..701", "--partial", "s.lpart"],
        ]
        .concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = merge(&["a.lpart", "s.lpart", "c.lpart"], "x.pfm");
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("different renders"), "{}", stderr(&o));
    assert!(!d.join("x.pfm").exists());
}

#[test]
fn bad_pass_ranges_are_refused() {
    let d = temp_dir("cli-parts", "bad");
    for (args, expect) in [
        (&["--passes", "3..2", "--partial", "p"][..], "A < B"),
        (&["--passes", "0..3"][..], "--partial"),
        (&["--passes", "0..4000", "--partial", "p"][..], "0..3000"),
        (
            &["--passes", "0..3", "--partial", "p", "--time", "1"][..],
            "time budget",
        ),
    ] {
        let o = lumis(&d, &[&RENDER[..], args].concat());
        assert_ne!(o.status.code(), Some(0), "{args:?}");
        assert!(stderr(&o).contains(expect), "{args:?}: {}", stderr(&o));
        assert!(!d.join("p").exists());
    }
    let o = lumis(&d, &["merge", "nothing.lpart"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("nothing.lpart"), "{}", stderr(&o));
}

/// `scripts/render-parts.sh` (the loop that also drives a Slurm array)
/// splits the passes so the merge equals the whole render.
#[test]
fn the_parts_script_renders_and_merges() {
    let d = temp_dir("cli-parts", "script");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/render-parts.sh");
    let args = [
        "--integrator",
        "bdpt",
        "--resolution",
        "24x16",
        "--spp",
        "7",
    ];
    let o = std::process::Command::new("bash")
        .arg(&script)
        .args(["3", "out", "--"])
        .args(args)
        .env("LUMIS", env!("CARGO_BIN_EXE_lumis"))
        .current_dir(&d)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    for i in 0..3 {
        assert!(d.join(format!("out/part-{i}.lpart")).exists());
    }
    let o = lumis(
        &d,
        &[&["render", "-q", "-o", "whole.exr"][..], &args[..]].concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(bits(&d.join("out/image.exr")) == bits(&d.join("whole.exr")));
}
