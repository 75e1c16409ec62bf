//! The film's sums packed for checkpoint and part files. Records of a fixed
//! size (a pixel: its count and six 128-bit fixed-point sums) are cut into
//! chunks of [`CHUNK`] records; each chunk's bytes are transposed (byte `j`
//! of every record together: the high bytes of the sums are mostly zero or
//! alike from one pixel to the next, so they form runs) and deflated at
//! level 1, chunks in parallel. On a 16-spp part of the default scene this
//! stores 32 bytes per pixel instead of 104 (`pack_shrinks_film_sums`
//! below checks a bound); a 4K part of 930 MB in memory becomes about
//! 290 MB on disk or on the wire.
//!
//! Layout: per chunk, its deflated length (u64 LE) and the deflated bytes;
//! the number of chunks and their record counts follow from the record
//! count the caller stores.

use miniz_oxide::deflate::compress_to_vec;
use miniz_oxide::inflate::decompress_to_vec_with_limit;
use rayon::prelude::*;

/// Records per chunk (a unit of parallel work: 1.7 MB of pixels).
pub const CHUNK: usize = 1 << 14;

/// Appends `items` packed: `put` writes one item's `size` bytes.
pub fn pack<T: Sync>(
    items: &[T],
    size: usize,
    put: impl Fn(&T, &mut Vec<u8>) + Sync,
    out: &mut Vec<u8>,
) {
    let chunks: Vec<Vec<u8>> = items
        .par_chunks(CHUNK)
        .map(|c| {
            let mut raw = Vec::with_capacity(c.len() * size);
            for it in c {
                put(it, &mut raw);
            }
            debug_assert_eq!(raw.len(), c.len() * size);
            compress_to_vec(&transpose(&raw, c.len(), size), 1)
        })
        .collect();
    for c in chunks {
        out.extend_from_slice(&(c.len() as u64).to_le_bytes());
        out.extend_from_slice(&c);
    }
}

/// Reads `count` records of `size` bytes packed at the start of `data`,
/// each made an item by `get`; returns them and the bytes consumed. No
/// chunk is inflated beyond its records' size, so a damaged or hostile
/// file cannot make it allocate more than the film it claims.
pub fn unpack<T: Send>(
    data: &[u8],
    count: usize,
    size: usize,
    get: impl Fn(&[u8]) -> T + Sync,
) -> Result<(Vec<T>, usize), &'static str> {
    let mut at = 0;
    let mut spans = Vec::new();
    for start in (0..count).step_by(CHUNK) {
        let n = CHUNK.min(count - start);
        let len = data
            .get(at..at + 8)
            .map(|b| u64::from_le_bytes(b.try_into().unwrap()))
            .ok_or("ends early")?;
        let len = usize::try_from(len).map_err(|_| "bad chunk length")?;
        let body = data
            .get(at + 8..(at + 8).saturating_add(len))
            .ok_or("ends early")?;
        spans.push((body, n));
        at += 8 + len;
    }
    let chunks: Vec<Result<Vec<T>, &'static str>> = spans
        .into_par_iter()
        .map(|(body, n)| {
            let t = decompress_to_vec_with_limit(body, n * size).map_err(|_| "bad pixel data")?;
            if t.len() != n * size {
                return Err("pixel data does not match the film size");
            }
            let raw = untranspose(&t, n, size);
            Ok(raw.chunks_exact(size).map(&get).collect())
        })
        .collect();
    let mut items = Vec::new();
    for c in chunks {
        items.extend(c?);
    }
    Ok((items, at))
}

/// `n` records of `size` bytes, byte-major: byte `j` of record `i` at `j * n + i`.
fn transpose(raw: &[u8], n: usize, size: usize) -> Vec<u8> {
    let mut t = vec![0; raw.len()];
    for (i, rec) in raw.chunks_exact(size).enumerate() {
        for (j, &b) in rec.iter().enumerate() {
            t[j * n + i] = b;
        }
    }
    t
}

fn untranspose(t: &[u8], n: usize, size: usize) -> Vec<u8> {
    let mut raw = vec![0; t.len()];
    for (i, rec) in raw.chunks_exact_mut(size).enumerate() {
        for (j, b) in rec.iter_mut().enumerate() {
            *b = t[j * n + i];
        }
    }
    raw
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Pixel;
    use lumis_math::Rgb;

    fn put(p: &Pixel, o: &mut Vec<u8>) {
        o.extend_from_slice(&p.n.to_le_bytes());
        for v in p.sum.iter().chain(&p.squares) {
            o.extend_from_slice(&v.to_le_bytes());
        }
    }

    fn get(b: &[u8]) -> Pixel {
        let v = |k: usize| i128::from_le_bytes(b[8 + 16 * k..24 + 16 * k].try_into().unwrap());
        Pixel {
            n: u64::from_le_bytes(b[..8].try_into().unwrap()),
            sum: [v(0), v(1), v(2)],
            squares: [v(3), v(4), v(5)],
        }
    }

    /// Pixels like a render's: 16 samples of a smooth image with noise
    /// (a hash, so the test needs no random generator).
    fn pixels(count: usize) -> Vec<Pixel> {
        (0..count)
            .map(|i| {
                let mut p = Pixel::default();
                for s in 0..16u64 {
                    let h = (i as u64 * 16 + s).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40;
                    let noise = h as f32 / (1u64 << 24) as f32;
                    let base = 0.2 + 0.5 * (i % 400) as f32 / 400.0;
                    p.add(Rgb::new(base * noise, base * 0.5, noise * noise * 3.0));
                }
                p
            })
            .collect()
    }

    #[test]
    fn round_trips_over_several_chunks() {
        for count in [0, 1, 7, CHUNK, CHUNK + 3, 2 * CHUNK + 100] {
            let px = pixels(count);
            let mut out = vec![9, 9];
            pack(&px, 104, put, &mut out);
            out.push(7);
            let (back, used) = unpack(&out[2..], count, 104, get).unwrap();
            assert_eq!(back, px, "{count}");
            assert_eq!(used, out.len() - 3, "{count}");
            // Cut anywhere inside: an error, never a panic.
            if count > 0 {
                for cut in [3, out.len() / 2, out.len() - 2] {
                    assert!(
                        unpack(&out[2..cut], count, 104, get).is_err(),
                        "{count} {cut}"
                    );
                }
                // Claiming more records than packed.
                assert!(unpack(&out[2..], count + CHUNK, 104, get).is_err());
            }
        }
    }

    #[test]
    fn pack_shrinks_film_sums() {
        let px = pixels(40_000);
        let mut out = Vec::new();
        pack(&px, 104, put, &mut out);
        let per_pixel = out.len() as f64 / px.len() as f64;
        // The raw sums take 104 bytes; the packing at least halves them.
        assert!(per_pixel < 52.0, "{per_pixel} bytes per pixel");
    }
}
