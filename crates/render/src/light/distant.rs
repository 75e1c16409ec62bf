//! Directional light from infinitely far away.

use super::{LeSample, LiSample};
use crate::geometry::{Aabb, Ray};
use lumis_math::sampling::square_to_disk_concentric;
use lumis_math::{Frame, Rgb, Vec2, Vec3, PI};

#[derive(Clone, Debug)]
pub struct DistantLight {
    /// Unit direction towards the light.
    pub w_light: Vec3,
    /// Radiance scale such that irradiance on a perpendicular surface is `l`.
    pub l: Rgb,
    pub scene_center: Vec3,
    pub scene_radius: f32,
}

impl DistantLight {
    pub fn preprocess(&mut self, b: &Aabb) {
        let (c, r) = b.bounding_sphere();
        self.scene_center = c;
        self.scene_radius = r.max(1e-3);
    }

    pub fn sample_li(&self, p_ref: Vec3) -> Option<LiSample> {
        let p_light = p_ref + self.w_light * (2.0 * self.scene_radius);
        Some(LiSample {
            wi: self.w_light,
            li: self.l,
            pdf: 1.0,
            p_light,
            n_light: Vec3::ZERO,
            delta: true,
            infinite: true,
        })
    }

    pub fn sample_le(&self, u: Vec2) -> Option<LeSample> {
        let frame = Frame::from_normal(-self.w_light);
        let d = square_to_disk_concentric(u) * self.scene_radius;
        let p =
            self.scene_center + self.w_light * self.scene_radius + frame.s * d.x + frame.t * d.y;
        Some(LeSample {
            ray: Ray::new(p, -self.w_light),
            le: self.l,
            pdf_pos: 1.0 / (PI * self.scene_radius * self.scene_radius),
            pdf_dir: 1.0,
            n: Vec3::ZERO,
            delta_pos: false,
            delta_dir: true,
        })
    }

    pub fn power(&self) -> Rgb {
        self.l * (PI * self.scene_radius * self.scene_radius)
    }
}
