//! Film: per-pixel sums of samples and of their squares in fixed point
//! (exact and associative, so renders split into parts merge to the same
//! bits), pixel bounds, the
//! film size limit, and pixel filters applied by importance sampling so
//! each sample touches only its own pixel, or by splatting with weights
//! summed per pixel (`weights`); in both, sums are exact, so images do not
//! depend on the thread count.

pub mod exact;
mod filter;
pub use filter::Filter;

use lumis_math::Rgb;

/// Most pixels a film (or an image file read) may have: absurd sizes are
/// refused before anything is allocated.
pub const MAX_PIXELS: u64 = 1 << 28;

/// Pixel bounds `[x0, x1) x [y0, y1)` in full-film raster coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelBounds {
    pub x0: u32,
    pub x1: u32,
    pub y0: u32,
    pub y1: u32,
}

impl PixelBounds {
    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }
    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }
    pub fn area(&self) -> u64 {
        self.width() as u64 * self.height() as u64
    }
}

/// Running sums of one pixel's samples, in fixed point (see [`exact`]):
/// integer sums are associative, so passes rendered anywhere, in any
/// split, add up to the same bits (partial renders and their merge).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pixel {
    pub n: u64,
    /// Sum of the samples, units of 2^-[`exact::SUM_BITS`].
    pub sum: [i128; 3],
    /// Sum of their squares, units of 2^-[`exact::SQUARE_BITS`].
    pub squares: [i128; 3],
}

impl Pixel {
    #[inline]
    pub fn add(&mut self, c: Rgb) {
        self.n += 1;
        for (i, v) in [c.r, c.g, c.b].into_iter().enumerate() {
            let v = v as f64;
            self.sum[i] = self.sum[i].wrapping_add(exact::sum_units(v));
            self.squares[i] = self.squares[i].wrapping_add(exact::square_units(v * v));
        }
    }

    /// Adds another pixel's sums (a partial render of other passes).
    pub fn merge(&mut self, o: &Pixel) {
        self.n += o.n;
        for i in 0..3 {
            self.sum[i] = self.sum[i].wrapping_add(o.sum[i]);
            self.squares[i] = self.squares[i].wrapping_add(o.squares[i]);
        }
    }

    /// The sample mean per channel (0 without samples). In a film with
    /// weights (a splatting filter) the samples are weighted sums and this
    /// is not the pixel's value: [`Film::mean_image`] is.
    pub fn mean(&self) -> [f64; 3] {
        let n = self.n.max(1) as f64;
        self.sum.map(|s| exact::sum_value(s) / n)
    }

    pub fn mean_rgb(&self) -> Rgb {
        let m = self.mean();
        Rgb::new(m[0] as f32, m[1] as f32, m[2] as f32)
    }

    /// Variance of the pixel mean (sample variance / n).
    pub fn variance_of_mean(&self) -> Rgb {
        if self.n < 2 {
            return Rgb::BLACK;
        }
        let n = self.n as f64;
        let v = |i: usize| {
            let s = exact::sum_value(self.sum[i]);
            let q = exact::square_value(self.squares[i]);
            ((q - s * s / n) / ((n - 1.0) * n)).max(0.0) as f32
        };
        Rgb::new(v(0), v(1), v(2))
    }
}

#[derive(Clone, Debug)]
pub struct Film {
    pub full_resolution: (u32, u32),
    pub bounds: PixelBounds,
    pub pixels: Vec<Pixel>,
    /// Sums of contributions splatted to pixels other than their sample's
    /// (light tracing, bidirectional connections), one RGB per pixel; empty
    /// until the first splat, in fixed point like the pixels' sums. They
    /// enter the image divided by `splat_samples`, the samples per pixel
    /// taken (pbrt-v4's rule).
    pub splats: Vec<[i128; 3]>,
    pub splat_samples: u32,
    /// With a splatting filter (`Filter::splat`): per pixel, the sum of the
    /// filter weights of the samples its sums hold (weighted samples, one
    /// per sample index: `integrator/splatted.rs`), in fixed point like
    /// them; the pixel's value is then its sum divided by this instead of
    /// by its count. Empty otherwise.
    pub weights: Vec<i128>,
}

impl Film {
    pub fn new(full_resolution: (u32, u32), bounds: PixelBounds) -> Film {
        Film {
            full_resolution,
            bounds,
            pixels: vec![Pixel::default(); bounds.area() as usize],
            splats: Vec::new(),
            splat_samples: 0,
            weights: Vec::new(),
        }
    }

    /// The film's size and bounds without its pixels (a placeholder).
    pub fn clone_header(&self) -> Film {
        Film {
            full_resolution: self.full_resolution,
            bounds: self.bounds,
            pixels: Vec::new(),
            splats: Vec::new(),
            splat_samples: self.splat_samples,
            weights: Vec::new(),
        }
    }

    /// Adds `c` to the splat sum of full-film pixel (x, y); outside the
    /// film's bounds it is dropped.
    pub fn add_splat(&mut self, x: u32, y: u32, c: Rgb) {
        let b = self.bounds;
        if x < b.x0 || x >= b.x1 || y < b.y0 || y >= b.y1 {
            return;
        }
        if self.splats.is_empty() {
            self.splats = vec![[0; 3]; self.pixels.len()];
        }
        let s = &mut self.splats[((y - b.y0) * b.width() + (x - b.x0)) as usize];
        for (a, v) in s.iter_mut().zip([c.r, c.g, c.b]) {
            *a = a.wrapping_add(exact::sum_units(v as f64));
        }
    }

    /// Adds the sums of `o`, a render of other passes of the same film
    /// (same resolution and bounds): the result does not depend on the
    /// order or grouping of the merges.
    pub fn merge(&mut self, o: &Film) -> Result<(), String> {
        if (self.full_resolution, self.bounds) != (o.full_resolution, o.bounds)
            || self.pixels.len() != o.pixels.len()
        {
            return Err(format!(
                "films differ: {:?} {:?} against {:?} {:?}",
                self.full_resolution, self.bounds, o.full_resolution, o.bounds
            ));
        }
        for (p, q) in self.pixels.iter_mut().zip(&o.pixels) {
            p.merge(q);
        }
        if !o.splats.is_empty() {
            if self.splats.is_empty() {
                self.splats = vec![[0; 3]; self.pixels.len()];
            }
            for (a, b) in self.splats.iter_mut().zip(&o.splats) {
                for (x, y) in a.iter_mut().zip(b) {
                    *x = x.wrapping_add(*y);
                }
            }
        }
        self.splat_samples += o.splat_samples;
        if !o.weights.is_empty() {
            self.weights.resize(self.pixels.len(), 0);
            for (a, b) in self.weights.iter_mut().zip(&o.weights) {
                *a = a.wrapping_add(*b);
            }
        }
        Ok(())
    }

    /// Bytes of the pixels' sums, the light splats and the weights.
    pub fn memory_bytes(&self) -> usize {
        self.pixels.len() * std::mem::size_of::<Pixel>()
            + self.splats.len() * std::mem::size_of::<[i128; 3]>()
            + self.weights.len() * std::mem::size_of::<i128>()
    }

    pub fn width(&self) -> u32 {
        self.bounds.width()
    }
    pub fn height(&self) -> u32 {
        self.bounds.height()
    }

    /// Mean image, row-major RGB triples: each pixel's sample mean, plus
    /// its splats divided by the samples per pixel.
    pub fn mean_image(&self) -> Vec<f32> {
        let mut img: Vec<f32> = if self.weights.is_empty() {
            self.pixels
                .iter()
                .flat_map(|p| p.mean_rgb().to_array())
                .collect()
        } else {
            // Splatted: weighted sums over the weights.
            self.pixels
                .iter()
                .zip(&self.weights)
                .flat_map(|(p, &w)| {
                    let w = exact::sum_value(w);
                    let inv = if w > 0.0 { 1.0 / w } else { 0.0 };
                    p.sum.map(|s| (exact::sum_value(s) * inv) as f32)
                })
                .collect()
        };
        if !self.splats.is_empty() {
            let inv = 1.0 / self.splat_samples.max(1) as f64;
            for (px, s) in img.chunks_exact_mut(3).zip(&self.splats) {
                for (v, a) in px.iter_mut().zip(s) {
                    *v = (*v as f64 + exact::sum_value(*a) * inv) as f32;
                }
            }
        }
        img
    }

    /// Variance-of-the-mean image, row-major RGB triples.
    /// Splatted, the weighted samples' variance scaled by the square of
    /// count over weight (as if each sample's weight were the mean weight).
    pub fn variance_image(&self) -> Vec<f32> {
        self.pixels
            .iter()
            .enumerate()
            .flat_map(|(i, p)| {
                let v = p.variance_of_mean();
                let scale = match self.weights.get(i) {
                    Some(&w) if w > 0 => (p.n as f64 / exact::sum_value(w)).powi(2) as f32,
                    Some(_) => 0.0,
                    None => 1.0,
                };
                (v * scale).to_array()
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_match_two_pass_statistics() {
        let vals = [1.0f32, 2.0, 4.0, 8.0, 3.0];
        let mut p = Pixel::default();
        for v in vals {
            p.add(Rgb::splat(v));
        }
        let mean = vals.iter().sum::<f32>() / 5.0;
        let var = vals.iter().map(|v| (v - mean).powi(2)).sum::<f32>() / 4.0;
        assert!((p.mean_rgb().r - mean).abs() < 1e-6);
        assert!((p.variance_of_mean().g - var / 5.0).abs() < 1e-5);
    }

    #[test]
    fn films_of_parts_merge_to_the_bits_of_one() {
        let b = PixelBounds {
            x0: 0,
            x1: 3,
            y0: 0,
            y1: 2,
        };
        let sample = |i: usize, s: usize| {
            let t = (i * 31 + s * 7) as f32;
            Rgb::new((t * 0.37).sin().abs() * 1e3, 1e-7 * t, (t * 0.1).cos())
        };
        let render = |passes: std::ops::Range<usize>| {
            let mut f = Film::new((3, 2), b);
            for s in passes.clone() {
                for (i, p) in f.pixels.iter_mut().enumerate() {
                    p.add(sample(i, s));
                }
                f.add_splat((s % 3) as u32, 1, sample(9, s));
            }
            f.splat_samples = passes.len() as u32;
            f
        };
        let whole = render(0..40);
        for cuts in [vec![0, 1, 40], vec![0, 13, 14, 40], vec![0, 39, 40]] {
            // Parts merged in reverse order, to show the order does not matter.
            let mut merged = Film::new((3, 2), b);
            for w in cuts.windows(2).rev() {
                merged.merge(&render(w[0]..w[1])).unwrap();
            }
            assert_eq!(merged.pixels, whole.pixels, "{cuts:?}");
            assert_eq!(merged.splats, whole.splats);
            assert_eq!(merged.mean_image(), whole.mean_image());
        }
        // A splatting filter's films: the weights merge like the sums, and
        // the image divides by them.
        let weighted = |passes: std::ops::Range<usize>| {
            let mut f = render(passes.clone());
            f.weights = (0..6)
                .map(|i| exact::sum_units(0.25 * (i + passes.len()) as f64))
                .collect();
            f
        };
        let mut merged = weighted(0..13);
        merged.merge(&weighted(13..40)).unwrap();
        let sums = whole.pixels[4].sum.map(exact::sum_value);
        let w = 0.25 * (4 + 13) as f64 + 0.25 * (4 + 27) as f64;
        for (c, s) in sums.iter().enumerate() {
            let own = (s * (1.0 / w)) as f32;
            let want = (own as f64 + exact::sum_value(whole.splats[4][c]) * (1.0 / 40.0)) as f32;
            assert_eq!(merged.mean_image()[12 + c], want);
        }
        let other = Film::new((4, 2), b);
        assert!(Film::new((3, 2), b).merge(&other).is_err());
    }
}
