//! Spectra to linear sRGB: sums against the CIE 1931 matching functions at
//! 1 nm over 360-830 nm (pbrt-v4's `InnerProduct`), then XYZ to sRGB.
//!
//! Why these reductions reproduce pbrt-v4 (sRGB colour space, default
//! `cie1931` sensor, no white balance: the film stores `XYZ = ∫ L xyz dλ`
//! times the imaging ratio and converts it with the sRGB matrix):
//! - a light's spectrum `S` is divided by its luminance `Σ ȳ S` (lights'
//!   `scale /= SpectrumToPhotometric(S)`), so its pixel colour is
//!   `scale · XYZ(S) / Y(S)`: [`illuminant_rgb`]. An `rgb` light is
//!   `rgb × D65`-shaped and its luminance is taken from D65 alone, so it
//!   renders as the rgb itself.
//! - a reflectance `R` lit by a white (D65, rgb 1) light of luminance 1 sends
//!   `XYZ = Σ R D65 xyz / Σ D65 ȳ` to the film: [`reflectance_rgb`]. A
//!   constant `c` gives exactly `(c, c, c)` because the matrix is built with
//!   the white point of the same D65 table (as pbrt-v4 builds its own). An
//!   RGB renderer cannot reproduce products of spectra exactly; this is the
//!   one-bounce, white-light answer.

use super::{cie::CMF, named, Spectrum, LAMBDA_MIN};
use crate::Rgb;
use glam::{DMat3, DVec3};
use std::sync::OnceLock;

/// `Σ ȳ(λ)` over 360..=830 nm at 1 nm steps: pbrt-v4's `CIE_Y_integral`.
pub const CIE_Y_INTEGRAL: f64 = 106.856_895;

/// CIE 1931 `(x̄, ȳ, z̄)` at a whole wavelength in 360..=830 nm.
pub fn cmf(nm: u32) -> Option<[f64; 3]> {
    let c = CMF.get(nm.checked_sub(LAMBDA_MIN as u32)? as usize)?;
    Some([c[0] as f64, c[1] as f64, c[2] as f64])
}

/// `(X, Y, Z) = Σ S(λ) (x̄, ȳ, z̄)(λ)` over 360..=830 nm at 1 nm steps.
pub fn xyz(s: &Spectrum) -> [f64; 3] {
    let mut acc = [0.0f64; 3];
    for (i, c) in CMF.iter().enumerate() {
        let v = s.eval(LAMBDA_MIN + i as f64);
        for k in 0..3 {
            acc[k] += v * c[k] as f64;
        }
    }
    acc
}

struct Consts {
    xyz_to_rgb: DMat3,
    /// Per wavelength: the sRGB each nm of a reflectance contributes under
    /// D65 (`M · xyz(λ) D65(λ) / Σ D65 ȳ`).
    white_weights: Vec<[f64; 3]>,
    /// Per wavelength: `D65(λ) ȳ(λ) / Σ D65 ȳ`.
    white_y: Vec<f64>,
}

fn consts() -> &'static Consts {
    static C: OnceLock<Consts> = OnceLock::new();
    C.get_or_init(|| {
        let d65 = named("stdillum-D65").expect("D65 is a named spectrum");
        let w = xyz(&d65);
        let white = DVec3::new(w[0] / w[1], 1.0, w[2] / w[1]);
        // Rec. 709 / sRGB primaries; the columns of RGB→XYZ are scaled so
        // that rgb (1, 1, 1) is the white point.
        let col = |x: f64, y: f64| DVec3::new(x / y, 1.0, (1.0 - x - y) / y);
        let p = DMat3::from_cols(col(0.64, 0.33), col(0.30, 0.60), col(0.15, 0.06));
        let s = p.inverse() * white;
        let rgb_to_xyz = DMat3::from_cols(p.x_axis * s.x, p.y_axis * s.y, p.z_axis * s.z);
        let xyz_to_rgb = rgb_to_xyz.inverse();
        let d: Vec<f64> = (0..CMF.len())
            .map(|i| d65.eval(LAMBDA_MIN + i as f64))
            .collect();
        let norm: f64 = d.iter().zip(&CMF).map(|(d, c)| d * c[1] as f64).sum();
        let white_weights = d
            .iter()
            .zip(&CMF)
            .map(|(d, c)| {
                let v = xyz_to_rgb * DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) * (d / norm);
                [v.x, v.y, v.z]
            })
            .collect();
        let white_y = d
            .iter()
            .zip(&CMF)
            .map(|(d, c)| d * c[1] as f64 / norm)
            .collect();
        Consts {
            xyz_to_rgb,
            white_weights,
            white_y,
        }
    })
}

/// CIE XYZ to linear sRGB (D65 white of the same tables).
pub fn xyz_to_linear_srgb(c: [f64; 3]) -> Rgb {
    let v = consts().xyz_to_rgb * DVec3::from_array(c);
    Rgb::new(v.x as f32, v.y as f32, v.z as f32)
}

/// An emitted spectrum as linear sRGB of luminance 1 (black if it has no
/// luminance): a light's `scale` then sets its luminance, as in pbrt-v4.
pub fn illuminant_rgb(s: &Spectrum) -> Rgb {
    let c = xyz(s);
    if !(c[1] > 0.0) || !c.iter().all(|v| v.is_finite()) {
        return Rgb::BLACK;
    }
    xyz_to_linear_srgb([c[0] / c[1], 1.0, c[2] / c[1]])
}

/// A reflectance spectrum as linear sRGB: the colour it reflects from a
/// white (D65) light, a constant 1 giving exactly (1, 1, 1).
pub fn reflectance_rgb(s: &Spectrum) -> Rgb {
    let w = &consts().white_weights;
    let mut acc = [0.0f64; 3];
    for (i, wi) in w.iter().enumerate() {
        let v = s.eval(LAMBDA_MIN + i as f64);
        for k in 0..3 {
            acc[k] += v * wi[k];
        }
    }
    Rgb::new(acc[0] as f32, acc[1] as f32, acc[2] as f32)
}

/// The spectrum's mean weighted by the luminance of white (D65) light:
/// `Σ S D65 ȳ / Σ D65 ȳ` (a dielectric's single index of refraction).
pub fn mean_under_white(s: &Spectrum) -> f64 {
    consts()
        .white_y
        .iter()
        .enumerate()
        .map(|(i, w)| s.eval(LAMBDA_MIN + i as f64) * w)
        .sum()
}

/// The reflectance weights of [`reflectance_rgb`], per nm from 360.
pub(crate) fn white_weights() -> &'static [[f64; 3]] {
    &consts().white_weights
}
