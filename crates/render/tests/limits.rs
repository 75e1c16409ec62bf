//! Absurd sizes are refused with a message before anything big is
//! allocated: a counting allocator records the largest single allocation
//! made by this thread while the input is read.

use lumis_render::load::photon::PhotonOverrides;
use lumis_render::load::{load_text, BuildOverrides};
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
    let (r, big) = largest_alloc(|| load_text(&s, "s.pbrt", &dir, &BuildOverrides::default()));
    let e = r.err().expect("refused").to_string();
    assert!(e.contains("huge.ply") && e.contains("1000000000000"), "{e}");
    assert!(big < MIB, "allocated {big} bytes");
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
    let (r, big) =
        largest_alloc(|| load_text(&s, "s.pbrt", Path::new("."), &BuildOverrides::default()));
    let e = r.err().expect("refused").to_string();
    assert!(e.contains("1000000000x1000000000 is out of range"), "{e}");
    assert!(e.starts_with("s.pbrt:1:"), "{e}");
    assert!(big < MIB, "allocated {big} bytes");
    // The command line's --resolution is checked the same way.
    let ov = BuildOverrides {
        resolution: Some((1_000_000_000, 1_000_000_000)),
        ..Default::default()
    };
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
    let ov = BuildOverrides {
        integrator: Some("photon".into()),
        photon: PhotonOverrides {
            photons: Some(1_000_000_000_000),
            ..Default::default()
        },
        ..Default::default()
    };
    let (r, big) = largest_alloc(|| load_text(&scene("", ""), "s.pbrt", Path::new("."), &ov));
    let e = r.err().expect("refused").to_string();
    assert!(e.contains("photons") && e.contains("GiB"), "{e}");
    assert!(big < MIB, "allocated {big} bytes");
}
