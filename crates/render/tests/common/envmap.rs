//! Environment-map test images written to a temporary folder.
#![allow(dead_code)]

use lumis_math::Rgb;
use lumis_render::image_io::{write_image, RgbImage};
use std::path::PathBuf;

/// Writes `f(x, y)` as a `w` × `h` image named `name` (extension picks the
/// format) in cargo's temporary folder for tests (under `target/`, so runs
/// leave nothing in the system's); returns its path. One folder for every
/// run: a name always holds the same image, and each write is a rename of
/// a whole file, so concurrent test processes cannot tear one.
pub fn write_env(name: &str, w: u32, h: u32, f: impl Fn(u32, u32) -> Rgb) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("envmaps");
    std::fs::create_dir_all(&dir).unwrap();
    let mut data = Vec::with_capacity((w * h * 3) as usize);
    for y in 0..h {
        for x in 0..w {
            data.extend_from_slice(&f(x, y).to_array());
        }
    }
    let path = dir.join(name);
    write_image(&path, &RgbImage::new(w, h, data), 0.0).unwrap();
    path
}

/// A lumpy test map: a smooth gradient, a bright spot, and a dark band of
/// exact zeros (so that the sampler must avoid texels of zero radiance).
pub fn lumpy(w: u32, h: u32) -> impl Fn(u32, u32) -> Rgb {
    move |x, y| {
        let (u, v) = ((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
        if (0.40..0.48).contains(&v) {
            return Rgb::BLACK;
        }
        let spot = if (u - 0.7).powi(2) + (v - 0.25).powi(2) < 0.01 {
            40.0
        } else {
            0.0
        };
        Rgb::new(0.2 + u + spot, 0.5 + 0.3 * v, 0.1 + v * v + 0.5 * spot)
    }
}
