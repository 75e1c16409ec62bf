//! Trowbridge-Reitz (GGX): `D`, Smith's `Lambda` and visible-normal
//! sampling (Heitz 2018), as pbrt-v4 has them.

use super::Microfacet;
use lumis_math::{lerp, safe_sqrt, sampling::square_to_disk_concentric, Vec2, Vec3};

/// `D` from the scaled squared slope `e` and `pi alpha_x alpha_y cos^4`.
pub(super) fn d(e: f32, norm: f32) -> f32 {
    1.0 / (norm * (1.0 + e) * (1.0 + e))
}

/// `Lambda` from `alpha^2 tan^2(theta)` along the direction's azimuth.
pub(super) fn lambda(a2t2: f32) -> f32 {
    ((1.0 + a2t2).sqrt() - 1.0) / 2.0
}

/// A visible normal from `w` (upper hemisphere).
pub(super) fn sample_wm(m: &Microfacet, w: Vec3, u: Vec2) -> Vec3 {
    // Stretch to the hemisphere configuration (alpha = 1).
    let wh = Vec3::new(m.alpha_x * w.x, m.alpha_y * w.y, w.z).normalize();
    let t1 = if wh.z < 0.99999 {
        Vec3::Z.cross(wh).normalize()
    } else {
        Vec3::X
    };
    let t2 = wh.cross(t1);
    // Uniform disk point, warped to the projected visible hemisphere.
    let mut p = square_to_disk_concentric(u);
    let h = safe_sqrt(1.0 - p.x * p.x);
    p.y = lerp((1.0 + wh.z) / 2.0, h, p.y);
    let pz = safe_sqrt(1.0 - p.length_squared());
    let nh = p.x * t1 + p.y * t2 + pz * wh;
    // Unstretch.
    Vec3::new(m.alpha_x * nh.x, m.alpha_y * nh.y, nh.z.max(1e-6)).normalize()
}
