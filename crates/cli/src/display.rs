//! Live preview in tev over its TCP protocol. Every packet is a u32 total
//! length (including itself), a type byte and the payload, little-endian,
//! strings NUL-terminated. lumis sends CreateImage (type 4: grab focus, name,
//! width, height, channel count, channel names) once, then UpdateImage
//! (type 3: grab focus, name, channel, x, y, width, height, floats) for each
//! channel of each changed tile of at most 128x128.
//!
//! The render only drops its latest image into a one-slot mailbox; a thread
//! of its own connects and sends. A viewer that is absent, slow or gone costs
//! the render nothing: one warning, then frames are dropped.

use std::io::Write;
use std::net::{TcpStream, ToSocketAddrs};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

pub const TILE: u32 = 128;
const CHANNELS: [&str; 3] = ["R", "G", "B"];

#[derive(Default)]
struct Mailbox {
    frame: Option<Vec<f32>>,
    closed: bool,
}

pub struct Display {
    mailbox: Arc<(Mutex<Mailbox>, Condvar)>,
    thread: Option<JoinHandle<()>>,
    last_offer: Option<Instant>,
    pub interval: Duration,
}

impl Display {
    /// Starts the sender for an image `name` of `width` x `height`.
    pub fn start(addr: &str, name: &str, width: u32, height: u32) -> Display {
        let mailbox: Arc<(Mutex<Mailbox>, Condvar)> = Arc::default();
        let (m, addr, name) = (mailbox.clone(), addr.to_string(), name.to_string());
        let thread = std::thread::spawn(move || {
            if let Err(e) = send_loop(&m, &addr, &name, width, height) {
                eprintln!("lumis: warning: display server {addr}: {e}; rendering continues without the preview");
                // Drain: later frames are dropped.
                let mut g = m.0.lock().unwrap();
                while !g.closed {
                    g.frame = None;
                    g = m.1.wait(g).unwrap();
                }
            }
        });
        Display {
            mailbox,
            thread: Some(thread),
            last_offer: None,
            interval: Duration::from_millis(500),
        }
    }

    /// Offers the image (row-major RGB) if the last offer is older than the
    /// interval; `make` is only called then.
    pub fn offer(&mut self, make: impl FnOnce() -> Vec<f32>) {
        if self.last_offer.is_some_and(|t| t.elapsed() < self.interval) {
            return;
        }
        self.last_offer = Some(Instant::now());
        self.put(make());
    }

    fn put(&self, img: Vec<f32>) {
        let mut g = self.mailbox.0.lock().unwrap();
        g.frame = Some(img);
        self.mailbox.1.notify_one();
    }

    /// Sends the final image and waits for the sender (whose writes time out).
    pub fn finish(mut self, img: Vec<f32>) {
        self.put(img);
        self.mailbox.0.lock().unwrap().closed = true;
        self.mailbox.1.notify_one();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

fn send_loop(
    m: &(Mutex<Mailbox>, Condvar),
    addr: &str,
    name: &str,
    width: u32,
    height: u32,
) -> std::io::Result<()> {
    let sock = addr
        .to_socket_addrs()?
        .next()
        .ok_or_else(|| std::io::Error::other("no address"))?;
    let mut s = TcpStream::connect_timeout(&sock, Duration::from_secs(2))?;
    s.set_write_timeout(Some(Duration::from_secs(5)))?;
    s.set_nodelay(true)?;
    s.write_all(&create_image(name, width, height))?;
    let mut sent: Option<Vec<f32>> = None;
    loop {
        let (frame, closed) = {
            let mut g = m.0.lock().unwrap();
            while g.frame.is_none() && !g.closed {
                g = m.1.wait(g).unwrap();
            }
            (g.frame.take(), g.closed)
        };
        if let Some(f) = frame {
            for p in changed_tiles(sent.as_deref(), &f, name, width, height) {
                s.write_all(&p)?;
            }
            sent = Some(f);
        }
        if closed {
            return s.flush();
        }
    }
}

fn packet(ty: u8, body: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut p = vec![0, 0, 0, 0, ty];
    body(&mut p);
    let n = p.len() as u32;
    p[..4].copy_from_slice(&n.to_le_bytes());
    p
}

fn put_str(p: &mut Vec<u8>, s: &str) {
    p.extend(s.bytes().filter(|&b| b != 0));
    p.push(0);
}

pub fn create_image(name: &str, width: u32, height: u32) -> Vec<u8> {
    packet(4, |p| {
        p.push(0); // grab focus: no
        put_str(p, name);
        for v in [width as i32, height as i32, CHANNELS.len() as i32] {
            p.extend_from_slice(&v.to_le_bytes());
        }
        for c in CHANNELS {
            put_str(p, c);
        }
    })
}

/// UpdateImage packets (one per channel) for every tile that differs from
/// `old` (all tiles without one).
fn changed_tiles(old: Option<&[f32]>, img: &[f32], name: &str, w: u32, h: u32) -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    for ty in (0..h).step_by(TILE as usize) {
        for tx in (0..w).step_by(TILE as usize) {
            let (tw, th) = (TILE.min(w - tx), TILE.min(h - ty));
            let rows = (ty..ty + th).map(|y| {
                let i = 3 * (y * w + tx) as usize;
                i..i + 3 * tw as usize
            });
            if let Some(old) = old {
                if rows.clone().all(|r| old[r.clone()] == img[r]) {
                    continue;
                }
            }
            for (c, cname) in CHANNELS.iter().enumerate() {
                out.push(packet(3, |p| {
                    p.push(0);
                    put_str(p, name);
                    put_str(p, cname);
                    for v in [tx, ty, tw, th] {
                        p.extend_from_slice(&(v as i32).to_le_bytes());
                    }
                    for r in rows.clone() {
                        for px in img[r].chunks_exact(3) {
                            p.extend_from_slice(&px[c].to_le_bytes());
                        }
                    }
                }));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_changed_tiles_are_sent() {
        let (w, h) = (200, 130);
        let mut img = vec![0.5f32; (3 * w * h) as usize];
        // 2 x 2 tiles, 3 channels each.
        assert_eq!(changed_tiles(None, &img, "a", w, h).len(), 12);
        let old = img.clone();
        img[3 * (129 * w + 150) as usize + 1] = 2.0; // bottom-right tile
        let p = changed_tiles(Some(&old), &img, "a", w, h);
        assert_eq!(p.len(), 3);
        // Header of the first: length, type 3, focus 0, "a\0", "R\0", x=128, y=128, 72 x 2.
        assert_eq!(
            u32::from_le_bytes(p[0][..4].try_into().unwrap()) as usize,
            p[0].len()
        );
        assert_eq!(&p[0][4..10], &[3, 0, b'a', 0, b'R', 0]);
        let ints: Vec<i32> = p[0][10..26]
            .chunks(4)
            .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(ints, [128, 128, 72, 2]);
        assert_eq!(p[0].len(), 26 + 4 * 72 * 2);
    }
}
