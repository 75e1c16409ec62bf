//! A conductor's spectral `eta`, `k` reduced to one `(eta, k)` per sRGB
//! channel.
//!
//! pbrt-v4 evaluates the Fresnel reflectance `F(θ, λ)` of the complex index
//! `eta(λ) + i k(λ)` per wavelength. The best an RGB renderer can do is, per
//! channel `c`, a Fresnel curve `F(θ; eta_c, k_c)` close to the channel's
//! share `T_c(θ)` of the spectral curve under white light
//! ([`super::reflectance_rgb`] of `F(θ, ·)`). Averaging `eta` and `k` over
//! the channel does not give that (Fresnel is far from linear in them), so
//! the pair is fitted: `eta_c, k_c` reproduce `T_c` at normal incidence
//! exactly (the colour of the metal seen head-on), and among those pairs the
//! one closest to `T_c(θ)` at every other angle, in the least-squares sense
//! weighted by `cos θ` over the hemisphere's projected solid angle (how much
//! each angle contributes under uniform light), is kept.

use super::convert::white_weights;
use super::{Spectrum, LAMBDA_MIN};
use crate::Rgb;

/// Fresnel reflectance of unpolarised light from outside (index 1) onto a
/// conductor of complex index `eta + i k`, for `cos_i` in [0, 1].
pub fn fresnel_conductor(cos_i: f64, eta: f64, k: f64) -> f64 {
    let c2 = (cos_i * cos_i).clamp(0.0, 1.0);
    let s2 = 1.0 - c2;
    let t0 = eta * eta - k * k - s2;
    let a2b2 = (t0 * t0 + 4.0 * eta * eta * k * k).max(0.0).sqrt();
    let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
    let t1 = a2b2 + c2;
    let t2 = 2.0 * a * cos_i.clamp(0.0, 1.0);
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = c2 * a2b2 + s2 * s2;
    let t4 = t2 * s2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    if !(t1 + t2 > 0.0) {
        return 1.0;
    }
    (0.5 * (rs + rp)).clamp(0.0, 1.0)
}

/// Cosines at which the fit compares curves (midpoints of 32 equal steps).
const N_COS: usize = 32;

fn cosines() -> impl Iterator<Item = f64> {
    (0..N_COS).map(|j| (j as f64 + 0.5) / N_COS as f64)
}

/// Per-channel `(eta, k)` of a conductor given by spectral `eta` and `k`.
pub fn conductor_rgb(eta: &Spectrum, k: &Spectrum) -> (Rgb, Rgb) {
    let ww = white_weights();
    let ek: Vec<(f64, f64)> = (0..ww.len())
        .map(|i| {
            let l = LAMBDA_MIN + i as f64;
            (eta.eval(l).max(0.0), k.eval(l).max(0.0))
        })
        .collect();
    // T_c at each cosine, and at normal incidence.
    let target = |mu: f64| -> [f64; 3] {
        let mut t = [0.0f64; 3];
        for (w, &(e, kk)) in ww.iter().zip(&ek) {
            let f = fresnel_conductor(mu, e, kk);
            for c in 0..3 {
                t[c] += f * w[c];
            }
        }
        t
    };
    let curves: Vec<(f64, [f64; 3])> = cosines().map(|mu| (mu, target(mu))).collect();
    let normal = target(1.0);
    let mut eta_rgb = [0.0f32; 3];
    let mut k_rgb = [0.0f32; 3];
    for c in 0..3 {
        let curve: Vec<(f64, f64)> = curves.iter().map(|(mu, t)| (*mu, t[c])).collect();
        let (e, kk) = fit_channel(normal[c], &curve);
        eta_rgb[c] = e as f32;
        k_rgb[c] = kk as f32;
    }
    (Rgb::from_slice(&eta_rgb), Rgb::from_slice(&k_rgb))
}

/// `k` for which a conductor of index `eta` reflects `r0` at normal
/// incidence: `r0 = ((eta-1)² + k²) / ((eta+1)² + k²)`; `None` when no real
/// `k` does.
fn k_for(r0: f64, eta: f64) -> Option<f64> {
    let k2 = (r0 * (eta + 1.0).powi(2) - (eta - 1.0).powi(2)) / (1.0 - r0);
    (k2 >= 0.0).then(|| k2.sqrt())
}

/// The `(eta, k)` with normal reflectance `r0` closest to `curve`
/// (`(cos θ, F)` samples), weighted by `cos θ`.
fn fit_channel(r0: f64, curve: &[(f64, f64)]) -> (f64, f64) {
    let r0 = r0.clamp(1e-4, 0.9999);
    let sr = r0.sqrt();
    // eta range where k is real: between the two dielectric solutions.
    let (lo, hi) = ((1.0 - sr) / (1.0 + sr), (1.0 + sr) / (1.0 - sr));
    let (lo, hi) = (lo.max(1e-3), hi.min(20.0));
    let err = |eta: f64| -> f64 {
        let Some(k) = k_for(r0, eta) else {
            return f64::INFINITY;
        };
        curve
            .iter()
            .map(|&(mu, t)| mu * (fresnel_conductor(mu, eta, k) - t).powi(2))
            .sum()
    };
    // Log-spaced scan, then golden-section refinement around the best.
    const N: usize = 400;
    let at = |i: f64| lo * (hi / lo).powf(i / N as f64);
    let best = (0..=N)
        .map(|i| (i, err(at(i as f64))))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |b| b.0);
    let (mut a, mut b) = (
        (best as f64 - 1.0).max(0.0),
        (best as f64 + 1.0).min(N as f64),
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if err(at(x1)) < err(at(x2)) {
            b = x2;
        } else {
            a = x1;
        }
    }
    let eta = at(0.5 * (a + b));
    (eta, k_for(r0, eta).unwrap_or(0.0))
}
