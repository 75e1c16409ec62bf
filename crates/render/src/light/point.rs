//! Isotropic point light.

use super::{LeSample, LiSample};
use crate::geometry::Ray;
use lumis_math::sampling::{square_to_uniform_sphere, UNIFORM_SPHERE_PDF};
use lumis_math::{Rgb, Vec2, Vec3, PI};

#[derive(Clone, Debug)]
pub struct PointLight {
    pub pos: Vec3,
    /// Radiant intensity, scale included.
    pub intensity: Rgb,
}

impl PointLight {
    pub fn sample_li(&self, p_ref: Vec3) -> Option<LiSample> {
        let d = self.pos - p_ref;
        let dist2 = d.length_squared();
        if dist2 == 0.0 {
            return None;
        }
        let wi = d / dist2.sqrt();
        Some(LiSample {
            wi,
            li: self.intensity / dist2,
            pdf: 1.0,
            p_light: self.pos,
            n_light: Vec3::ZERO,
            delta: true,
            infinite: false,
        })
    }

    pub fn sample_le(&self, u: Vec2) -> Option<LeSample> {
        let d = square_to_uniform_sphere(u);
        Some(LeSample {
            ray: Ray::new(self.pos, d),
            le: self.intensity,
            pdf_pos: 1.0,
            pdf_dir: UNIFORM_SPHERE_PDF,
            n: Vec3::ZERO,
            delta_pos: true,
            delta_dir: false,
        })
    }

    pub fn power(&self) -> Rgb {
        self.intensity * (4.0 * PI)
    }
}
