//! End to end: a tiny study (two scenes, 16x16 images, references rendered
//! here) writes its report, every image and finite metrics, and a rerun
//! resumes by skipping every finished run. Also `compare --heatmap`.

use crate::common;

use common::*;
use std::path::Path;

const HEAD: &str = r#"Integrator "photon" "integer maxdepth" [ 5 ]
LookAt 0 1.6 3.4   0 0.4 0   0 1 0
Camera "perspective" "float fov" [ 35 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
Sampler "sobol" "integer pixelsamples" [ 4 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 30 30 30 ]
  Shape "trianglemesh" "point3 P" [ -0.3 3 -0.3  0.3 3 -0.3  0.3 3 0.3  -0.3 3 0.3 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
Shape "trianglemesh" "point3 P" [ -3 0 -3  -3 0 3  3 0 3  3 0 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
"#;

fn config(dir: &Path) {
    std::fs::write(dir.join("plain.pbrt"), HEAD).unwrap();
    let glass = format!(
        "{HEAD}Material \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0 0.8 0\nShape \"sphere\" \"float radius\" [ 0.5 ]\n"
    );
    std::fs::write(dir.join("glass.pbrt"), glass).unwrap();
    for s in ["plain", "glass"] {
        let o = lumis(
            dir,
            &[
                "render",
                &format!("{s}.pbrt"),
                "--integrator",
                "path",
                "--spp",
                "64",
                "-q",
                "-o",
                &format!("{s}-ref.exr"),
            ],
        );
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let cfg = r#"
title = "tiny"
seeds = [1, 2]
time = [0.2]
spp = [2]
threads = 2
[[scene]]
name = "plain"
file = "plain.pbrt"
reference = "plain-ref.exr"
[[scene]]
name = "glass"
file = "glass.pbrt"
reference = "glass-ref.exr"
mask = [0.25, 0.75, 0.5, 1.0]
lit_only = true
[[setting]]
name = "path"
flags = ["--integrator", "path"]
[[setting]]
name = "mis"
flags = ["--integrator", "photon", "--photons", "2000", "--caustic-photons", "20000", "--gather-rays", "4"]
"#;
    std::fs::write(dir.join("tiny.toml"), cfg).unwrap();
}

#[test]
fn tiny_study_writes_report_images_and_finite_metrics_then_resumes() {
    let d = temp_dir("study", "tiny");
    config(&d);
    let o = lumis(&d, &["study", "tiny.toml", "--out", "rep"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rep = d.join("rep");
    let html = std::fs::read_to_string(rep.join("index.html")).unwrap();
    for s in ["plain", "glass", "<svg", "class=best", "reference.png"] {
        assert!(html.contains(s), "report lacks `{s}`");
    }
    assert!(!html.contains("<script"), "the report must need no scripts");
    let csv = std::fs::read_to_string(rep.join("metrics.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    // 2 scenes x 2 settings x 2 budgets x 2 seeds.
    assert_eq!(rows.len(), 16, "{csv}");
    for row in &rows {
        let f: Vec<&str> = row.split(',').collect();
        assert_eq!(f.len(), 14, "{row}");
        for v in &f[7..14] {
            let x: f64 = v.parse().unwrap();
            assert!(x.is_finite(), "non-finite metric in {row}");
        }
        let spp: u32 = f[4].parse().unwrap();
        assert!(spp >= 1);
        let id = format!("{}__{}__{}__s{}", f[0], f[1], f[2], f[3]);
        for ext in ["exr", "png", "err.png"] {
            let p = rep.join(f[0]).join(format!("{id}.{ext}"));
            assert!(p.is_file(), "missing {}", p.display());
        }
        assert!(rep.join("runs").join(format!("{id}.json")).is_file());
    }
    for s in ["plain", "glass"] {
        assert!(rep.join(s).join("reference.png").is_file());
    }
    // Every file the page shows exists.
    let shown = std::fs::read_to_string(rep.join("report-files.txt")).unwrap();
    for f in shown.lines() {
        assert!(rep.join(f).is_file(), "report shows missing {f}");
        assert!(f == "index.html" || f.starts_with("metrics") || html.contains(f));
    }
    // spp budgets are exact; the manifest has every run finished.
    assert!(rows
        .iter()
        .filter(|r| r.contains(",2spp,"))
        .all(|r| r.split(',').nth(4) == Some("2")));
    let manifest = std::fs::read_to_string(rep.join("manifest.json")).unwrap();
    assert!(manifest.contains("\"finished\": 16"), "{manifest}");

    // Resume: remove one run's record; only that run renders again.
    std::fs::remove_file(rep.join("runs").join("glass__mis__2spp__s2.json")).unwrap();
    let o = lumis(&d, &["study", "tiny.toml", "--out", "rep"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    assert_eq!(e.matches("skipped").count(), 15, "{e}");
    assert!(e.contains("glass__mis__2spp__s2: 2 spp"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn bad_study_config_is_a_clear_error() {
    let d = temp_dir("study", "bad");
    std::fs::write(d.join("b.toml"), "seeds = [1]\nspp = [2]\n[[scene]]\nname = \"x\"\nfile = \"none.pbrt\"\nreference = \"none.exr\"\n[[setting]]\nname = \"p\"\nflags = []\n").unwrap();
    let o = lumis(&d, &["study", "b.toml"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("none.exr"), "{}", stderr(&o));
    std::fs::write(d.join("c.toml"), "seeds = [1]\nspp = [2]\nbogus = 1\n").unwrap();
    let o = lumis(&d, &["study", "c.toml"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("bogus"), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn compare_writes_a_heatmap_with_a_colour_bar() {
    let d = temp_dir("study", "heat");
    config(&d);
    let o = lumis(
        &d,
        &[
            "compare",
            "plain-ref.exr",
            "glass-ref.exr",
            "--heatmap",
            "h.png",
            "--heatmap-range",
            "1e-4,10",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("relative squared error per pixel, log scale 1.00e-4 .. 1.00e1"),
        "{out}"
    );
    let h = lumis_render::image_io::read_image(&d.join("h.png")).unwrap();
    // The image (16x16) plus the bar and its labels, at least as wide as the labels.
    assert!(h.width >= 16 && h.height > 16 + 8);
    let o = lumis(
        &d,
        &[
            "compare",
            "plain-ref.exr",
            "glass-ref.exr",
            "--heatmap",
            "h.png",
            "--heatmap-error",
            "x",
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    let _ = std::fs::remove_dir_all(&d);
}
