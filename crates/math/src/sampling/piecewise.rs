//! Piecewise-constant distributions on [0,1) and [0,1)², with densities:
//! importance sampling of tabulated functions (environment maps).

use crate::{Vec2, ONE_MINUS_EPSILON};

/// A density on [0,1) proportional to a step function of `n` equal bins.
/// A function that is zero everywhere becomes the uniform density.
#[derive(Clone, Debug)]
pub struct PiecewiseConstant1D {
    func: Vec<f32>,
    /// `cdf[i]` = mass of bins `0..i`; `cdf[n]` = 1.
    cdf: Vec<f32>,
    /// Mean of the function (its integral over [0,1)).
    integral: f32,
}

/// The largest f32 below `x` (for positive finite `x`).
fn prev_float(x: f32) -> f32 {
    if x > 0.0 {
        f32::from_bits(x.to_bits() - 1)
    } else {
        0.0
    }
}

impl PiecewiseConstant1D {
    /// From bin values; negative and non-finite values count as zero.
    /// Panics on an empty slice.
    pub fn new(f: &[f32]) -> PiecewiseConstant1D {
        assert!(!f.is_empty(), "piecewise-constant distribution of no bins");
        let mut func: Vec<f32> = f
            .iter()
            .map(|&v| if v.is_finite() && v > 0.0 { v } else { 0.0 })
            .collect();
        let n = func.len();
        let total: f64 = func.iter().map(|&v| v as f64).sum();
        if !(total > 0.0) || !total.is_finite() {
            func.iter_mut().for_each(|v| *v = 1.0);
        }
        let total: f64 = func.iter().map(|&v| v as f64).sum();
        let mut cdf = Vec::with_capacity(n + 1);
        let mut acc = 0.0f64;
        cdf.push(0.0);
        for &v in &func {
            acc += v as f64;
            cdf.push((acc / total) as f32);
        }
        cdf[n] = 1.0;
        PiecewiseConstant1D {
            func,
            cdf,
            integral: (total / n as f64) as f32,
        }
    }

    pub fn len(&self) -> usize {
        self.func.len()
    }

    pub fn is_empty(&self) -> bool {
        self.func.is_empty()
    }

    /// Integral of the (clamped) function over [0,1).
    pub fn integral(&self) -> f32 {
        self.integral
    }

    /// Bin of `x` in [0,1] (1 falls in the last bin).
    #[inline]
    pub fn bin(&self, x: f32) -> usize {
        let n = self.func.len();
        ((x * n as f32) as usize).min(n - 1)
    }

    /// Density of bin `i`.
    #[inline]
    pub fn pdf_bin(&self, i: usize) -> f32 {
        self.func[i] / self.integral
    }

    /// Density at `x` in [0,1].
    #[inline]
    pub fn pdf(&self, x: f32) -> f32 {
        if !(0.0..=1.0).contains(&x) {
            return 0.0;
        }
        self.pdf_bin(self.bin(x))
    }

    /// Probability of bin `i` (its density times its width).
    pub fn pmf(&self, i: usize) -> f32 {
        self.cdf[i + 1] - self.cdf[i]
    }

    /// Inverts the CDF at `u` in [0,1): returns `(x, density, bin)`, with
    /// `bin(x) == bin` and a density that is never zero.
    pub fn sample(&self, u: f32) -> (f32, f32, usize) {
        let n = self.func.len();
        let u = u.clamp(0.0, ONE_MINUS_EPSILON);
        // Last i with cdf[i] <= u: the bin [cdf[i], cdf[i+1]) holding u has mass.
        let i = (self.cdf.partition_point(|&c| c <= u) - 1).min(n - 1);
        let mass = self.cdf[i + 1] - self.cdf[i];
        let du = if mass > 0.0 {
            ((u - self.cdf[i]) / mass).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let mut x = (i as f32 + du) / n as f32;
        // Rounding must not carry x into a neighbouring bin.
        while x > 0.0 && self.bin(x) > i {
            x = prev_float(x);
        }
        while self.bin(x) < i {
            x = f32::from_bits(x.to_bits() + 1);
        }
        (x, self.pdf_bin(i), i)
    }
}

/// A density on [0,1)² proportional to a step function on a `nu` × `nv`
/// grid (row-major, `v` rows of `u` bins): a marginal over rows, then the
/// row's conditional.
#[derive(Clone, Debug)]
pub struct PiecewiseConstant2D {
    conditional: Vec<PiecewiseConstant1D>,
    marginal: PiecewiseConstant1D,
}

impl PiecewiseConstant2D {
    /// `f` has `nu * nv` values, row `v` at `f[v*nu..(v+1)*nu]`.
    pub fn new(f: &[f32], nu: usize, nv: usize) -> PiecewiseConstant2D {
        assert!(nu > 0 && nv > 0 && f.len() == nu * nv, "bad 2D table size");
        // A zero row gets a uniform conditional, but no marginal mass.
        let conditional: Vec<PiecewiseConstant1D> =
            f.chunks_exact(nu).map(PiecewiseConstant1D::new).collect();
        let row_integrals: Vec<f32> = f
            .chunks_exact(nu)
            .map(|row| {
                let s: f64 = row
                    .iter()
                    .map(|&v| {
                        if v.is_finite() && v > 0.0 {
                            v as f64
                        } else {
                            0.0
                        }
                    })
                    .sum();
                (s / nu as f64) as f32
            })
            .collect();
        let marginal = PiecewiseConstant1D::new(&row_integrals);
        PiecewiseConstant2D {
            conditional,
            marginal,
        }
    }

    pub fn resolution(&self) -> (usize, usize) {
        (self.conditional[0].len(), self.conditional.len())
    }

    /// Density of grid cell `(iu, iv)`.
    #[inline]
    pub fn pdf_bin(&self, iu: usize, iv: usize) -> f32 {
        self.marginal.pdf_bin(iv) * self.conditional[iv].pdf_bin(iu)
    }

    /// Density at `p` in [0,1]².
    pub fn pdf(&self, p: Vec2) -> f32 {
        if !(0.0..=1.0).contains(&p.x) || !(0.0..=1.0).contains(&p.y) {
            return 0.0;
        }
        let iv = self.marginal.bin(p.y);
        self.pdf_bin(self.conditional[iv].bin(p.x), iv)
    }

    /// Returns the point, its density (never zero) and its cell `(iu, iv)`.
    pub fn sample(&self, u: Vec2) -> (Vec2, f32, (usize, usize)) {
        let (y, _, iv) = self.marginal.sample(u.y);
        let (x, _, iu) = self.conditional[iv].sample(u.x);
        (Vec2::new(x, y), self.pdf_bin(iu, iv), (iu, iv))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Pcg32;

    #[test]
    fn one_d_pdf_matches_function_and_integrates_to_one() {
        let f = [0.0, 1.0, 3.0, 0.0, 4.0];
        let d = PiecewiseConstant1D::new(&f);
        assert!((d.integral() - 8.0 / 5.0).abs() < 1e-6);
        let total: f32 = (0..5).map(|i| d.pdf_bin(i) / 5.0).sum();
        assert!((total - 1.0).abs() < 1e-6);
        assert_eq!(d.pdf(0.1), 0.0);
        assert!((d.pdf(0.5) - 3.0 / 1.6).abs() < 1e-5);
        assert!((d.pmf(4) - 0.5).abs() < 1e-6);
        assert_eq!(d.pdf(-0.1), 0.0);
    }

    #[test]
    fn one_d_sampling_follows_the_function() {
        let f = [0.0, 1.0, 3.0, 0.0, 4.0, 0.0];
        let d = PiecewiseConstant1D::new(&f);
        let mut rng = Pcg32::new(1, 2);
        let n = 400_000;
        let mut counts = [0f64; 6];
        for _ in 0..n {
            let (x, pdf, i) = d.sample(rng.next_f32());
            assert!((0.0..1.0).contains(&x));
            assert_eq!(d.bin(x), i);
            assert!(pdf > 0.0 && pdf == d.pdf(x));
            counts[i] += 1.0;
        }
        for i in 0..6 {
            let p = f[i] as f64 / 8.0;
            let se = (p * (1.0 - p) / n as f64).sqrt();
            assert!(
                (counts[i] / n as f64 - p).abs() <= 5.0 * se + 1e-12,
                "bin {i}"
            );
        }
        // The inverse CDF is exact at bin boundaries.
        assert!((d.sample(0.125).0 - 2.0 / 6.0).abs() < 1e-6);
        // u at the very end still lands in the last non-empty bin.
        assert_eq!(d.sample(ONE_MINUS_EPSILON).2, 4);
        assert_eq!(d.sample(0.0).2, 1);
    }

    #[test]
    fn one_d_zero_function_is_uniform() {
        let d = PiecewiseConstant1D::new(&[0.0, 0.0, f32::NAN, -1.0]);
        assert!((d.pdf(0.3) - 1.0).abs() < 1e-6);
        assert!((d.sample(0.3).0 - 0.3).abs() < 1e-6);
    }

    #[test]
    fn sampled_points_stay_in_their_bin_under_rounding() {
        // Many tiny bins: (i + du) / n rounds up to the next bin for du near 1.
        let f: Vec<f32> = (0..4097)
            .map(|i| if i % 2 == 0 { 1.0 } else { 0.0 })
            .collect();
        let d = PiecewiseConstant1D::new(&f);
        let mut rng = Pcg32::new(9, 9);
        for _ in 0..200_000 {
            let (x, pdf, i) = d.sample(rng.next_f32());
            assert_eq!(i % 2, 0);
            assert_eq!(d.bin(x), i);
            assert_eq!(d.pdf(x), pdf);
        }
    }

    #[test]
    fn two_d_pdf_and_sampling() {
        // 3 x 2 grid, one empty row and one empty cell.
        let f = [1.0, 0.0, 2.0, 0.0, 0.0, 0.0];
        let d = PiecewiseConstant2D::new(&f, 3, 2);
        assert_eq!(d.resolution(), (3, 2));
        // Cell area 1/6: densities 6 * f / sum(f).
        assert!((d.pdf(Vec2::new(0.1, 0.2)) - 2.0).abs() < 1e-5);
        assert!((d.pdf(Vec2::new(0.9, 0.2)) - 4.0).abs() < 1e-5);
        assert_eq!(d.pdf(Vec2::new(0.5, 0.2)), 0.0);
        assert_eq!(d.pdf(Vec2::new(0.1, 0.7)), 0.0);
        let mut rng = Pcg32::new(5, 5);
        let n = 200_000;
        let mut right = 0.0;
        for _ in 0..n {
            let (p, pdf, (iu, iv)) = d.sample(Vec2::new(rng.next_f32(), rng.next_f32()));
            assert_eq!(iv, 0);
            assert!(iu == 0 || iu == 2);
            assert_eq!(pdf, d.pdf(p));
            if iu == 2 {
                right += 1.0;
            }
        }
        let p = 2.0 / 3.0;
        let se = (p * (1.0 - p) / n as f64).sqrt();
        assert!((right / n as f64 - p).abs() < 5.0 * se);
    }

    #[test]
    fn two_d_density_integrates_to_one() {
        let mut rng = Pcg32::new(3, 3);
        let (nu, nv) = (7, 5);
        let f: Vec<f32> = (0..nu * nv).map(|_| rng.next_f32().powi(3)).collect();
        let d = PiecewiseConstant2D::new(&f, nu, nv);
        let mut total = 0.0f64;
        for iv in 0..nv {
            for iu in 0..nu {
                total += d.pdf_bin(iu, iv) as f64 / (nu * nv) as f64;
                let expected = f[iv * nu + iu] as f64 * (nu * nv) as f64
                    / f.iter().map(|&x| x as f64).sum::<f64>();
                assert!((d.pdf_bin(iu, iv) as f64 - expected).abs() < 1e-4 * expected.max(1.0));
            }
        }
        assert!((total - 1.0).abs() < 1e-5);
    }
}
