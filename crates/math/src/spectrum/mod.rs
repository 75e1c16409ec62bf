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
mod optical;

pub use balance::{white_balance, white_balance_illuminant};
pub use conductor::{conductor_rgb, fresnel_conductor};
pub use convert::{
    cmf, illuminant_rgb, mean_under_white, reflectance_rgb, xyz, xyz_to_linear_srgb, CIE_Y_INTEGRAL,
};

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

/// Every name [`named`] knows, in pbrt-v4's order.
pub const NAMED: [&str; 38] = [
    "glass-BK7",
    "glass-BAF10",
    "glass-FK51A",
    "glass-LASF9",
    "glass-F5",
    "glass-F10",
    "glass-F11",
    "metal-Ag-eta",
    "metal-Ag-k",
    "metal-Al-eta",
    "metal-Al-k",
    "metal-Au-eta",
    "metal-Au-k",
    "metal-Cu-eta",
    "metal-Cu-k",
    "metal-CuZn-eta",
    "metal-CuZn-k",
    "metal-MgO-eta",
    "metal-MgO-k",
    "metal-TiO2-eta",
    "metal-TiO2-k",
    "stdillum-A",
    "stdillum-D50",
    "stdillum-D65",
    "stdillum-F1",
    "stdillum-F2",
    "stdillum-F3",
    "stdillum-F4",
    "stdillum-F5",
    "stdillum-F6",
    "stdillum-F7",
    "stdillum-F8",
    "stdillum-F9",
    "stdillum-F10",
    "stdillum-F11",
    "stdillum-F12",
    "illum-acesD60",
    // Not one of pbrt-v4's names: kept because earlier lumis accepted it.
    "glass-fused-silica",
];

/// A named spectrum of pbrt-v4 (see [`NAMED`]), with pbrt-v4's conventions:
/// samples extended by their end values to cover 360-830 nm, illuminants
/// scaled to luminance 1 (`Σ ȳ S = Σ ȳ` over 360-830 nm, 1 nm steps).
pub fn named(name: &str) -> Option<Spectrum> {
    use optical::*;
    let zip = |nm: &[f32], v: &[f32]| -> Vec<(f64, f64)> {
        nm.iter()
            .zip(v)
            .map(|(&l, &v)| (l as f64, v as f64))
            .collect()
    };
    let pairs = |p: &[(f32, f32)]| -> Vec<(f64, f64)> {
        p.iter().map(|&(l, v)| (l as f64, v as f64)).collect()
    };
    let every10 = |start: f32, v: &'static [f32]| {
        Table {
            start,
            step: 10.0,
            values: v,
        }
        .samples()
    };
    let illuminant = |s: Vec<(f64, f64)>| Some(normalised(extended(s)));
    let samples = match name {
        "glass-BK7" => pairs(&GLASS_BK7),
        "glass-BAF10" => pairs(&GLASS_BAF10),
        "glass-FK51A" => pairs(&GLASS_FK51A),
        "glass-LASF9" => pairs(&GLASS_LASF9),
        "glass-F5" => pairs(&GLASS_SF5),
        "glass-F10" => pairs(&GLASS_SF10),
        "glass-F11" => pairs(&GLASS_SF11),
        "glass-fused-silica" => return Some(Spectrum::Constant(1.4585)),
        "metal-Ag-eta" => zip(&PALIK_NM, &AG_ETA),
        "metal-Ag-k" => zip(&PALIK_NM, &AG_K),
        "metal-Al-eta" => zip(&PALIK_NM, &AL_ETA),
        "metal-Al-k" => zip(&PALIK_NM, &AL_K),
        "metal-Au-eta" => zip(&PALIK_NM, &AU_ETA),
        "metal-Au-k" => zip(&PALIK_NM, &AU_K),
        "metal-Cu-eta" => zip(&PALIK_NM, &CU_ETA),
        "metal-Cu-k" => zip(&PALIK_NM, &CU_K),
        "metal-CuZn-eta" => every10(290.0, &CUZN_ETA),
        "metal-CuZn-k" => every10(290.0, &CUZN_K),
        "metal-MgO-eta" => zip(&MGO_NM, &MGO_ETA),
        "metal-MgO-k" => zip(&MGO_NM, &MGO_K),
        "metal-TiO2-eta" => zip(&TIO2_NM, &TIO2_ETA),
        "metal-TiO2-k" => zip(&TIO2_NM, &TIO2_K),
        "stdillum-A" => {
            return illuminant(
                (300..=830)
                    .step_by(5)
                    .map(|l| (l as f64, illuminant_a(l as f64)))
                    .collect(),
            )
        }
        "stdillum-D50" => return illuminant(illum::D50.samples()),
        "stdillum-D65" => return illuminant(illum::D65.samples()),
        "illum-acesD60" => return illuminant(daylight_xy(0.32168, 0.33767)),
        _ => {
            let n: usize = name.strip_prefix("stdillum-F")?.parse().ok()?;
            let t = [
                &illum::F1,
                &illum::F2,
                &illum::F3,
                &illum::F4,
                &illum::F5,
                &illum::F6,
                &illum::F7,
                &illum::F8,
                &illum::F9,
                &illum::F10,
                &illum::F11,
                &illum::F12,
            ];
            return illuminant(t.get(n.checked_sub(1)?)?.samples());
        }
    };
    Some(Spectrum::Piecewise(extended(samples)))
}

/// pbrt-v4 extends named spectra by their end values to cover 360-830 nm.
fn extended(mut s: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    if s[0].0 > LAMBDA_MIN {
        s.insert(0, (LAMBDA_MIN - 1.0, s[0].1));
    }
    let last = s[s.len() - 1];
    if last.0 < LAMBDA_MAX {
        s.push((LAMBDA_MAX + 1.0, last.1));
    }
    s
}

/// Scales an illuminant to luminance 1: `Σ ȳ S = CIE_Y_INTEGRAL`.
fn normalised(s: Vec<(f64, f64)>) -> Spectrum {
    let s = Spectrum::Piecewise(s);
    let y = xyz(&s)[1];
    s.scaled(CIE_Y_INTEGRAL / y)
}

/// CIE standard illuminant A (relative power, 100 at 560 nm): Planck's law
/// at 2856 K, which the CIE's defining formula writes as 2848 K with the
/// older radiation constant c2 = 1.435e7 nm K.
pub fn illuminant_a(nm: f64) -> f64 {
    let c: f64 = 1.435e7 / 2848.0;
    100.0 * (560.0 / nm).powi(5) * (c / 560.0).exp_m1() / (c / nm).exp_m1()
}

/// A CIE daylight (D series) spectrum of chromaticity `x`, `y`, from the
/// basis functions S0, S1, S2 (CIE 15:2004, 10 nm steps).
pub fn daylight_xy(x: f64, y: f64) -> Vec<(f64, f64)> {
    let m = 0.0241 + 0.2562 * x - 0.7341 * y;
    let m1 = (-1.3515 - 1.7703 * x + 5.9114 * y) / m;
    let m2 = (0.0300 - 31.4424 * x + 30.0717 * y) / m;
    let (s0, s1, s2) = (
        illum::D_S0.samples(),
        illum::D_S1.samples(),
        illum::D_S2.samples(),
    );
    s0.iter()
        .zip(&s1)
        .zip(&s2)
        .map(|((a, b), c)| (a.0, a.1 + m1 * b.1 + m2 * c.1))
        .collect()
}

/// The CIE daylight illuminant of correlated colour temperature `cct`
/// (4000-25000 K): its chromaticity by the CIE's formula, then its spectrum.
pub fn daylight(cct: f64) -> Spectrum {
    let t = cct.clamp(4000.0, 25000.0);
    let x = if t <= 7000.0 {
        -4.6070e9 / t.powi(3) + 2.9678e6 / (t * t) + 0.09911e3 / t + 0.244063
    } else {
        -2.0064e9 / t.powi(3) + 1.9018e6 / (t * t) + 0.24748e3 / t + 0.237040
    };
    let y = -3.0 * x * x + 2.870 * x - 0.275;
    Spectrum::Piecewise(daylight_xy(x, y))
}

#[cfg(test)]
mod tests;
