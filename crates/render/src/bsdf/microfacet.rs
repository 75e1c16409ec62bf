//! Anisotropic Trowbridge-Reitz (GGX) microfacet distribution with the
//! height-correlated masking-shadowing of pbrt-v4 and visible-normal sampling
//! (Heitz 2018). Directions are in the local shading frame (+z = normal).

use lumis_math::{lerp, safe_sqrt, sampling::square_to_disk_concentric, Vec2, Vec3, PI};

/// Below this roughness a microfacet BSDF is treated as perfectly smooth.
pub const SMOOTH_ALPHA: f32 = 1e-3;

#[inline]
pub(crate) fn cos2_theta(w: Vec3) -> f32 {
    w.z * w.z
}
#[inline]
pub(crate) fn sin2_theta(w: Vec3) -> f32 {
    (1.0 - cos2_theta(w)).max(0.0)
}
#[inline]
pub(crate) fn tan2_theta(w: Vec3) -> f32 {
    sin2_theta(w) / cos2_theta(w)
}
/// `(cos^2 phi, sin^2 phi)`; `(1, 0)` at the pole.
#[inline]
fn cos2_sin2_phi(w: Vec3) -> (f32, f32) {
    let s2 = w.x * w.x + w.y * w.y;
    if s2 <= 0.0 {
        (1.0, 0.0)
    } else {
        let c2 = (w.x * w.x / s2).clamp(0.0, 1.0);
        (c2, 1.0 - c2)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrowbridgeReitz {
    pub alpha_x: f32,
    pub alpha_y: f32,
}

impl TrowbridgeReitz {
    pub fn new(alpha_x: f32, alpha_y: f32) -> Self {
        TrowbridgeReitz { alpha_x, alpha_y }
    }

    /// Too smooth to be sampled as a distribution: use a delta lobe instead.
    pub fn effectively_smooth(&self) -> bool {
        self.alpha_x.max(self.alpha_y) < SMOOTH_ALPHA
    }

    /// Microfacet normal density D(wm), normalized so that the projected area
    /// integrates to one: `∫ D(wm) cos(theta_m) dwm = 1`.
    pub fn d(&self, wm: Vec3) -> f32 {
        let tan2 = tan2_theta(wm);
        if !tan2.is_finite() {
            return 0.0;
        }
        let cos4 = cos2_theta(wm) * cos2_theta(wm);
        if cos4 < 1e-16 {
            return 0.0;
        }
        let (c2, s2) = cos2_sin2_phi(wm);
        let e = tan2 * (c2 / (self.alpha_x * self.alpha_x) + s2 / (self.alpha_y * self.alpha_y));
        1.0 / (PI * self.alpha_x * self.alpha_y * cos4 * (1.0 + e) * (1.0 + e))
    }

    /// Smith's auxiliary function Lambda(w).
    pub fn lambda(&self, w: Vec3) -> f32 {
        let tan2 = tan2_theta(w);
        if !tan2.is_finite() {
            return 0.0;
        }
        let (c2, s2) = cos2_sin2_phi(w);
        let alpha2 = c2 * self.alpha_x * self.alpha_x + s2 * self.alpha_y * self.alpha_y;
        ((1.0 + alpha2 * tan2).sqrt() - 1.0) / 2.0
    }

    /// Masking function.
    pub fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking-shadowing.
    pub fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// Distribution of normals visible from `w`:
    /// `D_w(wm) = G1(w) / |cos w| * D(wm) * max(0, w · wm)`, where `w` is
    /// first flipped to the upper hemisphere (as in [`Self::sample_wm`]).
    /// Normalized: `∫ D_w(wm) dwm = 1`.
    pub fn d_visible(&self, w: Vec3, wm: Vec3) -> f32 {
        let cos = w.z.abs();
        if cos == 0.0 {
            return 0.0;
        }
        let w_up = if w.z < 0.0 { -w } else { w };
        self.g1(w) / cos * self.d(wm) * w_up.dot(wm).max(0.0)
    }

    /// Density of [`Self::sample_wm`] (per solid angle of `wm`).
    pub fn pdf(&self, w: Vec3, wm: Vec3) -> f32 {
        self.d_visible(w, wm)
    }

    /// Sample a visible normal from `w` (Heitz 2018); the result lies in the
    /// upper hemisphere. `w` may be below the surface: it is then flipped.
    pub fn sample_wm(&self, w: Vec3, u: Vec2) -> Vec3 {
        // Stretch to the hemisphere configuration (alpha = 1).
        let mut wh = Vec3::new(self.alpha_x * w.x, self.alpha_y * w.y, w.z).normalize();
        if wh.z < 0.0 {
            wh = -wh;
        }
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
        Vec3::new(self.alpha_x * nh.x, self.alpha_y * nh.y, nh.z.max(1e-6)).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::{sampling::square_to_uniform_hemisphere, Pcg32, INV_2PI};

    fn dists() -> Vec<TrowbridgeReitz> {
        vec![
            TrowbridgeReitz::new(0.1, 0.1),
            TrowbridgeReitz::new(0.3, 0.3),
            TrowbridgeReitz::new(0.8, 0.8),
            TrowbridgeReitz::new(0.1, 0.4),
        ]
    }

    /// `∫ D(wm) cos(theta_m) dwm = 1`, by stratified uniform hemisphere sampling.
    #[test]
    fn projected_area_is_one() {
        for dist in dists() {
            // Stratified in (cos theta, phi) with a jitter: density 1/(2 pi).
            let mut rng = Pcg32::new(5, 1);
            let (nu, nv) = (1000, 200);
            let mut sum = 0.0f64;
            for i in 0..nu {
                for j in 0..nv {
                    let u = Vec2::new(
                        (i as f32 + rng.next_f32()) / nu as f32,
                        (j as f32 + rng.next_f32()) / nv as f32,
                    );
                    let wm = square_to_uniform_hemisphere(u);
                    sum += (dist.d(wm) * wm.z / INV_2PI) as f64;
                }
            }
            let mean = sum / (nu * nv) as f64;
            assert!((mean - 1.0).abs() < 0.01, "{dist:?}: {mean}");
        }
    }

    /// Visible normals integrate to one: `∫ D_w(wm) dwm = 1` for any `w`.
    #[test]
    fn visible_normals_normalized() {
        for dist in dists() {
            for cz in [0.95f32, 0.5, 0.1] {
                let w = Vec3::new(
                    (1.0 - cz * cz).sqrt() * 0.6,
                    (1.0 - cz * cz).sqrt() * 0.8,
                    cz,
                );
                let mut rng = Pcg32::new(9, 3);
                let (nu, nv) = (1000, 200);
                let mut sum = 0.0f64;
                for i in 0..nu {
                    for j in 0..nv {
                        let u = Vec2::new(
                            (i as f32 + rng.next_f32()) / nu as f32,
                            (j as f32 + rng.next_f32()) / nv as f32,
                        );
                        let wm = square_to_uniform_hemisphere(u);
                        sum += (dist.d_visible(w, wm) / INV_2PI) as f64;
                    }
                }
                let mean = sum / (nu * nv) as f64;
                assert!((mean - 1.0).abs() < 0.01, "{dist:?} cos {cz}: {mean}");
            }
        }
    }

    #[test]
    fn sampled_normals_face_the_viewer() {
        let mut rng = Pcg32::new(1, 1);
        for dist in dists() {
            for w in [
                Vec3::new(0.6, 0.0, 0.8),
                Vec3::new(-0.3, 0.2, -0.93).normalize(),
            ] {
                for _ in 0..1000 {
                    let wm = dist.sample_wm(w, Vec2::new(rng.next_f32(), rng.next_f32()));
                    assert!(wm.z > 0.0 && (wm.length() - 1.0).abs() < 1e-4);
                    // Visible from the (flipped) viewer, up to the unstretch clamp.
                    assert!(w.dot(wm) * w.z.signum() > -1e-3);
                }
            }
        }
    }
}
