//! Textured area emitters: pbrt-v4's `DiffuseAreaLight` with an image. The
//! radiance at a surface point is the image bilinearly interpolated at the
//! point's `(u, 1 - v)` (clamped at the borders), times the light's `scale`.
//!
//! Each primitive of the light carries a piecewise-constant density over
//! the unit square of its area-preserving map (`geometry/square_map.rs`),
//! proportional to the luminance of the emitted radiance: points (for light
//! sampling and for photons) are chosen by importance, so photons leave
//! with nearly equal power (exactly `L / pdf`, hence unbiased; equal up to
//! the variation of the bilinear image inside one cell). The same cell
//! averages give the primitive's mean radiance, so the light's power is the
//! integral of the image over the surface (a midpoint rule with at least
//! six points per texel along each direction, and 8x8 per cell), not the
//! image's mean.

use crate::geometry::square_map::square_to_surface;
use crate::geometry::{Prim, Shapes};
use crate::texture::mipmap::{Level, WrapMode};
use lumis_math::sampling::PiecewiseConstant2D;
use lumis_math::{Rgb, Vec2};
use std::sync::Arc;

/// Most cells along each side of a primitive's square.
const MAX_CELLS: usize = 64;
/// Most sample points along each side of one cell.
const MAX_POINTS: usize = 16;
/// Fewest sample points along each side of the whole square.
const MIN_POINTS: usize = 64;
/// Every cell keeps this fraction of the mean cell weight, so a point whose
/// radiance the cell average missed can still be sampled (unbiasedness).
const FLOOR: f32 = 1e-3;

/// An area light's image: linear RGB, negative values clamped to zero.
#[derive(Clone, Debug)]
pub struct EmissionImage {
    level: Level,
}

impl EmissionImage {
    pub fn new(mut level: Level) -> EmissionImage {
        level
            .texels
            .iter_mut()
            .for_each(|t| *t = t.map(|c| c.max(0.0)));
        EmissionImage { level }
    }

    /// Radiance (before `scale`) at surface parameters `uv`: pbrt-v4 flips `v`
    /// (row 0 is the image's top) and interpolates bilinearly, clamping.
    #[inline]
    pub fn lookup(&self, uv: Vec2) -> Rgb {
        self.level
            .bilerp(Vec2::new(uv.x, 1.0 - uv.y), WrapMode::Clamp)
    }

    pub fn size(&self) -> (u32, u32) {
        (self.level.width, self.level.height)
    }
}

/// One primitive's share of a textured light.
#[derive(Clone, Debug)]
pub struct TexturedEmission {
    pub image: Arc<EmissionImage>,
    /// Over the primitive's square; `None`: uniform (one cell).
    dist: Option<PiecewiseConstant2D>,
    /// `∫ L dA / A` over the primitive, before `scale`.
    pub mean: Rgb,
}

impl TexturedEmission {
    /// The primitive's density with about `cells_per_texel` cells along each
    /// side of a texel it covers (at most 64 x 64 cells), and its mean
    /// radiance by a midpoint rule of at least 64 points along each side of
    /// its square and six per texel.
    pub fn build(
        image: Arc<EmissionImage>,
        shapes: &Shapes,
        prim: Prim,
        cells_per_texel: f32,
    ) -> TexturedEmission {
        let (w, h) = image.size();
        let texels = texel_coverage(&image, shapes, prim);
        let n = ((cells_per_texel * texels.sqrt()).ceil() as usize).clamp(1, MAX_CELLS);
        let k_min = MIN_POINTS.div_ceil(n).max(2);
        let at = |x: f32, y: f32| square_to_surface(shapes, prim, Vec2::new(x, y)).uv;
        // Surface uv at the grid's corners, to size each cell's quadrature.
        let corners: Vec<Vec2> = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (i, j)))
            .map(|(i, j)| at(i as f32 / n as f32, j as f32 / n as f32))
            .collect();
        let mut avg = vec![Rgb::BLACK; n * n];
        for j in 0..n {
            for i in 0..n {
                let c = [
                    corners[j * (n + 1) + i],
                    corners[j * (n + 1) + i + 1],
                    corners[(j + 1) * (n + 1) + i],
                    corners[(j + 1) * (n + 1) + i + 1],
                ];
                let (lo, hi) = c
                    .iter()
                    .fold((c[0], c[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
                let extent = ((hi.x - lo.x) * w as f32).max((hi.y - lo.y) * h as f32);
                let k = ((6.0 * extent).ceil() as usize).clamp(k_min, MAX_POINTS.max(k_min));
                let mut sum = Rgb::BLACK;
                for b in 0..k {
                    for a in 0..k {
                        let x = (i as f32 + (a as f32 + 0.5) / k as f32) / n as f32;
                        let y = (j as f32 + (b as f32 + 0.5) / k as f32) / n as f32;
                        sum += image.lookup(at(x, y));
                    }
                }
                avg[j * n + i] = sum / (k * k) as f32;
            }
        }
        let mean = avg.iter().fold(Rgb::BLACK, |s, &a| s + a) / (n * n) as f32;
        let mut weights: Vec<f32> = avg.iter().map(|a| a.luminance().max(0.0)).collect();
        let mean_w = weights.iter().sum::<f32>() / weights.len() as f32;
        let dist = (n > 1 && mean_w > 0.0).then(|| {
            weights.iter_mut().for_each(|x| *x += FLOOR * mean_w);
            PiecewiseConstant2D::new(&weights, n, n)
        });
        TexturedEmission { image, dist, mean }
    }

    /// Radiance before `scale` at surface parameters `uv`.
    #[inline]
    pub fn l(&self, uv: Vec2) -> Rgb {
        self.image.lookup(uv)
    }

    /// A point of the square and its density there.
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        match &self.dist {
            None => (u, 1.0),
            Some(d) => {
                let (x, pdf, _) = d.sample(u);
                (x, pdf)
            }
        }
    }

    /// Density of [`TexturedEmission::sample`] at square coordinates `x`.
    pub fn pdf(&self, x: Vec2) -> f32 {
        match &self.dist {
            None => 1.0,
            Some(d) => d.pdf(x),
        }
    }

    /// Cells along each side of the square (1: uniform sampling).
    pub fn resolution(&self) -> usize {
        self.dist.as_ref().map_or(1, |d| d.resolution().0)
    }
}

/// Texels of the image the primitive covers: its footprint's area in uv
/// space (pbrt's default uvs for triangles without them; the unit square for
/// quadrics) times the image's resolution.
pub fn texel_coverage(image: &EmissionImage, shapes: &Shapes, prim: Prim) -> f32 {
    let (w, h) = image.size();
    shapes.uv_area(prim) * w as f32 * h as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::TriangleMesh;
    use lumis_math::Vec3;

    /// A unit quad in z = 0 with uv = (x, y): two triangles.
    fn quad() -> Shapes {
        Shapes {
            meshes: vec![TriangleMesh {
                positions: vec![
                    Vec3::new(0.0, 0.0, 0.0),
                    Vec3::new(1.0, 0.0, 0.0),
                    Vec3::new(1.0, 1.0, 0.0),
                    Vec3::new(0.0, 1.0, 0.0),
                ],
                uvs: Some(vec![
                    Vec2::new(0.0, 0.0),
                    Vec2::new(1.0, 0.0),
                    Vec2::new(1.0, 1.0),
                    Vec2::new(0.0, 1.0),
                ]),
                indices: vec![0, 1, 2, 0, 2, 3],
                ..Default::default()
            }],
            ..Default::default()
        }
    }

    fn two_texels(a: Rgb, b: Rgb) -> Arc<EmissionImage> {
        Arc::new(EmissionImage::new(Level {
            width: 2,
            height: 1,
            texels: vec![a, b],
        }))
    }

    #[test]
    fn lookup_flips_v_and_interpolates_bilinearly() {
        let img = EmissionImage::new(Level {
            width: 1,
            height: 2,
            // Top row 1, bottom row 3.
            texels: vec![Rgb::splat(1.0), Rgb::splat(3.0)],
        });
        assert_eq!(img.lookup(Vec2::new(0.5, 1.0)).g, 1.0); // v = 1: top
        assert_eq!(img.lookup(Vec2::new(0.5, 0.0)).g, 3.0); // v = 0: bottom
        assert!((img.lookup(Vec2::new(0.2, 0.5)).g - 2.0).abs() < 1e-6);
        assert!((img.lookup(Vec2::new(0.2, 0.625)).g - 1.5).abs() < 1e-6);
        let neg = EmissionImage::new(Level {
            width: 1,
            height: 1,
            texels: vec![Rgb::new(-1.0, 2.0, 0.0)],
        });
        assert_eq!(neg.lookup(Vec2::ZERO), Rgb::new(0.0, 2.0, 0.0));
    }

    /// Each triangle of the quad covers half the uv square: the mean over the
    /// lower-right triangle (x > y) of the clamped ramp of a 2x1 image.
    #[test]
    fn mean_is_the_integral_over_the_primitive() {
        let s = quad();
        let (a, b) = (1.0f64, 9.0f64);
        let img = two_texels(Rgb::splat(a as f32), Rgb::splat(b as f32));
        // L(x) = a for x < 1/4, b for x > 3/4, linear between; triangle 0 is
        // {y < x}: weight of column x is x (its height), total 1/2.
        let l = |x: f64| a + (b - a) * ((x - 0.25) / 0.5).clamp(0.0, 1.0);
        let m = 200_000;
        let (mut num, mut num2) = (0.0, 0.0);
        for i in 0..m {
            let x = (i as f64 + 0.5) / m as f64;
            num += l(x) * x / m as f64;
            num2 += l(x) * (1.0 - x) / m as f64;
        }
        for (tri, expected) in [(0, num / 0.5), (1, num2 / 0.5)] {
            let t = TexturedEmission::build(img.clone(), &s, Prim::Triangle { mesh: 0, tri }, 4.0);
            let got = t.mean.g as f64;
            eprintln!("triangle {tri}: mean {got} expected {expected}");
            assert!(
                (got / expected - 1.0).abs() < 5e-4,
                "triangle {tri}: mean {got} expected {expected}"
            );
        }
    }

    #[test]
    fn sampling_density_integrates_to_one_and_matches_pdf() {
        let s = quad();
        let img = two_texels(Rgb::splat(0.5), Rgb::new(4.0, 1.0, 8.0));
        let t = TexturedEmission::build(img, &s, Prim::Triangle { mesh: 0, tri: 0 }, 4.0);
        assert!(t.resolution() > 1);
        let n = 100 * t.resolution();
        let mut total = 0.0f64;
        for j in 0..n {
            for i in 0..n {
                let x = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                total += t.pdf(x) as f64 / (n * n) as f64;
            }
        }
        assert!((total - 1.0).abs() < 1e-4, "integral {total}");
        let mut rng = lumis_math::Pcg32::new(5, 5);
        for _ in 0..1000 {
            let (x, pdf) = t.sample(Vec2::new(rng.next_f32(), rng.next_f32()));
            assert!((pdf / t.pdf(x) - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn black_primitives_have_no_distribution_and_no_power() {
        let s = quad();
        let t = TexturedEmission::build(
            two_texels(Rgb::BLACK, Rgb::BLACK),
            &s,
            Prim::Triangle { mesh: 0, tri: 1 },
            4.0,
        );
        assert_eq!(t.mean, Rgb::BLACK);
        assert_eq!(t.resolution(), 1);
        assert_eq!(t.pdf(Vec2::splat(0.3)), 1.0);
    }
}
