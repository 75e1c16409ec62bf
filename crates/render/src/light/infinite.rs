//! Constant-radiance environment ("infinite" without a map).

use super::{LeSample, LiSample};
use crate::geometry::{Aabb, Ray};
use lumis_math::sampling::{
    square_to_disk_concentric, square_to_uniform_sphere, UNIFORM_SPHERE_PDF,
};
use lumis_math::{Frame, Rgb, Vec2, Vec3, PI};

#[derive(Clone, Debug)]
pub struct UniformInfiniteLight {
    pub l: Rgb,
    pub scene_center: Vec3,
    pub scene_radius: f32,
}

impl UniformInfiniteLight {
    pub fn preprocess(&mut self, b: &Aabb) {
        let (c, r) = b.bounding_sphere();
        self.scene_center = c;
        self.scene_radius = r.max(1e-3);
    }

    pub fn le(&self, _d: Vec3) -> Rgb {
        self.l
    }

    pub fn sample_li(&self, p_ref: Vec3, u: Vec2) -> Option<LiSample> {
        let wi = square_to_uniform_sphere(u);
        let p_light = p_ref + wi * (2.0 * self.scene_radius);
        Some(LiSample {
            wi,
            li: self.l,
            pdf: UNIFORM_SPHERE_PDF,
            p_light,
            n_light: Vec3::ZERO,
            delta: false,
            infinite: true,
        })
    }

    pub fn pdf_li(&self, _wi: Vec3) -> f32 {
        UNIFORM_SPHERE_PDF
    }

    pub fn sample_le(&self, u1: Vec2, u2: Vec2) -> Option<LeSample> {
        let w = -square_to_uniform_sphere(u1); // direction of travel
        let frame = Frame::from_normal(w);
        let d = square_to_disk_concentric(u2) * self.scene_radius;
        let p = self.scene_center - w * self.scene_radius + frame.s * d.x + frame.t * d.y;
        Some(LeSample {
            ray: Ray::new(p, w),
            le: self.l,
            pdf_pos: 1.0 / (PI * self.scene_radius * self.scene_radius),
            pdf_dir: UNIFORM_SPHERE_PDF,
            n: Vec3::ZERO,
            delta_pos: false,
            delta_dir: false,
        })
    }

    pub fn power(&self) -> Rgb {
        self.l * (4.0 * PI * PI * self.scene_radius * self.scene_radius)
    }
}
