//! pbrt-v4's film white balance (`Film "rgb" "float whitebalance" [T]` with
//! the default `cie1931` sensor): a von Kries adaptation in the Bradford
//! cone space from the white of a daylight illuminant of temperature `T`
//! (a blackbody below 4000 K) to the output colour space's white (D65).
//! lumis renders in linear sRGB, so the adaptation is applied to the
//! finished image as one 3x3 matrix on linear sRGB, which is what pbrt-v4's
//! per-sample matrix amounts to (the film is linear).

use super::{daylight, xyz, xyz_to_linear_srgb, Spectrum};
use glam::{DMat3, DVec3, Mat3};

/// Bradford's XYZ to cone-response (LMS) matrix.
fn lms_from_xyz() -> DMat3 {
    DMat3::from_cols_array(&[
        0.8951, -0.7502, 0.0389, 0.2664, 1.7135, -0.0685, -0.1614, 0.0367, 1.0296,
    ])
}

/// The illuminant pbrt-v4 balances for at `kelvin`: the temperature is
/// first rescaled by 1.4388 / 1.4380 (the radiation constant's revision),
/// then a CIE daylight, or a blackbody below 4000 K.
pub fn white_balance_illuminant(kelvin: f64) -> Spectrum {
    let cct = kelvin * 1.4388 / 1.4380;
    if cct < 4000.0 {
        Spectrum::Blackbody(cct)
    } else {
        daylight(cct)
    }
}

/// The linear-sRGB matrix that maps the white of [`white_balance_illuminant`]
/// (`kelvin`) to D65 white (rgb 1, 1, 1) by Bradford adaptation.
pub fn white_balance(kelvin: f64) -> Mat3 {
    let src = xyz(&white_balance_illuminant(kelvin));
    let src = DVec3::new(src[0] / src[1], 1.0, src[2] / src[1]);
    // D65 as lumis' matrices see it: the XYZ of rgb (1, 1, 1).
    let xyz_of = |c: usize| {
        let mut e = [0.0; 3];
        e[c] = 1.0;
        let r = xyz_to_linear_srgb(e);
        DVec3::new(r.r as f64, r.g as f64, r.b as f64)
    };
    // Columns of XYZ -> RGB are the RGB of unit X, Y, Z.
    let rgb_from_xyz = DMat3::from_cols(xyz_of(0), xyz_of(1), xyz_of(2));
    let xyz_from_rgb = rgb_from_xyz.inverse();
    let dst = xyz_from_rgb * DVec3::ONE;
    let m = lms_from_xyz();
    let (s, d) = (m * src, m * dst);
    let adapt = m.inverse() * DMat3::from_diagonal(d / s) * m;
    (rgb_from_xyz * adapt * xyz_from_rgb).as_mat3()
}
