//! Chi-square goodness-of-fit test of a direction sampler against its claimed
//! density over the unit sphere (after pbrt-v4's bsdfs_test and Mitsuba 3's
//! chi2 tests).
//!
//! The sphere is binned uniformly in `(cos theta, phi)` (every bin has the
//! same solid angle); sample counts are compared with the expected counts
//! `N ∫_bin pdf dω`, integrated by tensor Gauss-Legendre quadrature inside each
//! bin (no node lies on a bin edge, so discontinuities placed on edges, such as
//! the horizon, are integrated accurately; other jumps along lines of constant
//! `cos theta` can be declared in [`Chi2Config::z_breaks`]). Samples that fail or are
//! delta count as missing mass, compared with `N (1 - ∫ pdf)` as one more
//! cell. Cells with small expectation are pooled (in order of increasing
//! expectation) until each pooled cell expects at least `min_expected`.
//!
//! Usage: `let out = run(&Chi2Config::default(), sampler, pdf);` then
//! `assert!(out.passes(alpha), "{}", out.report())` with `alpha` from
//! [`sidak_alpha`].

#![allow(dead_code)]

use lumis_math::{Pcg32, Vec2, Vec3, PI};

#[derive(Clone, Debug)]
pub struct Chi2Config {
    /// Bins in `cos theta` over [-1, 1].
    pub cos_bins: usize,
    /// Bins in `phi` over [0, 2 pi).
    pub phi_bins: usize,
    pub samples: usize,
    /// Gauss-Legendre points per bin along each axis.
    pub quad_points: usize,
    pub min_expected: f64,
    pub seed: u64,
    /// Values of `cos theta` where the pdf is known to jump (besides bin
    /// edges): bins containing one are integrated piecewise on either side.
    pub z_breaks: Vec<f64>,
}

impl Default for Chi2Config {
    fn default() -> Self {
        Chi2Config {
            cos_bins: 80,
            phi_bins: 160,
            samples: 1_000_000,
            quad_points: 10,
            min_expected: 5.0,
            seed: 1,
            z_breaks: Vec::new(),
        }
    }
}

#[derive(Clone, Debug)]
pub struct Chi2Outcome {
    pub chi2: f64,
    pub dof: usize,
    pub p_value: f64,
    /// Fraction of samples that produced a direction.
    pub sampled_fraction: f64,
    /// `∫ pdf` over the sphere.
    pub pdf_mass: f64,
    /// Samples landing in bins where the integrated pdf is zero.
    pub observed_where_pdf_zero: u64,
    /// Samples whose direction was not unit length or not finite.
    pub invalid: u64,
}

impl Chi2Outcome {
    /// The sampler fits its pdf at significance `alpha`, and nothing was
    /// sampled where the pdf vanishes or returned as a non-unit direction.
    pub fn passes(&self, alpha: f64) -> bool {
        self.p_value >= alpha && self.invalid == 0 && self.observed_where_pdf_zero == 0
    }

    pub fn report(&self) -> String {
        format!(
            "chi2 {:.1} dof {} p {:.3e}; sampled fraction {:.5}, pdf mass {:.5}, \
             {} samples where pdf = 0, {} invalid",
            self.chi2,
            self.dof,
            self.p_value,
            self.sampled_fraction,
            self.pdf_mass,
            self.observed_where_pdf_zero,
            self.invalid
        )
    }
}

/// Per-test significance so that `m` independent tests together reject a
/// correct implementation with probability `alpha` (Sidak correction).
pub fn sidak_alpha(alpha: f64, m: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / m as f64)
}

/// Bin index of a unit direction.
pub fn bin_of(cfg: &Chi2Config, d: Vec3) -> usize {
    let (nz, np) = (cfg.cos_bins, cfg.phi_bins);
    let z = (d.z as f64).clamp(-1.0, 1.0);
    let iz = (((z + 1.0) * 0.5 * nz as f64) as usize).min(nz - 1);
    let mut phi = (d.y as f64).atan2(d.x as f64);
    if phi < 0.0 {
        phi += 2.0 * std::f64::consts::PI;
    }
    let ip = ((phi / (2.0 * std::f64::consts::PI) * np as f64) as usize).min(np - 1);
    iz * np + ip
}

/// Histogram of `cfg.samples` draws; returns (counts per bin, invalid count).
/// The sampler gets `(u, uc)` with independent uniform numbers.
pub fn histogram(
    cfg: &Chi2Config,
    mut sampler: impl FnMut(Vec2, f32) -> Option<Vec3>,
) -> (Vec<u64>, u64) {
    let mut rng = Pcg32::new(cfg.seed, 0x5eed);
    let mut counts = vec![0u64; cfg.cos_bins * cfg.phi_bins];
    let mut invalid = 0;
    for _ in 0..cfg.samples {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let uc = rng.next_f32();
        if let Some(d) = sampler(u, uc) {
            if !d.is_finite() || (d.length() - 1.0).abs() > 1e-3 {
                invalid += 1;
                continue;
            }
            counts[bin_of(cfg, d)] += 1;
        }
    }
    (counts, invalid)
}

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        // Tricomi's initial guess for the i-th root.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // Recurrence for P_n(x) and P_{n-1}(x).
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 0 { 1.0 } else { p1 };
            let pn1 = if n == 1 { 1.0 } else { p0 };
            dp = n as f64 * (x * pn - pn1) / (x * x - 1.0);
            let dx = pn / dp;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// `∫_bin pdf dω` for every bin (dω = dz dphi).
pub fn integrate_pdf(cfg: &Chi2Config, pdf: impl Fn(Vec3) -> f32) -> Vec<f64> {
    let (nz, np) = (cfg.cos_bins, cfg.phi_bins);
    let gl = gauss_legendre(cfg.quad_points);
    let (hz, hp) = (2.0 / nz as f64, 2.0 * std::f64::consts::PI / np as f64);
    // Angles of all phi nodes with weights, bin-major.
    let mut phis = Vec::with_capacity(np * gl.len());
    for ip in 0..np {
        for &(x, w) in &gl {
            let phi = (ip as f64 + 0.5 * (x + 1.0)) * hp;
            phis.push((phi.cos(), phi.sin(), 0.5 * w * hp));
        }
    }
    let mut out = vec![0.0; nz * np];
    for iz in 0..nz {
        // Pieces of this bin's z range, split at the known jumps.
        let (z0, z1) = (-1.0 + iz as f64 * hz, -1.0 + (iz + 1) as f64 * hz);
        let mut cuts = vec![z0];
        cuts.extend(cfg.z_breaks.iter().copied().filter(|&b| b > z0 && b < z1));
        cuts.push(z1);
        cuts.sort_by(f64::total_cmp);
        for piece in cuts.windows(2) {
            let (a, b) = (piece[0], piece[1]);
            for &(x, wz) in &gl {
                let z = a + 0.5 * (x + 1.0) * (b - a);
                let wz = 0.5 * wz * (b - a);
                let r = (1.0 - z * z).max(0.0).sqrt();
                for ip in 0..np {
                    let mut s = 0.0;
                    for &(c, sn, wp) in &phis[ip * gl.len()..(ip + 1) * gl.len()] {
                        let d = Vec3::new((r * c) as f32, (r * sn) as f32, z as f32);
                        s += wp * pdf(d) as f64;
                    }
                    out[iz * np + ip] += wz * s;
                }
            }
        }
    }
    out
}

/// Pearson statistic with pooling of low-expectation cells; returns
/// (chi2, degrees of freedom).
pub fn pearson(observed: &[f64], expected: &[f64], min_expected: f64) -> (f64, usize) {
    let mut idx: Vec<usize> = (0..expected.len()).collect();
    idx.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]));
    let mut chi2 = 0.0;
    let mut cells = 0usize;
    let (mut po, mut pe) = (0.0, 0.0);
    for &i in &idx {
        po += observed[i];
        pe += expected[i];
        if pe >= min_expected {
            chi2 += (po - pe) * (po - pe) / pe;
            cells += 1;
            po = 0.0;
            pe = 0.0;
        }
    }
    if po > 0.0 || pe > 0.0 {
        // Leftover pool: compare as its own cell if it can be, otherwise it
        // only matters when observations appeared where nothing was expected.
        let e = pe.max(min_expected);
        chi2 += (po - pe) * (po - pe) / e;
        cells += 1;
    }
    (chi2, cells.saturating_sub(1))
}

/// Full test: histogram, integration, pooling, p-value.
pub fn run(
    cfg: &Chi2Config,
    sampler: impl FnMut(Vec2, f32) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f32,
) -> Chi2Outcome {
    let (counts, invalid) = histogram(cfg, sampler);
    let integrals = integrate_pdf(cfg, pdf);
    let n = cfg.samples as f64;
    let mut observed: Vec<f64> = counts.iter().map(|&c| c as f64).collect();
    let mut expected: Vec<f64> = integrals.iter().map(|&p| p * n).collect();
    let hit: u64 = counts.iter().sum();
    let mass: f64 = integrals.iter().sum();
    let observed_where_pdf_zero = counts
        .iter()
        .zip(&integrals)
        .filter(|(_, &p)| p <= 0.0)
        .map(|(&c, _)| c)
        .sum();
    // Missing mass: failed, delta and invalid samples.
    observed.push((cfg.samples as u64 - hit) as f64);
    expected.push(((1.0 - mass) * n).max(0.0));
    let (chi2, dof) = pearson(&observed, &expected, cfg.min_expected);
    Chi2Outcome {
        chi2,
        dof,
        p_value: chi2_sf(chi2, dof),
        sampled_fraction: hit as f64 / n,
        pdf_mass: mass,
        observed_where_pdf_zero,
        invalid,
    }
}

/// Survival function of the chi-square distribution: `P(X >= x)`.
pub fn chi2_sf(x: f64, dof: usize) -> f64 {
    if dof == 0 {
        return if x > 0.0 { 0.0 } else { 1.0 };
    }
    gamma_q(0.5 * dof as f64, 0.5 * x)
}

/// `ln Γ(x)` for `x > 0` (Lanczos, g = 7, n = 9).
pub fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection formula.
        return (std::f64::consts::PI / (std::f64::consts::PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, &c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Regularized lower incomplete gamma `P(a, x)` by its power series
/// (converges quickly for `x < a + 1`).
fn gamma_p_series(a: f64, x: f64) -> f64 {
    let mut term = 1.0 / a;
    let mut sum = term;
    let mut ap = a;
    for _ in 0..100_000 {
        ap += 1.0;
        term *= x / ap;
        sum += term;
        if term.abs() < sum.abs() * 1e-15 {
            break;
        }
    }
    (sum.ln() - x + a * x.ln() - ln_gamma(a)).exp()
}

/// Regularized upper incomplete gamma `Q(a, x)` by its continued fraction
/// (modified Lentz; converges quickly for `x > a + 1`).
fn gamma_q_cf(a: f64, x: f64) -> f64 {
    const TINY: f64 = 1e-300;
    let mut b = x + 1.0 - a;
    let mut c = 1.0 / TINY;
    let mut d = 1.0 / b;
    let mut h = d;
    for i in 1..100_000 {
        let an = -(i as f64) * (i as f64 - a);
        b += 2.0;
        d = an * d + b;
        if d.abs() < TINY {
            d = TINY;
        }
        c = b + an / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        let delta = d * c;
        h *= delta;
        if (delta - 1.0).abs() < 1e-15 {
            break;
        }
    }
    (h.ln() - x + a * x.ln() - ln_gamma(a)).exp()
}

/// Regularized upper incomplete gamma function `Q(a, x) = Γ(a, x) / Γ(a)`.
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    if x < a + 1.0 {
        (1.0 - gamma_p_series(a, x)).max(0.0)
    } else {
        gamma_q_cf(a, x)
    }
}

/// Solid angle of one bin, for reference.
pub fn bin_solid_angle(cfg: &Chi2Config) -> f64 {
    4.0 * PI as f64 / (cfg.cos_bins * cfg.phi_bins) as f64
}
