//! Separable, non-negative pixel filters sampled by inverting a tabulated
//! 1D CDF. With filter importance sampling every sample has weight one;
//! a filter that splats (`splat`) instead weighs each sample into every
//! pixel it reaches (`integrator/splatted.rs`).

use lumis_math::Vec2;

const TABLE: usize = 256;

#[derive(Clone, Debug)]
pub struct Filter {
    pub name: &'static str,
    pub radius: Vec2,
    /// Reconstruct by splatting: camera samples uniform in their pixel,
    /// each added to every pixel within the radius with the filter's
    /// density there (Mitsuba's and pbrt-v3's reconstruction), instead of
    /// one sample per pixel at an offset drawn from the filter (pbrt-v4's).
    pub splat: bool,
    /// CDF of the 1D profile over [-1, 1] (in units of the radius), TABLE + 1 entries.
    cdf: Vec<f32>,
}

impl Filter {
    pub fn boxf(radius: Vec2) -> Filter {
        Filter::tabulate("box", radius, |_| 1.0)
    }

    /// Tent of the given radius.
    pub fn triangle(radius: Vec2) -> Filter {
        Filter::tabulate("triangle", radius, |x| (1.0 - x.abs()).max(0.0))
    }

    /// pbrt-v4's Gaussian: `g(x) - g(radius)`, clamped at zero.
    pub fn gaussian(radius: Vec2, sigma: f32) -> Filter {
        // Same profile in both axes when the radii match; otherwise the profile is
        // taken relative to each axis' radius with sigma scaled alike.
        let r = radius.x;
        let g = move |x: f32| (-(x * x) / (2.0 * sigma * sigma)).exp();
        let edge = g(r);
        Filter::tabulate("gaussian", radius, move |t| (g(t * r) - edge).max(0.0))
    }

    fn tabulate(name: &'static str, radius: Vec2, f: impl Fn(f32) -> f32) -> Filter {
        let mut cdf = Vec::with_capacity(TABLE + 1);
        cdf.push(0.0f32);
        let mut acc = 0.0f64;
        for i in 0..TABLE {
            // Midpoint rule within each cell, several sub-points.
            let mut s = 0.0f64;
            for k in 0..8 {
                let x = -1.0 + 2.0 * (i as f32 + (k as f32 + 0.5) / 8.0) / TABLE as f32;
                s += f(x) as f64;
            }
            acc += s;
            cdf.push(acc as f32);
        }
        let total = *cdf.last().unwrap();
        for c in cdf.iter_mut() {
            *c /= total;
        }
        Filter {
            name,
            radius,
            splat: false,
            cdf,
        }
    }

    fn sample_1d(&self, u: f32) -> f32 {
        let i = self.cdf.partition_point(|&c| c <= u).clamp(1, TABLE) - 1;
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let t = if c1 > c0 { (u - c0) / (c1 - c0) } else { 0.5 };
        -1.0 + 2.0 * (i as f32 + t) / TABLE as f32
    }

    /// Offset from the pixel centre, distributed as the filter.
    pub fn sample(&self, u: Vec2) -> Vec2 {
        Vec2::new(
            self.sample_1d(u.x) * self.radius.x,
            self.sample_1d(u.y) * self.radius.y,
        )
    }

    /// The density of [`Filter::sample`]'s offsets at `offset` (per square
    /// pixel): the filter normalised to integrate to one, which is the
    /// weight a contribution at `offset` from a pixel's centre has in that
    /// pixel (splats from light paths).
    pub fn pdf(&self, offset: Vec2) -> f32 {
        self.pdf_1d(offset.x / self.radius.x) / self.radius.x
            * self.pdf_1d(offset.y / self.radius.y)
            / self.radius.y
    }

    /// How many pixels away a pixel's samples can count, along x and y:
    /// the nearest point of a pixel `d` away is `d - 0.5` from the centre,
    /// within the support while that is below the radius. Zero for a box
    /// of radius 1/2, which splatting leaves each sample's own.
    pub fn reach(&self) -> (usize, usize) {
        let reach = |r: f32| (r + 0.5).ceil() as usize - 1;
        (reach(self.radius.x), reach(self.radius.y))
    }

    /// [`Filter::pdf`]'s factor along `x` (else `y`) at offset `d`: the
    /// density is their product (up to rounding).
    #[inline]
    pub fn pdf_axis(&self, x: bool, d: f32) -> f32 {
        let r = if x { self.radius.x } else { self.radius.y };
        self.pdf_1d(d / r) / r
    }

    /// Density of `sample_1d` at `t` in [-1, 1] (0 outside).
    fn pdf_1d(&self, t: f32) -> f32 {
        if !(t > -1.0 && t < 1.0) {
            return 0.0;
        }
        let i = (((t + 1.0) * 0.5 * TABLE as f32) as usize).min(TABLE - 1);
        (self.cdf[i + 1] - self.cdf[i]) * TABLE as f32 * 0.5
    }

    /// The area (in pixels) a pixel's samples spread over: `12 sigma_x
    /// sigma_y` of the sampled offsets, which is 1 for a one-pixel box.
    pub fn sample_spread(&self) -> f32 {
        let n = 1024;
        let (mut m, mut m2) = (0.0f64, 0.0f64);
        for i in 0..n {
            let x = self.sample_1d((i as f32 + 0.5) / n as f32) as f64;
            m += x;
            m2 += x * x;
        }
        let var = (m2 / n as f64 - (m / n as f64).powi(2)).max(0.0);
        (12.0 * var * (self.radius.x * self.radius.y) as f64) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pdf_integrates_to_one_and_matches_the_samples() {
        for f in [
            Filter::boxf(Vec2::splat(0.5)),
            Filter::triangle(Vec2::new(1.0, 1.5)),
            Filter::gaussian(Vec2::splat(2.0), 0.5),
        ] {
            // Midpoint rule over the support.
            let n = 400;
            let (rx, ry) = (f.radius.x, f.radius.y);
            let mut sum = 0.0f64;
            for i in 0..n {
                for j in 0..n {
                    let x = -rx + 2.0 * rx * (i as f32 + 0.5) / n as f32;
                    let y = -ry + 2.0 * ry * (j as f32 + 0.5) / n as f32;
                    sum += f.pdf(Vec2::new(x, y)) as f64;
                }
            }
            sum *= (4.0 * rx * ry) as f64 / (n * n) as f64;
            assert!((sum - 1.0).abs() < 2e-3, "{}: {sum}", f.name);
            // Samples fall where the density is: the share of them within
            // half the radius of the centre along x matches its integral.
            let inner: f64 = (0..n)
                .map(|i| -0.5 * rx + rx * (i as f32 + 0.5) / n as f32)
                .map(|x| f.pdf_1d(x / rx) as f64 / rx as f64)
                .sum::<f64>()
                * rx as f64
                / n as f64;
            let m = 4000;
            let hits = (0..m)
                .filter(|k| {
                    f.sample(Vec2::new((*k as f32 + 0.5) / m as f32, 0.5))
                        .x
                        .abs()
                        < 0.5 * rx
                })
                .count();
            assert!((hits as f64 / m as f64 - inner).abs() < 5e-3, "{}", f.name);
        }
        assert_eq!(Filter::boxf(Vec2::splat(0.5)).pdf(Vec2::new(0.6, 0.0)), 0.0);
    }

    #[test]
    fn box_is_uniform_and_tent_is_peaked() {
        let b = Filter::boxf(Vec2::splat(0.5));
        assert!((b.sample(Vec2::new(0.25, 0.75)) - Vec2::new(-0.25, 0.25)).length() < 1e-3);
        let t = Filter::triangle(Vec2::splat(1.0));
        // Median at zero, quartile of a tent: x = -1 + sqrt(0.5).
        assert!(t.sample(Vec2::splat(0.5)).length() < 1e-3);
        assert!((t.sample_1d(0.25) - (-1.0 + 0.5f32.sqrt())).abs() < 1e-3);
        let g = Filter::gaussian(Vec2::splat(1.5), 0.5);
        assert!(g.sample(Vec2::splat(0.999)).x <= 1.5);
    }

    #[test]
    fn sample_spread_is_twelve_variances() {
        // Box: uniform over one pixel; tent of radius 1: variance 1/6 per axis.
        assert!((Filter::boxf(Vec2::splat(0.5)).sample_spread() - 1.0).abs() < 1e-3);
        assert!((Filter::boxf(Vec2::new(1.0, 0.5)).sample_spread() - 2.0).abs() < 2e-3);
        assert!((Filter::triangle(Vec2::splat(1.0)).sample_spread() - 2.0).abs() < 1e-2);
    }
}
