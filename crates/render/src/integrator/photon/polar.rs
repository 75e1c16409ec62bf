//! A light-wide test of a caustic photon's polar angle, made before the
//! point on the light is sampled.
//!
//! A caustic photon from a flat area light is refused by its polar angle
//! in [`crate::light::AreaLight::sample_le_culled`] (the cone test at the sampled point)
//! and by [`Targets::may_hit`] after its ray is made. On a small light most
//! refused photons are refused by their polar angle alone, but only after
//! the point, its ray origin and the cone test were computed. Here each
//! flat light gets, per side, the polar angles at which a ray from
//! anywhere on it may meet one of the start spheres; a photon whose
//! direction sample falls outside them is refused before its point is
//! sampled ([`EmitCull::polar_may_pass`]).
//! The windows are conservative by margins well above rounding, so a
//! photon they refuse is one `may_hit` refuses: the photons traced, and
//! the maps, are those without them.

use super::aim::{padded_r2, Targets};
use crate::light::{EmitCull, Light};
use crate::scene::Scene;
use lumis_math::Vec3;

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
    /// The windows of the scene's lights towards the start spheres `starts`.
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

    /// What light `li`'s caustic photons are culled by: its windows (if it
    /// has any) before its point is sampled, the cone test of `starts` (the
    /// spheres the windows were made for) after.
    #[inline]
    pub fn cull<'a>(&'a self, li: u32, starts: &'a Targets) -> LightCull<'a> {
        LightCull {
            starts,
            windows: self.lights.get(li as usize).and_then(Option::as_ref),
        }
    }
}

/// One light's [`EmitCull`] for caustic photons.
pub struct LightCull<'a> {
    starts: &'a Targets,
    windows: Option<&'a [Ranges; 2]>,
}

impl EmitCull for LightCull<'_> {
    fn cone_may_pass(&self, o: Vec3, n: Vec3, sin_t: f32, cos_t: f32) -> bool {
        self.starts.cone_may_pass(o, n, sin_t, cos_t)
    }

    fn polar_may_pass(&self, back: bool, cos_t: f32) -> bool {
        self.windows.is_none_or(|w| {
            w[back as usize]
                .iter()
                .any(|&(lo, hi)| lo <= cos_t && cos_t <= hi)
        })
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
