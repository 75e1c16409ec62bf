//! Film: per-pixel running mean and variance (Welford), pixel bounds, the
//! film size limit, and pixel filters applied by importance sampling so
//! each sample touches only its own pixel (which keeps images independent
//! of thread count).

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

/// Running statistics of one pixel.
#[derive(Clone, Copy, Debug, Default)]
pub struct Pixel {
    pub n: u64,
    pub mean: [f64; 3],
    pub m2: [f64; 3],
}

impl Pixel {
    #[inline]
    pub fn add(&mut self, c: Rgb) {
        self.n += 1;
        let inv = 1.0 / self.n as f64;
        for (i, v) in [c.r, c.g, c.b].into_iter().enumerate() {
            let v = v as f64;
            let d = v - self.mean[i];
            self.mean[i] += d * inv;
            self.m2[i] += d * (v - self.mean[i]);
        }
    }

    pub fn mean_rgb(&self) -> Rgb {
        Rgb::new(
            self.mean[0] as f32,
            self.mean[1] as f32,
            self.mean[2] as f32,
        )
    }

    /// Variance of the pixel mean (sample variance / n).
    pub fn variance_of_mean(&self) -> Rgb {
        if self.n < 2 {
            return Rgb::BLACK;
        }
        let d = (self.n - 1) as f64 * self.n as f64;
        Rgb::new(
            (self.m2[0] / d) as f32,
            (self.m2[1] / d) as f32,
            (self.m2[2] / d) as f32,
        )
    }
}

#[derive(Clone, Debug)]
pub struct Film {
    pub full_resolution: (u32, u32),
    pub bounds: PixelBounds,
    pub pixels: Vec<Pixel>,
    /// Sums of contributions splatted to pixels other than their sample's
    /// (light tracing, bidirectional connections), one RGB per pixel; empty
    /// until the first splat. They enter the image divided by
    /// `splat_samples`, the samples per pixel taken (pbrt-v4's rule).
    pub splats: Vec<[f64; 3]>,
    pub splat_samples: u32,
}

impl Film {
    pub fn new(full_resolution: (u32, u32), bounds: PixelBounds) -> Film {
        Film {
            full_resolution,
            bounds,
            pixels: vec![Pixel::default(); bounds.area() as usize],
            splats: Vec::new(),
            splat_samples: 0,
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
            self.splats = vec![[0.0; 3]; self.pixels.len()];
        }
        let s = &mut self.splats[((y - b.y0) * b.width() + (x - b.x0)) as usize];
        for (a, v) in s.iter_mut().zip([c.r, c.g, c.b]) {
            *a += v as f64;
        }
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
        let mut img: Vec<f32> = self
            .pixels
            .iter()
            .flat_map(|p| p.mean_rgb().to_array())
            .collect();
        if !self.splats.is_empty() {
            let inv = 1.0 / self.splat_samples.max(1) as f64;
            for (px, s) in img.chunks_exact_mut(3).zip(&self.splats) {
                for (v, a) in px.iter_mut().zip(s) {
                    *v = (*v as f64 + a * inv) as f32;
                }
            }
        }
        img
    }

    /// Variance-of-the-mean image, row-major RGB triples.
    pub fn variance_image(&self) -> Vec<f32> {
        self.pixels
            .iter()
            .flat_map(|p| p.variance_of_mean().to_array())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welford_matches_two_pass() {
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
}
