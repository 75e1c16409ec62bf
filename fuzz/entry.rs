#![allow(dead_code)]

//! Entry points shared by the fuzz targets and the corpus replay test
//! (`crates/render/tests/fuzz_corpus.rs`): any input may give an error,
//! none may panic.

use lumis_render::image_io::{decode_image, ImageFormat};
use std::path::Path;

/// pbrt-v4 text: parsed and built into a scene (files it names are looked
/// up in a folder that does not exist).
pub fn scene(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let ov = lumis_render::load::Overrides::default();
    let _ = lumis_render::load::load_text(
        &text,
        "fuzz.pbrt",
        Path::new("/nonexistent-lumis-fuzz"),
        &ov,
    );
}

pub fn ply(data: &[u8]) {
    let _ = lumis_scene::ply::parse_ply(data);
}

pub fn exr(data: &[u8]) {
    let _ = decode_image(data, ImageFormat::Exr, "fuzz.exr");
}

pub fn pfm(data: &[u8]) {
    let _ = decode_image(data, ImageFormat::Pfm, "fuzz.pfm");
}

pub fn png(data: &[u8]) {
    let _ = decode_image(data, ImageFormat::Png, "fuzz.png");
}

/// A checkpoint file (`--resume`). The trailing checksum is recomputed
/// first, so mutations reach the parser behind it.
pub fn checkpoint(data: &[u8]) {
    use lumis_render::checkpoint::{Checkpoint, Fnv};
    let mut d = data.to_vec();
    if d.len() >= 8 {
        let n = d.len() - 8;
        let h = Fnv::default().write(&d[..n]).0;
        d[n..].copy_from_slice(&h.to_le_bytes());
    }
    let _ = Checkpoint::decode(&d, "fuzz.ckpt");
}

/// The entry point for a corpus folder name.
pub fn by_name(target: &str) -> Option<fn(&[u8])> {
    Some(match target {
        "scene" => scene,
        "ply" => ply,
        "exr" => exr,
        "pfm" => pfm,
        "png" => png,
        "checkpoint" => checkpoint,
        _ => return None,
    })
}
