//! A light-wide test of a caustic photon's polar angle, made before the
//! point on the light is sampled.
//!
//! A caustic photon from a flat area light is refused by its polar angle
//! in [`AreaLight::sample_le_culled`] (the cone test at the sampled point)
//! and by [`Targets::may_hit`] after its ray is made. On a small light most
//! refused photons are refused by their polar angle alone, but only after
//! the point, its ray origin and the cone test were computed. Here each
//! flat light gets, per side, the polar angles at which a ray from
//! anywhere on it may meet one of the start spheres; a photon whose
//! direction sample falls outside them is refused before anything else.
//! The windows are conservative by margins well above rounding, so a
//! photon they refuse is one `may_hit` refuses: the photons traced, and
//! the maps, are those without them.

use super::aim::{padded_r2, Targets};
use crate::light::Light;
use crate::scene::Scene;
use lumis_math::sampling::disk_concentric_radius;
use lumis_math::{safe_sqrt, Vec2, Vec3};

/// Per light, the ranges of `cos(theta)` about each side's normal (front,
/// back) at which a ray from the light may meet a start sphere; None for
/// lights without windows (not flat, textured, or not an area light).
#[derive(Clone, Debug, Default)]
pub struct PolarWindows {
    lights: Vec<Option<[Ranges; 2]>>,
}

/// Ranges `(lo, hi)` of `cos(theta)`, one per start sphere.
type Ranges = Vec<(f32, f32)>;

/// Angle added to each window on both sides: above the rounding of a
/// sampled direction's polar angle (at most about 6e-4 radians, near the
/// horizon).
const SLACK: f64 = 2e-3;

impl PolarWindows {
    pub fn new(scene: &Scene, starts: &Targets) -> PolarWindows {
        let lights = scene
            .lights
            .iter()
            .map(|light| {
                let Light::Area(a) = light else {
                    return None;
                };
                let (corners, n) = a.flat.as_ref()?.corners_and_normal();
                if a.texture.is_some() {
                    return None;
                }
                let (c, r) = bounding_sphere(corners)?;
                let side = |n: Vec3| {
                    (starts.spheres().iter())
                        .map(|&(sc, sr)| window(c, r, n, sc, sr))
                        .collect()
                };
                Some([side(n), side(-n)])
            })
            .collect();
        PolarWindows { lights }
    }

    /// False only when light `li`'s direction sample `u2` gives a polar
    /// angle at which no ray from the light can meet a start sphere.
    #[inline]
    pub fn may_pass(&self, li: u32, light: &Light, u2: Vec2) -> bool {
        let (Some(Some(sides)), Light::Area(a)) = (self.lights.get(li as usize), light) else {
            return true;
        };
        let (back, u) = a.emission_side(u2);
        // The cosine-weighted direction's polar angle, as the light makes it.
        let sin_t = disk_concentric_radius(u);
        let cos_t = safe_sqrt(1.0 - sin_t * sin_t);
        sides[back as usize]
            .iter()
            .any(|&(lo, hi)| lo <= cos_t && cos_t <= hi)
    }
}

/// The triangle's centroid and the distance to its farthest corner, padded
/// for the sampled points' rounding and the ray origin's offset (at most
/// 256 ulps per coordinate); None if not finite.
fn bounding_sphere(corners: [Vec3; 3]) -> Option<(Vec3, f32)> {
    let c = (corners[0] + corners[1] + corners[2]) / 3.0;
    let r = corners
        .iter()
        .map(|v| (*v - c).length())
        .fold(0.0, f32::max);
    let scale = c.abs().max_element() + r;
    let r = r * 1.001 + 1e-4 * scale + 1e-4;
    (c.is_finite() && r.is_finite()).then_some((c, r))
}

/// The range of `cos(theta)` about unit `n` of the directions of rays from
/// points within `rl` of `cl` that may pass within sphere `(c, r)` as
/// `may_hit` pads it.
fn window(cl: Vec3, rl: f32, n: Vec3, c: Vec3, r: f32) -> (f32, f32) {
    let v = c - cl;
    let d = v.length() as f64;
    let (rl, reach) = (rl as f64, d + rl as f64);
    // `may_hit`'s padded radius, at the farthest the origin can be.
    let rp = (padded_r2(r, (reach * reach) as f32) as f64).sqrt() * 1.001;
    if !(d > rl + rp) {
        return (-1.0, 1.0);
    }
    // A ray from `p` passing within `rp` of `c` makes at most
    // asin(rp / |c - p|) with `c - p`, which makes at most asin(rl / d)
    // with `c - cl`.
    let beta = (rp / (d - rl)).asin() + (rl / d).asin() + SLACK;
    let axis = (v.dot(n) as f64 / d).clamp(-1.0, 1.0).acos();
    let (lo, hi) = (
        (axis - beta).max(0.0),
        (axis + beta).min(std::f64::consts::PI),
    );
    (hi.cos() as f32 - 1e-6, lo.cos() as f32 + 1e-6)
}
