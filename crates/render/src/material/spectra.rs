//! RGB reductions of named spectra pbrt-v4 ships (linear sRGB primaries).
//! Values: the usual RGB fits of measured complex IORs (as used by
//! Mitsuba and Tungsten for their RGB modes).

use lumis_math::Rgb;

/// `(eta, k)` of a named metal, e.g. "metal-Cu-eta" / "metal-Cu-k".
pub fn metal(name: &str) -> Option<(Rgb, Rgb)> {
    let base = name.strip_prefix("metal-")?;
    let base = base
        .strip_suffix("-eta")
        .or_else(|| base.strip_suffix("-k"))?;
    Some(match base {
        "Ag" => (
            Rgb::new(0.155_265, 0.116_723, 0.138_342),
            Rgb::new(4.828_35, 3.122_25, 2.146_96),
        ),
        "Al" => (
            Rgb::new(1.657_46, 0.880_369, 0.521_229),
            Rgb::new(9.223_87, 6.269_52, 4.837),
        ),
        "Au" => (
            Rgb::new(0.143_119, 0.374_957, 1.442_48),
            Rgb::new(3.983_16, 2.385_72, 1.603_22),
        ),
        "Cu" => (
            Rgb::new(0.200_438, 0.924_033, 1.102_21),
            Rgb::new(3.912_95, 2.452_85, 2.142_19),
        ),
        "CuZn" => (Rgb::new(0.444, 0.527, 1.094), Rgb::new(3.695, 2.765, 1.829)),
        _ => return None,
    })
}

/// Named metal spectrum component: eta for "-eta" names, k for "-k" names.
pub fn metal_component(name: &str) -> Option<Rgb> {
    let (eta, k) = metal(name)?;
    Some(if name.ends_with("-eta") { eta } else { k })
}

/// Index of refraction of a named glass at ~550 nm.
pub fn glass_ior(name: &str) -> Option<f32> {
    Some(match name {
        "glass-BK7" => 1.5185,
        "glass-BAF10" => 1.6700,
        "glass-FK51A" => 1.4866,
        "glass-LASF9" => 1.8503,
        "glass-F5" | "glass-SF5" => 1.6034,
        "glass-F10" | "glass-SF10" => 1.7283,
        "glass-F11" | "glass-SF11" => 1.7847,
        "fused-silica" | "glass-fused-silica" => 1.4585,
        _ => return None,
    })
}

/// Piecewise Gaussian fit of the CIE 1931 colour matching functions
/// (Wyman, Sloan & Shirley 2013, multi-lobe fit).
fn cie_xyz(lambda: f32) -> [f32; 3] {
    fn g(l: f32, mu: f32, s1: f32, s2: f32) -> f32 {
        let s = if l < mu { s1 } else { s2 };
        (-0.5 * ((l - mu) / s).powi(2)).exp()
    }
    let x = 1.056 * g(lambda, 599.8, 37.9, 31.0) + 0.362 * g(lambda, 442.0, 16.0, 26.7)
        - 0.065 * g(lambda, 501.1, 20.4, 26.2);
    let y = 0.821 * g(lambda, 568.8, 46.9, 40.5) + 0.286 * g(lambda, 530.9, 16.3, 31.1);
    let z = 1.217 * g(lambda, 437.0, 11.8, 36.0) + 0.681 * g(lambda, 459.0, 26.0, 13.8);
    [x, y, z]
}

fn xyz_to_linear_srgb(c: [f64; 3]) -> Rgb {
    let [x, y, z] = c;
    Rgb::new(
        (3.240_454_2 * x - 1.537_138_5 * y - 0.498_531_4 * z) as f32,
        (-0.969_266 * x + 1.876_010_8 * y + 0.041_556 * z) as f32,
        (0.055_643_4 * x - 0.204_025_9 * y + 1.057_225_2 * z) as f32,
    )
}

/// Integrates `s(lambda)` against the CMFs over 360-830 nm; returns XYZ and the
/// integral of y-bar (for normalisation).
fn integrate(s: impl Fn(f32) -> f32) -> ([f64; 3], f64) {
    let mut xyz = [0.0f64; 3];
    let mut ysum = 0.0f64;
    let mut l = 360.0f32;
    while l <= 830.0 {
        let c = cie_xyz(l);
        let v = s(l) as f64;
        for i in 0..3 {
            xyz[i] += c[i] as f64 * v;
        }
        ysum += c[1] as f64;
        l += 1.0;
    }
    (xyz, ysum)
}

/// Colour of a blackbody at `kelvin`, normalised to luminance 1 (pbrt-v4
/// normalises blackbody emitters so that `scale` sets their brightness).
pub fn blackbody_rgb(kelvin: f32) -> Rgb {
    if !(kelvin > 0.0) {
        return Rgb::BLACK;
    }
    let planck = |l_nm: f32| -> f32 {
        let l = l_nm as f64 * 1e-9;
        let (c, h, kb) = (299_792_458.0f64, 6.626_068_96e-34f64, 1.380_650_4e-23f64);
        let v =
            (2.0 * h * c * c) / (l.powi(5) * (((h * c) / (l * kb * kelvin as f64)).exp() - 1.0));
        v as f32
    };
    let (xyz, _) = integrate(planck);
    let y = xyz[1];
    if !(y > 0.0) {
        return Rgb::BLACK;
    }
    xyz_to_linear_srgb([xyz[0] / y, 1.0, xyz[2] / y])
}

/// A piecewise-linear spectrum given as (wavelength nm, value) pairs, reduced
/// to RGB. `illuminant`: keep absolute scale normalised so that a constant 1
/// maps to luminance 1 (as for reflectances).
pub fn sampled_rgb(pairs: &[(f32, f32)]) -> Rgb {
    if pairs.is_empty() {
        return Rgb::BLACK;
    }
    let eval = |l: f32| -> f32 {
        if l <= pairs[0].0 {
            return pairs[0].1;
        }
        if l >= pairs[pairs.len() - 1].0 {
            return pairs[pairs.len() - 1].1;
        }
        let i = pairs.partition_point(|p| p.0 <= l).max(1);
        let (a, b) = (pairs[i - 1], pairs[i]);
        let t = (l - a.0) / (b.0 - a.0).max(1e-6);
        a.1 + t * (b.1 - a.1)
    };
    let (xyz, ysum) = integrate(eval);
    let rgb = xyz_to_linear_srgb([xyz[0] / ysum, xyz[1] / ysum, xyz[2] / ysum]);
    // White-balance per channel (von Kries in RGB) so that a constant spectrum maps to
    // grey: the equal-energy white point is pinkish in sRGB's D65 primaries.
    let (wxyz, _) = integrate(|_| 1.0);
    let white = xyz_to_linear_srgb([wxyz[0] / ysum, wxyz[1] / ysum, wxyz[2] / ysum]);
    rgb / white
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blackbody_has_unit_luminance_and_plausible_hue() {
        let warm = blackbody_rgb(2700.0);
        let cool = blackbody_rgb(10000.0);
        assert!((warm.luminance() - 1.0).abs() < 0.02);
        assert!(warm.r > warm.b && cool.b > cool.r);
        let d65ish = blackbody_rgb(6500.0);
        assert!((d65ish.r / d65ish.b - 1.0).abs() < 0.35, "{d65ish:?}");
    }

    #[test]
    fn constant_spectrum_is_near_grey() {
        let c = sampled_rgb(&[(400.0, 0.5), (700.0, 0.5)]);
        assert!((c.luminance() - 0.5).abs() < 0.02);
        assert!(
            (c.r - c.b).abs() < 1e-3 && (c.g - 0.5).abs() < 1e-3,
            "{c:?}"
        );
    }

    #[test]
    fn named_metals() {
        assert!(metal_component("metal-Au-eta").is_some());
        assert!(metal_component("metal-Xx-eta").is_none());
    }
}
