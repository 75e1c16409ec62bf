//! `--display-server`: a small tev stand-in decodes the stream (CreateImage
//! once, then UpdateImage tiles of at most 128x128) and its final image must
//! equal the written EXR; an absent or vanishing viewer is one warning.

use crate::common;
use std::io::Read;
use std::net::TcpListener;

use common::*;

struct Cursor<'a>(&'a [u8]);

impl Cursor<'_> {
    fn u8(&mut self) -> u8 {
        let v = self.0[0];
        self.0 = &self.0[1..];
        v
    }
    fn i32(&mut self) -> i32 {
        let v = i32::from_le_bytes(self.0[..4].try_into().unwrap());
        self.0 = &self.0[4..];
        v
    }
    fn f32(&mut self) -> f32 {
        f32::from_bits(self.i32() as u32)
    }
    fn str(&mut self) -> String {
        let n = self.0.iter().position(|&b| b == 0).expect("NUL-terminated");
        let s = String::from_utf8(self.0[..n].to_vec()).unwrap();
        self.0 = &self.0[n + 1..];
        s
    }
}

#[derive(Default, Debug)]
struct Received {
    name: String,
    size: (i32, i32),
    channels: Vec<String>,
    creates: usize,
    updates: usize,
    image: Vec<f32>,
}

/// Reads packets until the sender closes the connection.
fn decode(stream: &mut impl Read) -> Received {
    let mut all = Vec::new();
    stream.read_to_end(&mut all).unwrap();
    let mut r = Received::default();
    let mut at = 0;
    while at < all.len() {
        let len = u32::from_le_bytes(all[at..at + 4].try_into().unwrap()) as usize;
        let mut c = Cursor(&all[at + 4..at + len]);
        at += len;
        match c.u8() {
            4 => {
                assert_eq!(c.u8(), 0, "grab focus");
                r.name = c.str();
                r.size = (c.i32(), c.i32());
                let n = c.i32();
                r.channels = (0..n).map(|_| c.str()).collect();
                r.creates += 1;
                r.image = vec![f32::NAN; (3 * r.size.0 * r.size.1) as usize];
            }
            3 => {
                assert_eq!(r.creates, 1, "update before create");
                c.u8();
                assert_eq!(c.str(), r.name);
                let cname = c.str();
                let ch = r.channels.iter().position(|n| *n == cname).unwrap();
                let (x, y, w, h) = (c.i32(), c.i32(), c.i32(), c.i32());
                assert!(w > 0 && h > 0 && w <= 128 && h <= 128, "tile {w}x{h}");
                assert!(x + w <= r.size.0 && y + h <= r.size.1);
                for yy in y..y + h {
                    for xx in x..x + w {
                        r.image[(3 * (yy * r.size.0 + xx)) as usize + ch] = c.f32();
                    }
                }
                assert!(c.0.is_empty(), "packet longer than its tile");
                r.updates += 1;
            }
            t => panic!("unexpected packet type {t}"),
        }
    }
    r
}

#[test]
fn stream_decodes_to_the_final_image() {
    let d = temp_dir("tev", "stream");
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap().to_string();
    let server = std::thread::spawn(move || decode(&mut listener.accept().unwrap().0));
    let o = lumis(
        &d,
        &[
            "render",
            "--integrator",
            "path",
            "--resolution",
            "300x140",
            "--spp",
            "3",
            "-o",
            "view.exr",
            "-q",
            "--display-server",
            &addr,
        ],
    );
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{e}");
    assert!(!e.contains("warning: display"), "{e}");
    let r = server.join().unwrap();
    assert_eq!(r.creates, 1);
    assert_eq!(r.name, "view");
    assert_eq!(r.size, (300, 140));
    assert_eq!(r.channels, ["R", "G", "B"]);
    // At least the first full image: 3 x 2 tiles, 3 channels.
    assert!(r.updates >= 18, "{} updates", r.updates);
    let img = lumis_render::image_io::read_image(&d.join("view.exr")).unwrap();
    assert_eq!(r.image.len(), img.data.len());
    for (i, (a, b)) in r.image.iter().zip(&img.data).enumerate() {
        assert_eq!(
            a.to_bits(),
            b.to_bits(),
            "value {i}: streamed {a}, file {b}"
        );
    }
}

#[test]
fn absent_or_vanishing_viewer_is_one_warning() {
    let d = temp_dir("tev", "absent");
    // Nothing listens on a port we bound and released.
    let port = TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let args = |addr: &str, out: &str| {
        lumis(
            &d,
            &[
                "render",
                "--integrator",
                "path",
                "--resolution",
                "64x64",
                "--spp",
                "40",
                "-o",
                out,
                "-q",
                "--display-server",
                addr,
            ],
        )
    };
    let o = args(&format!("127.0.0.1:{port}"), "a.exr");
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{e}");
    assert_eq!(e.matches("warning: display server").count(), 1, "{e}");
    assert!(d.join("a.exr").exists());
    // A viewer that accepts, then goes away at once.
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap().to_string();
    let server = std::thread::spawn(move || drop(listener.accept().unwrap()));
    let o = args(&addr, "b.exr");
    server.join().unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{e}");
    assert!(e.matches("warning: display server").count() <= 1, "{e}");
    assert!(d.join("b.exr").exists());
}
