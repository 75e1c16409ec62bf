//! Spectra as pbrt-v4 reads them (blackbody, named, sampled) and their
//! reduction to linear sRGB, the colour space lumis renders in.
//!
//! Conventions (`convert.rs` says why each matches what pbrt-v4 renders):
//! - an **emitted** spectrum becomes the linear sRGB colour of unit luminance
//!   ([`illuminant_rgb`]): pbrt-v4 divides every light's `scale` by the
//!   spectrum's luminance;
//! - a **reflectance** (or any other unitless spectrum) becomes the sRGB of
//!   the light it reflects from a white (D65) light, normalised so that a
//!   constant 1 is white ([`reflectance_rgb`]);
//! - a conductor's `eta` and `k` become one `(eta, k)` per channel fitted to
//!   the channel's Fresnel reflectance over all angles ([`conductor_rgb`]);
//! - a dielectric's `eta` becomes its luminance-weighted mean
//!   ([`mean_under_white`]): dispersion is not rendered.

mod balance;
mod cie;
mod conductor;
mod convert;
mod illum;
mod named;
mod optical;

pub use balance::{white_balance, white_balance_illuminant};
pub use conductor::{conductor_rgb, fresnel_conductor};
pub use convert::{
    cmf, illuminant_rgb, mean_under_white, reflectance_rgb, xyz, xyz_to_linear_srgb, CIE_Y_INTEGRAL,
};
pub use named::{daylight, daylight_xy, illuminant_a, named, NAMED};

/// The wavelength range pbrt-v4 integrates over (nm).
pub const LAMBDA_MIN: f64 = 360.0;
pub const LAMBDA_MAX: f64 = 830.0;

/// A spectral distribution over wavelength in nm.
#[derive(Clone, Debug, PartialEq)]
pub enum Spectrum {
    Constant(f64),
    /// Planck's law at this temperature (kelvin), normalised to 1 at its
    /// peak, as pbrt-v4's `BlackbodySpectrum`.
    Blackbody(f64),
    /// Linear interpolation of `(nm, value)` samples with increasing
    /// wavelengths, zero outside them (pbrt-v4's `PiecewiseLinearSpectrum`).
    Piecewise(Vec<(f64, f64)>),
}

impl Spectrum {
    /// Checked samples: at least one, finite, wavelengths strictly increasing.
    pub fn piecewise(samples: Vec<(f64, f64)>) -> Result<Spectrum, String> {
        if samples.is_empty() {
            return Err("a sampled spectrum needs at least one (wavelength, value) pair".into());
        }
        for (i, &(l, v)) in samples.iter().enumerate() {
            if !l.is_finite() || !v.is_finite() {
                return Err(format!(
                    "sample {} ({l} nm, {v}) is not a finite number",
                    i + 1
                ));
            }
            if i > 0 && l <= samples[i - 1].0 {
                return Err(format!(
                    "wavelengths must increase, but sample {} ({l} nm) follows {} nm",
                    i + 1,
                    samples[i - 1].0
                ));
            }
        }
        Ok(Spectrum::Piecewise(samples))
    }

    pub fn eval(&self, nm: f64) -> f64 {
        match self {
            Spectrum::Constant(c) => *c,
            Spectrum::Blackbody(t) => {
                // Wien's displacement law gives the peak.
                let peak_nm = 2.897_772_1e-3 / t * 1e9;
                let p = planck(peak_nm, *t);
                if p > 0.0 {
                    planck(nm, *t) / p
                } else {
                    0.0
                }
            }
            Spectrum::Piecewise(s) => {
                let (first, last) = (s[0], s[s.len() - 1]);
                if nm < first.0 || nm > last.0 {
                    return 0.0;
                }
                let i = s.partition_point(|p| p.0 <= nm);
                if i >= s.len() {
                    return last.1;
                }
                let (a, b) = (s[i - 1], s[i]);
                a.1 + (nm - a.0) / (b.0 - a.0) * (b.1 - a.1)
            }
        }
    }

    /// The same spectrum times `k`.
    pub fn scaled(self, k: f64) -> Spectrum {
        match self {
            Spectrum::Constant(c) => Spectrum::Constant(c * k),
            Spectrum::Piecewise(s) => {
                Spectrum::Piecewise(s.into_iter().map(|(l, v)| (l, v * k)).collect())
            }
            Spectrum::Blackbody(_) => {
                let v: Vec<(f64, f64)> = (LAMBDA_MIN as i32 - 1..=LAMBDA_MAX as i32 + 1)
                    .map(|l| (l as f64, self.eval(l as f64) * k))
                    .collect();
                Spectrum::Piecewise(v)
            }
        }
    }

    /// Is it the same value at every wavelength pbrt-v4 integrates over?
    pub fn is_constant(&self) -> bool {
        match self {
            Spectrum::Constant(_) => true,
            Spectrum::Blackbody(_) => false,
            Spectrum::Piecewise(_) => {
                let v0 = self.eval(LAMBDA_MIN);
                (LAMBDA_MIN as i32..=LAMBDA_MAX as i32).all(|l| self.eval(l as f64) == v0)
            }
        }
    }
}

/// Planck's law: spectral radiance of a blackbody at `nm` and `kelvin`
/// (W / (m² sr m)). Zero for non-positive temperatures.
pub fn planck(nm: f64, kelvin: f64) -> f64 {
    if !(kelvin > 0.0) {
        return 0.0;
    }
    const C: f64 = 299_792_458.0;
    const H: f64 = 6.626_070_15e-34;
    const KB: f64 = 1.380_649e-23;
    let l = nm * 1e-9;
    2.0 * H * C * C / (l.powi(5) * ((H * C / (l * KB * kelvin)).exp_m1()))
}

/// A table sampled every `step` nm from `start`.
pub(crate) struct Table {
    pub start: f32,
    pub step: f32,
    pub values: &'static [f32],
}

impl Table {
    fn samples(&self) -> Vec<(f64, f64)> {
        self.values
            .iter()
            .enumerate()
            .map(|(i, &v)| ((self.start + i as f32 * self.step) as f64, v as f64))
            .collect()
    }
}

#[cfg(test)]
mod tests;
