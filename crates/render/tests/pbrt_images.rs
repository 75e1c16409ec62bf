//! pbrt-v4's EXR output (32-bit float, ZIP, channels stored B, G, R) reads
//! as exactly the pixels of its PFM output of the same render, in the
//! orientation and channel order of lumis' own image of the same scene
//! (`tests/data/pbrt-v4-rgb.*`; the scene file says how they were made).

use crate::common;

use common::*;
use lumis_render::image_io::read_image;
use lumis_render::load::Overrides;

fn strongest(p: &[f32]) -> usize {
    (0..3).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap()
}

#[test]
fn pbrt_v4_exr_reads_as_its_pfm_and_as_lumis_renders_the_scene() {
    let exr_path = test_data("pbrt-v4-rgb.exr");
    let meta = exr::meta::MetaData::read_from_file(&exr_path, false).unwrap();
    let names: Vec<String> = meta.headers[0]
        .channels
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    assert_eq!(
        names,
        ["B", "G", "R"],
        "the file stores channels by name, not in RGB order"
    );
    let exr = read_image(&exr_path).unwrap();
    let pfm = read_image(&test_data("pbrt-v4-rgb.pfm")).unwrap();
    assert_eq!((exr.width, exr.height), (8, 6));
    assert_eq!(exr.data, pfm.data);

    let text = std::fs::read_to_string(test_data("pbrt-v4-rgb.pbrt")).unwrap();
    let ours = render_loaded(&load(&text, &Overrides::default()), 16, 1, 1)
        .film
        .mean_image();
    let mut lit = [0; 3];
    for (theirs, ours) in exr.data.chunks(3).zip(ours.chunks(3)) {
        if theirs.iter().cloned().fold(0.0, f32::max) > 0.2 {
            assert_eq!(strongest(theirs), strongest(ours), "{theirs:?} vs {ours:?}");
            lit[strongest(theirs)] += 1;
        }
    }
    assert!(
        lit.iter().all(|&n| n >= 6),
        "each colour covers pixels: {lit:?}"
    );
}
