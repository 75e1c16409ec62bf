//! End to end: a study with an external setting (a shell script standing
//! in for another renderer) beside a lumis setting, and one whose program
//! is missing: placeholders, the scene copy, the calibration, measuring the
//! program's image, slopes, skipping, and a rerun that neither renders nor
//! calibrates again.

use crate::common;

use common::*;
use lumis_render::study::calibrate::Calibration;
use std::path::Path;

/// A 16x16 scene whose floor is a sibling file, included.
const SCENE: &str = r#"Integrator "photon" "integer maxdepth" [ 5 ]
LookAt 0 1.6 3.4   0 0.4 0   0 1 0
Camera "perspective" "float fov" [ 35 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 30 30 30 ]
  Shape "trianglemesh" "point3 P" [ -0.3 3 -0.3  0.3 3 -0.3  0.3 3 0.3  -0.3 3 0.3 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
Include "floor.pbrt"
"#;

const FLOOR: &str = r#"Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
Shape "trianglemesh" "point3 P" [ -3 0 -3  -3 0 3  3 0 3  3 0 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
"#;

/// A stand-in for another renderer: `fake.sh SPP SEED OUT SCENE THREADS`
/// logs its arguments to `calls.txt` in its working folder, sleeps 0.05 s
/// per sample, checks that the scene copy has `Integrator "sppm"` and an
/// `Include` that resolves from anywhere, and writes a 16x16 PFM of 0.5.
const FAKE: &str = r#"#!/bin/sh
echo "$*" >> calls.txt
i=0; while [ $i -lt "$1" ]; do sleep 0.05; i=$((i+1)); done
grep -q '^Integrator "sppm" "integer maxdepth" \[ 5 \]$' "$4" || { echo "no sppm in $4" >&2; exit 2; }
inc=$(sed -n 's/^Include "\(.*\)"$/\1/p' "$4")
[ -f "$inc" ] || { echo "Include '$inc' does not resolve" >&2; exit 3; }
{ printf 'PF\n16 16\n-1.0\n'; i=0; while [ $i -lt 768 ]; do printf '\000\000\000\077'; i=$((i+1)); done; } > "$3"
"#;

fn external_config(dir: &Path) {
    let scenes = dir.join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    std::fs::write(scenes.join("inc.pbrt"), SCENE).unwrap();
    std::fs::write(scenes.join("floor.pbrt"), FLOOR).unwrap();
    let fake = dir.join("fake.sh");
    std::fs::write(&fake, FAKE).unwrap();
    let o = std::process::Command::new("chmod")
        .arg("+x")
        .arg(&fake)
        .status()
        .unwrap();
    assert!(o.success());
    // The reference: 0.25 everywhere, so the fake's 0.5 has a known error.
    let r = lumis_render::image_io::RgbImage::new(16, 16, vec![0.25; 768]);
    lumis_render::image_io::write_image(&dir.join("ref.pfm"), &r, 0.0).unwrap();
    let cfg = r#"
title = "external"
seeds = [1, 2]
time = [0.4, 0.8]
spp = [2]
threads = 1
[[scene]]
name = "inc"
file = "scenes/inc.pbrt"
reference = "ref.pfm"
[[setting]]
name = "path"
flags = ["--integrator", "path"]
[[setting]]
name = "fake"
external = ["{config_dir}/fake.sh", "{spp}", "{seed}", "{out}", "{scene}", "{threads}"]
integrator = "sppm"
output = "pfm"
calibration_seconds = 0.3
[[setting]]
name = "gone"
external = ["{config_dir}/no-such-renderer", "{spp}", "{out}", "{scene}"]
"#;
    std::fs::write(dir.join("ext.toml"), cfg).unwrap();
}

#[test]
fn external_renderer_runs_calibrated_beside_lumis_and_a_missing_one_is_skipped() {
    let d = temp_dir("study", "external");
    external_config(&d);
    let o = lumis(&d, &["study", "ext.toml", "--out", "rep"]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    let rep = d.join("rep");
    // The missing program: one notice, no runs, said in the report.
    assert_eq!(e.matches("no-such-renderer").count(), 1, "{e}");
    assert!(
        e.contains("setting `gone`: its 6 runs are skipped, program `")
            && e.contains("no-such-renderer` not found"),
        "{e}"
    );
    let html = std::fs::read_to_string(rep.join("index.html")).unwrap();
    for s in [
        "Skipped:",
        "External renderers",
        "Error against time: slopes",
        "fake (",
        "path (",
    ] {
        assert!(html.contains(s), "report lacks `{s}`");
    }
    // The calibration: 1, 4 then 16 spp (0.05 s each: 0.75 s > 0.3 s spread).
    let cal: Calibration = serde_json::from_str(
        &std::fs::read_to_string(rep.join("calibration/inc__fake.json")).unwrap(),
    )
    .unwrap();
    let spps: Vec<u32> = cal.points.iter().map(|p| p.0).collect();
    assert_eq!(spps, [1, 4, 16]);
    for t in [0.4, 0.8] {
        let k = cal.line_for(t).slope;
        assert!((0.05..0.2).contains(&k), "{k} s per sample");
    }
    let calib_calls = std::fs::read_to_string(rep.join("calibration/calls.txt")).unwrap();
    assert_eq!(calib_calls.lines().count(), 3);
    // The scene copy: renamed Integrator, the sibling Include made absolute.
    let copy = rep.join("inc/fake.scene/inc.pbrt");
    let text = std::fs::read_to_string(&copy).unwrap();
    let floor = d.join("scenes/floor.pbrt");
    assert!(
        text.contains(&format!("Include \"{}\"", floor.display())),
        "{text}"
    );
    assert!(text.starts_with("Integrator \"sppm\" \"integer maxdepth\" [ 5 ]\n"));
    // Every run's arguments, substituted.
    let calls = std::fs::read_to_string(rep.join("inc/calls.txt")).unwrap();
    let calls: Vec<&str> = calls.lines().collect();
    assert_eq!(calls.len(), 6);
    for (call, (budget, seed)) in calls.iter().zip([
        ("t0.4s", 1),
        ("t0.4s", 2),
        ("t0.8s", 1),
        ("t0.8s", 2),
        ("2spp", 1),
        ("2spp", 2),
    ]) {
        let a: Vec<&str> = call.split(' ').collect();
        let seconds = match budget {
            "t0.4s" => 0.4,
            "t0.8s" => 0.8,
            _ => f64::NAN,
        };
        let spp = if seconds.is_nan() {
            2
        } else {
            cal.spp_for(seconds)
        };
        let out = rep
            .join("inc")
            .join(format!("inc__fake__{budget}__s{seed}.pfm"));
        let want = [
            spp.to_string(),
            seed.to_string(),
            out.display().to_string(),
            copy.display().to_string(),
            "1".into(),
        ];
        assert_eq!(a, want, "{call}");
    }
    // Measured like lumis runs: |0.5 - 0.25|^2 per channel; seconds are the
    // process's wall time, at least its sleeps.
    let csv = std::fs::read_to_string(rep.join("metrics.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|r| r.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 12, "{csv}");
    assert!(rows.iter().all(|r| r[1] != "gone"));
    for r in rows.iter().filter(|r| r[1] == "fake") {
        let (spp, secs): (f64, f64) = (r[4].parse().unwrap(), r[5].parse().unwrap());
        let (mse, relmse): (f64, f64) = (r[7].parse().unwrap(), r[9].parse().unwrap());
        assert!(secs >= 0.05 * spp, "{r:?}");
        assert!(
            (mse - 0.0625).abs() < 1e-9 && (relmse - 0.0625 / 0.0725).abs() < 1e-6,
            "{r:?}"
        );
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(rep.join("metrics.json")).unwrap()).unwrap();
    let slopes = json["slopes"].as_array().unwrap();
    assert_eq!(slopes.len(), 2, "{slopes:?}");
    let fake = slopes.iter().find(|s| s["setting"] == "fake").unwrap();
    assert!(
        fake["relmse"].as_f64().unwrap().abs() < 1e-9,
        "constant error: {fake}"
    );
    assert!(json["skipped"][0].as_str().unwrap().contains("gone"));

    // A rerun: nothing renders, nothing calibrates.
    let o = lumis(&d, &["study", "ext.toml", "--out", "rep"]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(!e.contains("calibrating"), "{e}");
    assert_eq!(e.matches("finished before, skipped").count(), 12, "{e}");
    let again = std::fs::read_to_string(rep.join("calibration/calls.txt")).unwrap();
    assert_eq!(again, calib_calls);
    let _ = std::fs::remove_dir_all(&d);
}
