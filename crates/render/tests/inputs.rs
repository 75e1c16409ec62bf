//! A loaded scene's inputs: its text and every file read to build it, each
//! once in first-read order, and their hash (which ties a checkpoint to them).

use lumis_render::image_io::{write_image, RgbImage};
use lumis_render::load::{inputs_hash, load_path, load_text, Overrides};

const PLY: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
    property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
    -1 -1 0\n1 -1 0\n0 1 0\n3 0 1 2\n";

#[test]
fn every_file_read_is_an_input_and_its_contents_count() {
    let d = std::env::temp_dir().join(format!("lumis-inputs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let main = "LookAt 0 0 -3 0 0 0 0 1 0\nCamera \"perspective\"\n\
        Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n\
        LightSource \"point\" \"rgb I\" [5 5 5] \"point3 from\" [0 0 -2]\n\
        Import \"mat.pbrt\"\nInclude \"mat.pbrt\"\n\
        Shape \"plymesh\" \"string filename\" \"m.ply\"\n";
    std::fs::write(d.join("main.pbrt"), main).unwrap();
    let mat = "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"t.exr\"\n\
        Material \"conductor\" \"spectrum eta\" \"eta.spd\" \"spectrum k\" \"eta.spd\"\n";
    std::fs::write(d.join("mat.pbrt"), mat).unwrap();
    std::fs::write(d.join("m.ply"), PLY).unwrap();
    std::fs::write(d.join("eta.spd"), "400 1.5\n700 1.5\n").unwrap();
    let image = |v: f32| write_image(&d.join("t.exr"), &RgbImage::new(1, 1, vec![v; 3]), 1.0);
    image(0.5).unwrap();

    let ov = Overrides::default();
    let l = load_path(&d.join("main.pbrt"), &ov).unwrap();
    let names: Vec<_> = l
        .inputs
        .files
        .iter()
        .map(|f| f.strip_prefix(&d).unwrap())
        .collect();
    let names: Vec<_> = names.iter().map(|f| f.to_str().unwrap()).collect();
    assert_eq!(
        names,
        ["main.pbrt", "mat.pbrt", "t.exr", "eta.spd", "m.ply"]
    );
    assert!(l.inputs.text.is_none());
    let h = inputs_hash(&l.inputs);
    assert_eq!(
        inputs_hash(&load_path(&d.join("main.pbrt"), &ov).unwrap().inputs),
        h
    );

    // Another image, same size and name: another scene.
    image(0.25).unwrap();
    assert_ne!(inputs_hash(&l.inputs), h);
    image(0.5).unwrap();
    assert_eq!(inputs_hash(&l.inputs), h);
    // The same files reached by a relative path: the same scene (and the
    // paths kept stay valid after the current folder changes).
    let here = std::env::current_dir().unwrap();
    std::env::set_current_dir(&d).unwrap();
    let rel = load_path(std::path::Path::new("main.pbrt"), &ov);
    std::env::set_current_dir(here).unwrap();
    assert_eq!(inputs_hash(&rel.unwrap().inputs), h);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn text_given_as_text_is_an_input() {
    let ov = Overrides::default();
    let scene = lumis_render::load::DEFAULT_SCENE;
    let l = load_text(scene, "<default>", std::path::Path::new("."), &ov).unwrap();
    assert_eq!(l.inputs.text.as_deref(), Some(scene));
    assert!(l.inputs.files.is_empty());
    let edited = format!("{scene}\n# edited\n");
    let e = load_text(&edited, "<default>", std::path::Path::new("."), &ov).unwrap();
    assert_ne!(inputs_hash(&e.inputs), inputs_hash(&l.inputs));
}
