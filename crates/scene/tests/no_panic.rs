//! Bad input never panics: random scene text and corrupted PLY data give errors.

use lumis_scene::load_str;
use lumis_scene::ply::parse_ply;
use proptest::prelude::*;
use std::path::Path;

const WORDS: &[&str] = &[
    "WorldBegin",
    "AttributeBegin",
    "AttributeEnd",
    "Shape",
    "\"sphere\"",
    "\"float radius\"",
    "[",
    "]",
    "1",
    "-2.5e3",
    "\"rgb L\"",
    "Translate",
    "LookAt",
    "Transform",
    "true",
    "\"",
    "#c\n",
    "\n",
    "Material",
    "NamedMaterial",
    "\"x\"",
    "ObjectBegin",
    "ObjectEnd",
    "Camera",
    "\"bool b\"",
    "CoordSysTransform",
    "\"integer n\"",
    "TransformEnd",
    "Include",
    "\\",
];

fn ply_bytes() -> Vec<u8> {
    let mut b = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        .to_vec();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        b.extend(v.to_le_bytes());
    }
    b.push(3);
    for i in [0i32, 1, 2] {
        b.extend(i.to_le_bytes());
    }
    b
}

proptest! {
    #[test]
    fn random_directive_soup(idx in prop::collection::vec(0..WORDS.len(), 0..40)) {
        let text: Vec<&str> = idx.iter().map(|&i| WORDS[i]).collect();
        let _ = load_str(&text.join(" "), "fuzz.pbrt", Path::new("/nonexistent"));
    }

    #[test]
    fn random_text(s in "\\PC{0,200}") {
        let _ = load_str(&s, "fuzz.pbrt", Path::new("/nonexistent"));
    }

    #[test]
    fn corrupted_ply(pos in 0usize..200, byte in any::<u8>(), cut in 0usize..200) {
        let mut b = ply_bytes();
        let p = pos % b.len();
        b[p] = byte;
        b.truncate(b.len() - cut.min(b.len()));
        let _ = parse_ply(&b);
    }
}

#[test]
fn uncorrupted_ply_parses() {
    let m = parse_ply(&ply_bytes()).unwrap();
    assert_eq!(m.indices, vec![0, 1, 2]);
}
