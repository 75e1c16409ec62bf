//! pbrt-v4's named spectra (metals, glasses, standard illuminants) and the
//! CIE illuminants computed from formulas (A, the D series).

use super::{illum, optical, xyz, Spectrum, Table, CIE_Y_INTEGRAL, LAMBDA_MAX, LAMBDA_MIN};

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
