//! End-to-end: a checkpoint resumes only the scene it was made of, and every
//! file read to build that scene counts (included files, texture images).
//! Resuming the unchanged scene is tested in cli.rs.

use crate::common;

use common::*;
use lumis_render::image_io::{write_image, RgbImage};
use std::path::Path;

/// Renders `main.pbrt` in `d` with a checkpoint `ck`.
fn render_with_checkpoint(d: &Path) {
    let o = lumis(
        d,
        &[
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
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

/// `--resume ck` is refused with the reason.
fn assert_resume_refused(d: &Path) {
    let o = lumis(d, &["render", "--resume", "ck"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("another scene"), "{}", stderr(&o));
}

const HEADER: &str = "Film \"rgb\" \"integer xresolution\" [8] \"integer yresolution\" [8]\n\
    LookAt 0 0 -3 0 0 0 0 1 0\nCamera \"perspective\"\nWorldBegin\n\
    LightSource \"point\" \"rgb I\" [5 5 5] \"point3 from\" [0 0 -2]\n";

const QUAD: &str = "Shape \"trianglemesh\" \"point3 P\" [-1 -1 0 1 -1 0 1 1 0 -1 1 0] \
    \"integer indices\" [0 1 2 0 2 3] \"point2 uv\" [0 0 1 0 1 1 0 1]\n";

#[test]
fn a_material_value_changed_in_an_included_file_is_refused() {
    let d = temp_dir("cli-resume", "material");
    let main = format!("{HEADER}Include \"mat.pbrt\"\nNamedMaterial \"m\"\n{QUAD}");
    std::fs::write(d.join("main.pbrt"), main).unwrap();
    let mat = |r: &str| {
        format!("MakeNamedMaterial \"m\" \"string type\" \"diffuse\" \"rgb reflectance\" [{r} 0.5 0.5]\n")
    };
    std::fs::write(d.join("mat.pbrt"), mat("0.5")).unwrap();
    render_with_checkpoint(&d);
    std::fs::write(d.join("mat.pbrt"), mat("0.6")).unwrap();
    assert_resume_refused(&d);
}

#[test]
fn a_texture_image_replaced_is_refused() {
    let d = temp_dir("cli-resume", "image");
    let main = format!(
        "{HEADER}Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"t.exr\"\n\
         Material \"diffuse\" \"texture reflectance\" \"t\"\n{QUAD}"
    );
    std::fs::write(d.join("main.pbrt"), main).unwrap();
    let image = |v: f32| {
        let img = RgbImage::new(2, 2, vec![v; 12]);
        write_image(&d.join("t.exr"), &img, 1.0).unwrap();
    };
    image(0.2);
    render_with_checkpoint(&d);
    image(0.8);
    assert_resume_refused(&d);
}
