//! Spot light: pbrt-v4's smoothstep falloff between the cone's inner and outer angles.

use super::{LeSample, LiSample};
use crate::geometry::Ray;
use lumis_math::sampling::{square_to_uniform_cone, uniform_cone_pdf};
use lumis_math::{Frame, Rgb, Vec2, Vec3, PI};

#[derive(Clone, Debug)]
pub struct SpotLight {
    pub pos: Vec3,
    pub frame: Frame,
    pub intensity: Rgb,
    pub cos_falloff_start: f32,
    pub cos_falloff_end: f32,
}

fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    if a == b {
        return if x < a { 0.0 } else { 1.0 };
    }
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl SpotLight {
    /// Intensity in world direction `w` leaving the light.
    pub fn i(&self, w: Vec3) -> Rgb {
        let cos = self.frame.n.dot(w);
        self.intensity * smoothstep(self.cos_falloff_end, self.cos_falloff_start, cos)
    }

    pub fn sample_li(&self, p_ref: Vec3) -> Option<LiSample> {
        LiSample::from_point(self.pos, p_ref, |w| self.i(w))
    }

    /// Solid-angle density of [`SpotLight::sample_le`]'s direction `w`:
    /// uniform over the outer cone.
    pub fn pdf_dir(&self, w: Vec3) -> f32 {
        if self.frame.n.dot(w) >= self.cos_falloff_end {
            uniform_cone_pdf(self.cos_falloff_end)
        } else {
            0.0
        }
    }

    pub fn sample_le(&self, u: Vec2) -> Option<LeSample> {
        let local = square_to_uniform_cone(u, self.cos_falloff_end);
        let d = self.frame.to_world(local);
        Some(LeSample {
            ray: Ray::new(self.pos, d),
            le: self.i(d),
            pdf_pos: 1.0,
            pdf_dir: uniform_cone_pdf(self.cos_falloff_end),
            n: Vec3::ZERO,
            delta_pos: true,
            delta_dir: false,
        })
    }

    pub fn power(&self) -> Rgb {
        // Integral of the smoothstep falloff over the sphere (pbrt-v4's closed form).
        self.intensity
            * (2.0
                * PI
                * ((1.0 - self.cos_falloff_start)
                    + (self.cos_falloff_start - self.cos_falloff_end) / 2.0))
    }
}
