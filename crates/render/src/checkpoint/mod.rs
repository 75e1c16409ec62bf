//! Checkpoints: a render's job and accumulated state (per-pixel fixed-point
//! sums, splats, sample counts, the integrator's own state as opaque
//! bytes, dropped-sample counts) in a small binary file, written atomically,
//! so a render can be continued exactly where it stopped. Photon maps are
//! not stored: they are rebuilt from the seed, which reproduces them bit for
//! bit.
//!
//! Layout (little-endian): magic `LUMISCKP`, format version (u32), lumis
//! version (string), scene hash (u64), the job (a string: the session's
//! serialized `RenderJob`), the state (the film's pixel and splat sums
//! packed by `pack.rs`), then an FNV-1a hash of everything before it
//! (catches truncated or damaged files). Partial renders' parts
//! (`session::merge`) are checkpoints of their pass range.

mod pack;

use crate::film::{Film, Pixel, PixelBounds};
use crate::integrator::{BadSample, RenderState};
use std::path::Path;
use std::time::Duration;

const MAGIC: &[u8; 8] = b"LUMISCKP";
/// Bumped whenever the layout changes.
pub const FORMAT_VERSION: u32 = 4;
/// Bytes per saved pixel before packing (`pack.rs`): n, then the
/// fixed-point sums and sums of squares.
const PIXEL_BYTES: usize = 8 + 6 * 16;
/// Bytes per pixel of splat sums.
const SPLAT_BYTES: usize = 3 * 16;

#[derive(Clone, Debug)]
pub struct Checkpoint {
    /// The lumis version that wrote it; others refuse it (sampling may differ).
    pub lumis_version: String,
    /// Hash of every input file and every setting that changes the image.
    pub scene_hash: u64,
    /// The render job, serialized by the session (JSON).
    pub job: String,
    pub state: RenderState,
}

#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    #[error("{0}: {1}")]
    Io(String, std::io::Error),
    #[error("{0}: not a lumis checkpoint")]
    NotCheckpoint(String),
    #[error("{path}: checkpoint format {found}, this lumis reads format {FORMAT_VERSION}; finish it with the lumis that wrote it")]
    Format { path: String, found: u32 },
    #[error("{path}: checkpoint written by lumis {found}, this is lumis {expected}; sampling may differ, so it cannot be resumed exactly (use lumis {found})")]
    Version {
        path: String,
        found: String,
        expected: String,
    },
    #[error("{0}: checkpoint is truncated or damaged ({1})")]
    Damaged(String, &'static str),
}

/// FNV-1a, 64-bit: a stable hash (std's hashers may change between releases).
#[derive(Clone, Copy, Debug)]
pub struct Fnv(pub u64);

impl Default for Fnv {
    fn default() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    pub fn write(&mut self, bytes: &[u8]) -> &mut Fnv {
        for &b in bytes {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x100_0000_01b3);
        }
        self
    }
    /// A length-prefixed string, so ("ab","c") and ("a","bc") differ.
    pub fn write_str(&mut self, s: &str) -> &mut Fnv {
        self.write(&(s.len() as u64).to_le_bytes())
            .write(s.as_bytes())
    }
}

impl Checkpoint {
    pub fn encode(&self) -> Vec<u8> {
        self.encode_with(&self.state)
    }

    /// Encodes this checkpoint's header with `st` in place of its state
    /// (saves a copy of the film while rendering).
    pub fn encode_with(&self, st: &RenderState) -> Vec<u8> {
        let mut o = Vec::with_capacity(256 + st.film.pixels.len() * PIXEL_BYTES);
        o.extend_from_slice(MAGIC);
        o.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        put_str(&mut o, &self.lumis_version);
        o.extend_from_slice(&self.scene_hash.to_le_bytes());
        put_str(&mut o, &self.job);
        o.extend_from_slice(&st.spp_done.to_le_bytes());
        o.extend_from_slice(&(st.integrator.len() as u32).to_le_bytes());
        o.extend_from_slice(&st.integrator);
        o.extend_from_slice(&st.bad_samples.to_le_bytes());
        let fb = st.first_bad.map_or([u32::MAX; 3], |b| [b.x, b.y, b.sample]);
        for v in fb {
            o.extend_from_slice(&v.to_le_bytes());
        }
        o.extend_from_slice(&st.rays.to_le_bytes());
        o.extend_from_slice(&(st.elapsed.as_nanos() as u64).to_le_bytes());
        let f = &st.film;
        let b = f.bounds;
        for v in [
            f.full_resolution.0,
            f.full_resolution.1,
            b.x0,
            b.x1,
            b.y0,
            b.y1,
        ] {
            o.extend_from_slice(&v.to_le_bytes());
        }
        o.extend_from_slice(&f.splat_samples.to_le_bytes());
        // Bit 0: light splats; bit 1: a splatting filter's weights.
        o.push(!f.splats.is_empty() as u8 | (!f.weights.is_empty() as u8) << 1);
        pack::pack(&f.pixels, PIXEL_BYTES, put_pixel, &mut o);
        pack::pack(&f.splats, SPLAT_BYTES, put_splat, &mut o);
        pack::pack(
            &f.weights,
            16,
            |w, o| o.extend_from_slice(&w.to_le_bytes()),
            &mut o,
        );
        let h = Fnv::default().write(&o).0;
        o.extend_from_slice(&h.to_le_bytes());
        o
    }

    /// Reads a checkpoint; `name` labels errors. Sizes are checked against
    /// the data present before anything is allocated.
    pub fn decode(bytes: &[u8], name: &str) -> Result<Checkpoint, CheckpointError> {
        let damaged = |what| CheckpointError::Damaged(name.to_string(), what);
        if bytes.len() < 12 || &bytes[..8] != MAGIC {
            return Err(CheckpointError::NotCheckpoint(name.to_string()));
        }
        let mut r = Reader {
            b: bytes,
            at: 8,
            name,
        };
        let format = r.u32()?;
        if format != FORMAT_VERSION {
            return Err(CheckpointError::Format {
                path: name.to_string(),
                found: format,
            });
        }
        let lumis_version = r.string()?;
        if lumis_version != env!("CARGO_PKG_VERSION") {
            return Err(CheckpointError::Version {
                path: name.to_string(),
                found: lumis_version,
                expected: env!("CARGO_PKG_VERSION").to_string(),
            });
        }
        let (body, tail) = bytes.split_at(bytes.len() - 8);
        if Fnv::default().write(body).0 != u64::from_le_bytes(tail.try_into().unwrap()) {
            return Err(damaged("checksum mismatch"));
        }
        r.b = body;
        let scene_hash = r.u64()?;
        let job = r.string()?;
        let spp_done = r.u32()?;
        let n_state = r.u32()? as usize;
        let integrator = r.take(n_state)?.to_vec();
        let bad_samples = r.u64()?;
        let fb = [r.u32()?, r.u32()?, r.u32()?];
        let first_bad = (fb != [u32::MAX; 3]).then_some(BadSample {
            x: fb[0],
            y: fb[1],
            sample: fb[2],
        });
        let rays = r.u64()?;
        let elapsed = Duration::from_nanos(r.u64()?);
        let full = (r.u32()?, r.u32()?);
        let bounds = PixelBounds {
            x0: r.u32()?,
            x1: r.u32()?,
            y0: r.u32()?,
            y1: r.u32()?,
        };
        if bounds.x0 >= bounds.x1
            || bounds.y0 >= bounds.y1
            || bounds.x1 > full.0
            || bounds.y1 > full.1
        {
            return Err(damaged("bad film bounds"));
        }
        let splat_samples = r.u32()?;
        let parts = r.take(1)?[0];
        if parts > 3 {
            return Err(damaged("unknown film parts"));
        }
        let (has_splats, has_weights) = (parts & 1 != 0, parts & 2 != 0);
        if bounds.area() > crate::film::MAX_PIXELS {
            return Err(damaged("bad film bounds"));
        }
        let area = bounds.area() as usize;
        let rest = &r.b[r.at..];
        let (pixels, used) = pack::unpack(rest, area, PIXEL_BYTES, get_pixel).map_err(damaged)?;
        let splat_count = if has_splats { area } else { 0 };
        let (splats, used2) =
            pack::unpack(&rest[used..], splat_count, SPLAT_BYTES, get_splat).map_err(damaged)?;
        let weight_count = if has_weights { area } else { 0 };
        let (weights, used3) =
            pack::unpack(&rest[used + used2..], weight_count, 16, |b| i128_at(b, 0))
                .map_err(damaged)?;
        if used + used2 + used3 != rest.len() {
            return Err(damaged("pixel data does not match the film size"));
        }
        Ok(Checkpoint {
            lumis_version,
            scene_hash,
            job,
            state: RenderState {
                film: Film {
                    full_resolution: full,
                    bounds,
                    pixels,
                    splats,
                    splat_samples,
                    weights,
                },
                spp_done,
                integrator,
                bad_samples,
                first_bad,
                rays,
                elapsed,
            },
        })
    }

    /// Writes to a temporary file in the same folder, then renames: a crash
    /// mid-write leaves the previous checkpoint intact.
    pub fn save(&self, path: &Path) -> Result<(), CheckpointError> {
        self.save_with(&self.state, path)
    }

    /// [`Checkpoint::save`] with `state` in place of this checkpoint's state.
    pub fn save_with(&self, state: &RenderState, path: &Path) -> Result<(), CheckpointError> {
        let io = |e| CheckpointError::Io(path.display().to_string(), e);
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_default();
        let tmp = path.with_file_name(format!(".{name}.tmp{}", std::process::id()));
        if let Err(e) = std::fs::write(&tmp, self.encode_with(state)) {
            let _ = std::fs::remove_file(&tmp);
            return Err(io(e));
        }
        std::fs::rename(&tmp, path).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            io(e)
        })
    }

    pub fn load(path: &Path) -> Result<Checkpoint, CheckpointError> {
        let bytes =
            std::fs::read(path).map_err(|e| CheckpointError::Io(path.display().to_string(), e))?;
        Checkpoint::decode(&bytes, &path.display().to_string())
    }
}

fn put_pixel(p: &Pixel, o: &mut Vec<u8>) {
    o.extend_from_slice(&p.n.to_le_bytes());
    for v in p.sum.iter().chain(&p.squares) {
        o.extend_from_slice(&v.to_le_bytes());
    }
}

fn put_splat(s: &[i128; 3], o: &mut Vec<u8>) {
    for v in s {
        o.extend_from_slice(&v.to_le_bytes());
    }
}

fn i128_at(b: &[u8], at: usize) -> i128 {
    i128::from_le_bytes(b[at..at + 16].try_into().expect("16 bytes"))
}

fn get_pixel(b: &[u8]) -> Pixel {
    Pixel {
        n: u64::from_le_bytes(b[..8].try_into().expect("8 bytes")),
        sum: [i128_at(b, 8), i128_at(b, 24), i128_at(b, 40)],
        squares: [i128_at(b, 56), i128_at(b, 72), i128_at(b, 88)],
    }
}

fn get_splat(b: &[u8]) -> [i128; 3] {
    [i128_at(b, 0), i128_at(b, 16), i128_at(b, 32)]
}

fn put_str(o: &mut Vec<u8>, s: &str) {
    o.extend_from_slice(&(s.len() as u32).to_le_bytes());
    o.extend_from_slice(s.as_bytes());
}

struct Reader<'a> {
    b: &'a [u8],
    at: usize,
    name: &'a str,
}

impl Reader<'_> {
    fn left(&self) -> usize {
        self.b.len().saturating_sub(self.at)
    }
    fn take(&mut self, n: usize) -> Result<&[u8], CheckpointError> {
        if self.left() < n {
            return Err(CheckpointError::Damaged(
                self.name.to_string(),
                "ends early",
            ));
        }
        self.at += n;
        Ok(&self.b[self.at - n..self.at])
    }
    fn u32(&mut self) -> Result<u32, CheckpointError> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().unwrap()))
    }
    fn u64(&mut self) -> Result<u64, CheckpointError> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().unwrap()))
    }
    fn string(&mut self) -> Result<String, CheckpointError> {
        let n = self.u32()? as usize;
        let b = self.take(n)?;
        String::from_utf8(b.to_vec())
            .map_err(|_| CheckpointError::Damaged(self.name.to_string(), "bad text"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::Rgb;

    fn sample() -> Checkpoint {
        let bounds = PixelBounds {
            x0: 1,
            x1: 4,
            y0: 0,
            y1: 2,
        };
        let mut film = Film::new((5, 2), bounds);
        for (i, p) in film.pixels.iter_mut().enumerate() {
            p.add(Rgb::new(i as f32, 0.1, 1e-30));
            p.add(Rgb::new(0.3, i as f32 * 7.0, 2.0));
        }
        film.add_splat(2, 1, Rgb::new(0.5, 1e-20, 3.0));
        film.splat_samples = 2;
        Checkpoint {
            lumis_version: env!("CARGO_PKG_VERSION").into(),
            scene_hash: 42,
            job: r#"{"scene": "a b.pbrt"}"#.into(),
            state: RenderState {
                film,
                spp_done: 2,
                integrator: vec![1, 2, 3, 4],
                bad_samples: 3,
                first_bad: Some(BadSample {
                    sample: 1,
                    y: 0,
                    x: 2,
                }),
                rays: 1234,
                elapsed: Duration::from_millis(1500),
            },
        }
    }

    #[test]
    fn a_splatting_films_weights_round_trip() {
        let mut c = sample();
        c.state.film.weights = (0..c.state.film.pixels.len() as i128)
            .map(|i| i << 70 | 5)
            .collect();
        let bytes = c.encode();
        let d = Checkpoint::decode(&bytes, "x").unwrap();
        assert_eq!(d.state.film.weights, c.state.film.weights);
        assert_eq!(d.state.film.splats, c.state.film.splats);
        assert_eq!(d.encode(), bytes);
        // Without weights the film has none after decoding.
        let plain = Checkpoint::decode(&sample().encode(), "x").unwrap();
        assert!(plain.state.film.weights.is_empty());
    }

    #[test]
    fn round_trips_bit_for_bit() {
        let c = sample();
        let bytes = c.encode();
        let d = Checkpoint::decode(&bytes, "x").unwrap();
        assert_eq!(d.encode(), bytes);
        assert_eq!(d.job, c.job);
        assert_eq!(d.state.integrator, c.state.integrator);
        assert_eq!(d.state.first_bad, c.state.first_bad);
        assert_eq!(d.state.film.splat_samples, 2);
        assert_eq!(d.state.film.splats, c.state.film.splats);
        assert_eq!(d.state.film.pixels, c.state.film.pixels);
    }

    #[test]
    fn damaged_truncated_and_foreign_files_are_refused() {
        let bytes = sample().encode();
        for cut in [0, 5, 11, 40, bytes.len() / 2, bytes.len() - 1] {
            assert!(Checkpoint::decode(&bytes[..cut], "x").is_err(), "cut {cut}");
        }
        let mut flipped = bytes.clone();
        let n = flipped.len();
        flipped[n - 20] ^= 1;
        let e = Checkpoint::decode(&flipped, "x").unwrap_err().to_string();
        assert!(e.contains("damaged"), "{e}");
        let mut other = sample();
        other.lumis_version = "0.0.1-other".into();
        let e = Checkpoint::decode(&other.encode(), "x")
            .unwrap_err()
            .to_string();
        assert!(e.contains("lumis 0.0.1-other"), "{e}");
        let mut fmt = bytes.clone();
        fmt[8] = 99;
        let e = Checkpoint::decode(&fmt, "x").unwrap_err().to_string();
        assert!(e.contains("format 99"), "{e}");
        let e = Checkpoint::decode(b"P6\n1 1\n255\n000", "x")
            .unwrap_err()
            .to_string();
        assert!(e.contains("not a lumis checkpoint"), "{e}");
    }
}
