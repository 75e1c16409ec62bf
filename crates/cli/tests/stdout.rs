//! End-to-end: a reader of stdout that stops early (`lumis compare a b |
//! head -3`) ends the program quietly, as with other command-line tools.

use crate::common;

use common::*;
use lumis_render::image_io::{write_image, RgbImage};

#[test]
fn compare_into_a_closed_pipe_ends_quietly() {
    let d = temp_dir("cli-stdout", "compare");
    for (name, v) in [("a.pfm", 0.5), ("b.pfm", 0.25)] {
        write_image(&d.join(name), &RgbImage::new(2, 2, vec![v; 12]), 0.0).unwrap();
    }
    let o = lumis_to_closed_pipe(&d, &["compare", "a.pfm", "b.pfm"]);
    let err = stderr(&o);
    assert!(!err.contains("panicked"), "{err}");
    assert!(!err.contains("Broken pipe"), "{err}");
    assert_eq!(o.status.code(), Some(0), "{err}");
}
