//! Absurd sizes are refused with a message before anything big is
//! allocated: a counting allocator records the largest single allocation
//! made by this thread while the input is read.

use lumis_render::load::{load_text, Overrides};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::Path;

struct Counting;

thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards to the system allocator; only records sizes in a
// const-initialised thread-local (no allocation inside the allocator).
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let _ = LARGEST.try_with(|m| m.set(m.get().max(l.size())));
        System.alloc(l)
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        System.dealloc(p, l)
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        let _ = LARGEST.try_with(|m| m.set(m.get().max(new)));
        System.realloc(p, l, new)
    }
}

#[global_allocator]
static A: Counting = Counting;

/// Runs `f`, returning its result and the largest allocation it made.
fn largest_alloc<T>(f: impl FnOnce() -> T) -> (T, usize) {
    LARGEST.with(|m| m.set(0));
    let r = f();
    (r, LARGEST.with(|m| m.get()))
}

const MIB: usize = 1 << 20;

fn scene(film: &str, world: &str) -> String {
    format!("Film \"rgb\" {film}\nCamera \"perspective\"\nWorldBegin\nLightSource \"point\" \"rgb I\" [1 1 1]\n{world}")
}

#[test]
fn ply_header_with_10_to_the_12_vertices() {
    let text = "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\n\
property float y\nproperty float z\nelement face 1000000000000\nproperty list uchar int vertex_indices\nend_header\n";
    let (r, big) = largest_alloc(|| lumis_scene::ply::parse_ply(text.as_bytes()));
    let e = r.unwrap_err().to_string();
    assert!(e.contains("declares 1000000000000 vertices"), "{e}");
    assert!(big < MIB, "allocated {big} bytes");
    // Through a scene file, the error names the PLY file.
    let dir = std::env::temp_dir().join(format!("lumis-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("huge.ply"), text).unwrap();
    let s = scene("", "Shape \"plymesh\" \"string filename\" \"huge.ply\"\n");
    let (r, big) = largest_alloc(|| load_text(&s, "s.pbrt", &dir, &Overrides::default()));
    let e = r.err().expect("refused").to_string();
    assert!(e.contains("huge.ply") && e.contains("1000000000000"), "{e}");
    assert!(big < MIB, "allocated {big} bytes");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_counter_sees_big_allocations() {
    let (v, big) = largest_alloc(|| vec![1u8; 2 * MIB]);
    assert_eq!(v.len(), 2 * MIB);
    assert!(big >= 2 * MIB, "{big}");
}

#[test]
fn film_of_10_to_the_9_squared_pixels() {
    let s = scene(
        "\"integer xresolution\" [1000000000] \"integer yresolution\" [1000000000]",
        "",
    );
    let (r, big) = largest_alloc(|| load_text(&s, "s.pbrt", Path::new("."), &Overrides::default()));
    let e = r.err().expect("refused").to_string();
    assert!(e.contains("1000000000x1000000000 is out of range"), "{e}");
    assert!(e.starts_with("s.pbrt:1:"), "{e}");
    assert!(big < MIB, "allocated {big} bytes");
    // The command line's --resolution is checked the same way.
    let mut ov = Overrides::default();
    ov.resolution(1_000_000_000, 1_000_000_000);
    let (r, big) = largest_alloc(|| load_text(&scene("", ""), "s.pbrt", Path::new("."), &ov));
    assert!(r
        .err()
        .expect("refused")
        .to_string()
        .contains("out of range"));
    assert!(big < MIB, "allocated {big} bytes");
}

#[test]
fn photon_budget_beyond_memory() {
    // The largest count a scene's integer holds: 2e9 photons, ~100 GiB of maps.
    let mut ov = Overrides::default();
    ov.integrator("photon")
        .integrator_param("integer photons", "2000000000");
    let (r, big) = largest_alloc(|| load_text(&scene("", ""), "s.pbrt", Path::new("."), &ov));
    let e = r.err().expect("refused").to_string();
    assert!(e.contains("photons") && e.contains("GiB"), "{e}");
    assert!(big < MIB, "allocated {big} bytes");
}

#[test]
fn image_headers_declaring_huge_sizes() {
    use lumis_render::image_io::{decode_image, write_image, ImageFormat, RgbImage};
    // EXR: a real 2x2 file whose data window is patched to 10^9 x 10^9.
    let dir = std::env::temp_dir().join(format!("lumis-limits-img-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("a.exr");
    write_image(&p, &RgbImage::new(2, 2, vec![0.5; 12]), 0.0).unwrap();
    let mut exr = std::fs::read(&p).unwrap();
    let key = b"dataWindow\0box2i\0";
    let at = exr.windows(key.len()).position(|w| w == key).unwrap() + key.len() + 4;
    for (i, v) in [0i32, 0, 999_999_999, 999_999_999].iter().enumerate() {
        exr[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
    }
    let (r, big) = largest_alloc(|| decode_image(&exr, ImageFormat::Exr, "a.exr"));
    let e = r.unwrap_err().to_string();
    assert!(e.starts_with("a.exr: not a valid EXR file"), "{e}");
    assert!(e.contains("declares 1000000000x1000000000 pixels"), "{e}");
    assert!(big < 16 * MIB, "allocated {big} bytes");
    // PFM: the header claims more data than the file has.
    let pfm = b"PF\n1000000000 1000000000\n-1.0\n\0\0\0\0";
    let (r, big) = largest_alloc(|| decode_image(pfm, ImageFormat::Pfm, "a.pfm"));
    assert!(r
        .unwrap_err()
        .to_string()
        .contains("shorter than its header"));
    assert!(big < MIB, "allocated {big} bytes");
    // PNG: a 100000 x 100000 IHDR in front of a tiny image stream.
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let chunk = |png: &mut Vec<u8>, ty: &[u8], data: &[u8]| {
        png.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let start = png.len();
        png.extend_from_slice(ty);
        png.extend_from_slice(data);
        let crc = crc32(&png[start..]);
        png.extend_from_slice(&crc.to_be_bytes());
    };
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&100_000u32.to_be_bytes());
    ihdr.extend_from_slice(&100_000u32.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    chunk(&mut png, b"IHDR", &ihdr);
    chunk(
        &mut png,
        b"IDAT",
        &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01],
    );
    chunk(&mut png, b"IEND", &[]);
    let (r, big) = largest_alloc(|| decode_image(&png, ImageFormat::Png, "a.png"));
    assert!(r.is_err());
    assert!(big < 16 * MIB, "allocated {big} bytes");
    let _ = std::fs::remove_dir_all(&dir);
}

fn crc32(data: &[u8]) -> u32 {
    let mut c = 0xffff_ffffu32;
    for &b in data {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xedb8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}
