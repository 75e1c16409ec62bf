//! Beckmann: `D`, Smith's `Lambda` (Walter et al. 2007's rational fit, as
//! pbrt-v3, Mitsuba and Tungsten use it) and sampling of `D(wm) cos(theta_m)`
//! (pbrt-v3's non-visible-area method).

use super::Microfacet;
use lumis_math::{Vec2, Vec3, PI};

/// `D` from the scaled squared slope `e` and `pi alpha_x alpha_y cos^4`.
pub(super) fn d(e: f32, norm: f32) -> f32 {
    (-e).exp() / norm
}

/// `Lambda` from `alpha^2 tan^2(theta)`: with `a = 1 / (alpha tan(theta))`,
/// `(1 - 1.259 a + 0.396 a^2) / (3.535 a + 2.181 a^2)` below `a = 1.6`, else 0.
pub(super) fn lambda(a2t2: f32) -> f32 {
    if a2t2 <= 0.0 {
        return 0.0;
    }
    let a = 1.0 / a2t2.sqrt();
    if a >= 1.6 {
        return 0.0;
    }
    (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a)
}

/// A normal with density `D(wm) cos(theta_m)` (upper hemisphere).
pub(super) fn sample_wm(m: &Microfacet, u: Vec2) -> Option<Vec3> {
    // -ln(1 - u0) is exponential: the scaled squared slope of `D`.
    let e = -(1.0 - u.x).ln();
    if !e.is_finite() {
        return None;
    }
    let (phi, tan2) = if m.alpha_x == m.alpha_y {
        (2.0 * PI * u.y, e * m.alpha_x * m.alpha_x)
    } else {
        // Azimuth with density proportional to the slope ellipse's extent.
        let mut phi = (m.alpha_y / m.alpha_x * (2.0 * PI * u.y + 0.5 * PI).tan()).atan();
        if u.y > 0.5 {
            phi += PI;
        }
        let (s, c) = phi.sin_cos();
        let k = c * c / (m.alpha_x * m.alpha_x) + s * s / (m.alpha_y * m.alpha_y);
        (phi, e / k)
    };
    let cos = 1.0 / (1.0 + tan2).sqrt();
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let (sp, cp) = phi.sin_cos();
    Some(Vec3::new(sin * cp, sin * sp, cos))
}
