use super::*;

fn close(a: Rgb, b: Rgb, tol: f32) -> bool {
    (a.r - b.r).abs() <= tol && (a.g - b.g).abs() <= tol && (a.b - b.b).abs() <= tol
}

fn chromaticity(s: &Spectrum) -> (f64, f64) {
    let c = xyz(s);
    let sum = c[0] + c[1] + c[2];
    (c[0] / sum, c[1] / sum)
}

use crate::Rgb;

#[test]
fn y_integral_is_the_tables_sum() {
    let sum: f64 = cie::CMF.iter().map(|c| c[1] as f64).sum();
    assert!((sum - CIE_Y_INTEGRAL).abs() < 1e-4, "{sum}");
    // A constant 1 has luminance `CIE_Y_INTEGRAL`.
    assert!((xyz(&Spectrum::Constant(1.0))[1] - CIE_Y_INTEGRAL).abs() < 1e-4);
}

#[test]
fn d65_is_white_and_constant_reflectances_are_grey() {
    let d65 = named("stdillum-D65").unwrap();
    let w = illuminant_rgb(&d65);
    assert!(close(w, Rgb::WHITE, 1e-6), "{w:?}");
    // D65's chromaticity as the CIE gives it (0.31272, 0.32903).
    let (x, y) = chromaticity(&d65);
    assert!(
        (x - 0.31272).abs() < 5e-5 && (y - 0.32903).abs() < 5e-5,
        "{x} {y}"
    );
    let half = reflectance_rgb(&Spectrum::Constant(0.5));
    assert!(close(half, Rgb::splat(0.5), 1e-6), "{half:?}");
    let one = reflectance_rgb(&Spectrum::piecewise(vec![(300.0, 1.0), (900.0, 1.0)]).unwrap());
    assert!(close(one, Rgb::WHITE, 1e-6), "{one:?}");
    assert!((mean_under_white(&Spectrum::Constant(1.7)) - 1.7).abs() < 1e-9);
}

#[test]
fn standard_illuminants_have_their_published_chromaticities() {
    // CIE 15:2004 table T.3/T.8 (2-degree observer).
    for (name, x0, y0) in [
        ("stdillum-A", 0.44757, 0.40745),
        ("stdillum-D50", 0.34567, 0.35850),
        ("stdillum-F2", 0.37208, 0.37529),
        ("stdillum-F7", 0.31292, 0.32933),
        ("stdillum-F11", 0.38052, 0.37713),
        ("illum-acesD60", 0.32168, 0.33767),
    ] {
        let (x, y) = chromaticity(&named(name).unwrap());
        assert!(
            (x - x0).abs() < 6e-4 && (y - y0).abs() < 6e-4,
            "{name}: {x} {y}"
        );
    }
}

#[test]
fn every_name_resolves_and_illuminants_have_unit_luminance() {
    for n in NAMED {
        let s = named(n).unwrap_or_else(|| panic!("{n}"));
        if n.contains("illum") {
            let y = xyz(&s)[1] / CIE_Y_INTEGRAL;
            assert!((y - 1.0).abs() < 1e-9, "{n}: {y}");
            let c = illuminant_rgb(&s);
            assert!((c.luminance() - 1.0).abs() < 2e-3, "{n}: {c:?}");
        }
    }
    assert!(named("stdillum-F13").is_none() && named("metal-Xx-eta").is_none());
    // Named spectra extend their end values over 360-830 nm (pbrt-v4).
    let tio2 = named("metal-TiO2-eta").unwrap();
    let want = 2.79 + (830.0 - 819.974) / (839.973 - 819.974) * (2.78 - 2.79);
    assert!((tio2.eval(830.0) - want).abs() < 1e-6);
    let cuzn = named("metal-CuZn-k").unwrap();
    assert!((cuzn.eval(295.0) - 0.5 * (1.688 + 1.731)).abs() < 1e-6);
}

#[test]
fn blackbody_is_peak_normalised_and_has_the_right_colour() {
    for t in [1000.0, 3000.0, 6504.0, 20000.0] {
        let b = Spectrum::Blackbody(t);
        let peak_nm = 2.897_772_1e-3 / t * 1e9;
        assert!((b.eval(peak_nm) - 1.0).abs() < 1e-12);
        let max = (1..3000).map(|l| b.eval(l as f64)).fold(0.0, f64::max);
        assert!(max <= 1.0 + 1e-9 && max > 0.999, "{t}: {max}");
    }
    let warm = illuminant_rgb(&Spectrum::Blackbody(3000.0));
    assert!((warm.luminance() - 1.0).abs() < 2e-3, "{warm:?}");
    assert!(warm.r > warm.g && warm.g > warm.b, "{warm:?}");
    // 6504 K is D65's correlated colour temperature, but the blackbody lies
    // off the daylight locus: within 5% of white per channel, and closer to
    // white than 5500 K or 8000 K.
    let d = |t: f64| {
        let c = illuminant_rgb(&Spectrum::Blackbody(t));
        ((c.r - 1.0).powi(2) + (c.g - 1.0).powi(2) + (c.b - 1.0).powi(2)).sqrt()
    };
    let w = illuminant_rgb(&Spectrum::Blackbody(6504.0));
    assert!(close(w, Rgb::WHITE, 0.05), "{w:?}");
    assert!(d(6504.0) < d(5500.0) && d(6504.0) < d(8000.0));
}

#[test]
fn sampled_spectra_are_checked_and_interpolated() {
    assert!(Spectrum::piecewise(vec![]).is_err());
    let e = Spectrum::piecewise(vec![(500.0, 1.0), (400.0, 2.0)]).unwrap_err();
    assert!(e.contains("increase"), "{e}");
    assert!(Spectrum::piecewise(vec![(500.0, f64::NAN)]).is_err());
    let s = Spectrum::piecewise(vec![(400.0, 1.0), (500.0, 3.0)]).unwrap();
    assert_eq!(s.eval(450.0), 2.0);
    assert_eq!(s.eval(399.0), 0.0);
    assert_eq!(s.eval(501.0), 0.0);
    assert!(!s.is_constant() && Spectrum::Constant(2.0).is_constant());
}

#[test]
fn glass_indices_are_their_luminance_weighted_means() {
    let bk7 = mean_under_white(&named("glass-BK7").unwrap());
    // n(540 nm) = 1.51893, n(586 nm) = 1.51687: the luminance peak lies between.
    assert!(bk7 > 1.5169 && bk7 < 1.5190, "{bk7}");
    let sf11 = mean_under_white(&named("glass-F11").unwrap());
    assert!(sf11 > 1.78 && sf11 < 1.80, "{sf11}");
}

#[test]
fn fresnel_conductor_limits() {
    // Normal incidence: ((n-1)² + k²) / ((n+1)² + k²).
    let f = fresnel_conductor(1.0, 0.2, 3.0);
    assert!((f - (0.64 + 9.0) / (1.44 + 9.0)).abs() < 1e-12);
    // Grazing: 1; k = 0: the dielectric's Fresnel reflectance.
    assert!((fresnel_conductor(0.0, 0.5, 2.0) - 1.0).abs() < 1e-12);
    let cos_i: f64 = 0.6;
    let n: f64 = 1.5;
    let cos_t = (1.0 - (1.0 - cos_i * cos_i) / (n * n)).sqrt();
    let rs = ((cos_i - n * cos_t) / (cos_i + n * cos_t)).powi(2);
    let rp = ((n * cos_i - cos_t) / (n * cos_i + cos_t)).powi(2);
    assert!((fresnel_conductor(cos_i, n, 0.0) - 0.5 * (rs + rp)).abs() < 1e-12);
}

/// The spectral Fresnel curve of a named metal reduced per channel.
fn metal_target(m: &str, mu: f64) -> Rgb {
    let (eta, k) = (
        named(&format!("metal-{m}-eta")).unwrap(),
        named(&format!("metal-{m}-k")).unwrap(),
    );
    let r: Vec<(f64, f64)> = (300..=900)
        .map(|l| {
            (
                l as f64,
                fresnel_conductor(mu, eta.eval(l as f64), k.eval(l as f64)),
            )
        })
        .collect();
    reflectance_rgb(&Spectrum::Piecewise(r))
}

#[test]
fn fitted_metals_match_their_spectral_fresnel_curves() {
    for m in ["Ag", "Al", "Au", "Cu", "CuZn"] {
        let (eta, k) = conductor_rgb(
            &named(&format!("metal-{m}-eta")).unwrap(),
            &named(&format!("metal-{m}-k")).unwrap(),
        );
        let f = |mu: f64| {
            Rgb::new(
                fresnel_conductor(mu, eta.r as f64, k.r as f64) as f32,
                fresnel_conductor(mu, eta.g as f64, k.g as f64) as f32,
                fresnel_conductor(mu, eta.b as f64, k.b as f64) as f32,
            )
        };
        // Head-on: the same colour, except where white light's reflection
        // exceeds 1 in a channel (gold's red: 1.022), which a Fresnel
        // reflectance cannot reach: that channel is clamped just below 1.
        let (t, got) = (metal_target(m, 1.0), f(1.0));
        let t_clamped = t.map(|v| v.min(0.9999));
        assert!(close(t_clamped, got, 2e-4), "{m}: {got:?} vs {t:?}");
        // At every angle: within 0.02 (the curves of one channel's
        // wavelengths do not all have one conductor's shape).
        for j in 0..20 {
            let mu = (j as f64 + 0.5) / 20.0;
            let (t, got) = (metal_target(m, mu).map(|v| v.min(1.0)), f(mu));
            assert!(close(t, got, 0.02), "{m} cos {mu}: {got:?} vs {t:?}");
        }
    }
    // Gold is yellow: red and green reflect, blue much less.
    let au = metal_target("Au", 1.0);
    assert!(
        au.r > 0.9 && au.g > 0.6 && au.b < 0.45 && au.r > au.g,
        "{au:?}"
    );
}

#[test]
fn white_balance_maps_its_illuminant_to_white() {
    for t in [2700.0, 3000.0, 5000.0, 10000.0] {
        let m = white_balance(t);
        let c = illuminant_rgb(&white_balance_illuminant(t));
        let v = m * glam::Vec3::new(c.r, c.g, c.b);
        // The adaptation takes that white (luminance 1) exactly to D65 white.
        assert!(
            (v - glam::Vec3::ONE).abs().max_element() < 1e-4,
            "{t}: {v:?}"
        );
    }
    // Balancing for D65 (6504 K is 6507.6 K after pbrt's rescaling, the
    // daylight formula's D65 differs slightly from the table): identity
    // within 0.5%.
    let m = white_balance(6504.0 * 1.4380 / 1.4388);
    let id = glam::Mat3::IDENTITY;
    for (a, b) in m.to_cols_array().iter().zip(id.to_cols_array()) {
        assert!((a - b).abs() < 5e-3, "{m:?}");
    }
    // Balancing for a warm light cools the image down.
    let warm = white_balance(3000.0) * glam::Vec3::ONE;
    assert!(warm.z > warm.x, "{warm:?}");
}
