//! Goniometric light (pbrt-v4): a point light whose intensity in each
//! direction is `I` times a monochrome equal-area square image (light-space
//! `y` is the image's pole, pbrt-v4's swap of `y` and `z`). Photons are
//! emitted by importance over the image.

use super::{LeSample, LiSample};
use crate::geometry::Ray;
use lumis_math::sampling::{
    equal_area_sphere_to_square, equal_area_square_to_sphere, wrap_equal_area_pixel,
    PiecewiseConstant2D,
};
use lumis_math::{Mat3, Rgb, Vec2, Vec3, PI};

#[derive(Clone, Debug)]
pub struct GoniometricLight {
    pub pos: Vec3,
    /// Intensity scale (`I` times `scale`).
    intensity: Rgb,
    res: u32,
    /// Image values (non-negative), top row first.
    values: Vec<f32>,
    to_world: Mat3,
    to_light: Mat3,
    distribution: PiecewiseConstant2D,
    mean: f32,
}

impl GoniometricLight {
    /// `values`: a `res` × `res` equal-area image; `to_world` orthogonal
    /// (light space to world, pbrt-v4's `y`/`z` swap included).
    pub fn new(pos: Vec3, intensity: Rgb, res: u32, values: Vec<f32>, to_world: Mat3) -> Self {
        assert_eq!(values.len(), (res * res) as usize);
        let values: Vec<f32> = values.into_iter().map(|v| v.max(0.0)).collect();
        let mean = (values.iter().map(|&v| v as f64).sum::<f64>() / values.len() as f64) as f32;
        GoniometricLight {
            pos,
            intensity,
            res,
            distribution: PiecewiseConstant2D::new(&values, res as usize, res as usize),
            values,
            to_world,
            to_light: to_world.transpose(),
            mean,
        }
    }

    fn texel(&self, uv: Vec2) -> (usize, usize) {
        let r = self.res as i32;
        let (x, y) = wrap_equal_area_pixel(
            (uv.x * r as f32).floor() as i32,
            (uv.y * r as f32).floor() as i32,
            r,
            r,
        );
        (x as usize, y as usize)
    }

    /// Radiant intensity towards world direction `w` (unit).
    pub fn i(&self, w: Vec3) -> Rgb {
        let (x, y) = self.texel(equal_area_sphere_to_square(
            (self.to_light * w).normalize_or_zero(),
        ));
        self.intensity * self.values[y * self.res as usize + x]
    }

    /// Solid-angle density of `sample_le`'s direction `w`.
    pub fn pdf_dir(&self, w: Vec3) -> f32 {
        let (x, y) = self.texel(equal_area_sphere_to_square(
            (self.to_light * w).normalize_or_zero(),
        ));
        self.distribution.pdf_bin(x, y) / (4.0 * PI)
    }

    pub fn sample_li(&self, p_ref: Vec3) -> Option<LiSample> {
        LiSample::from_point(self.pos, p_ref, |w| self.i(w))
    }

    pub fn sample_le(&self, u: Vec2) -> Option<LeSample> {
        let (uv, pdf_uv, (x, y)) = self.distribution.sample(u);
        let w = (self.to_world * equal_area_square_to_sphere(uv)).normalize_or_zero();
        if pdf_uv <= 0.0 || w == Vec3::ZERO {
            return None;
        }
        Some(LeSample {
            ray: Ray::new(self.pos, w),
            le: self.intensity * self.values[y * self.res as usize + x],
            pdf_pos: 1.0,
            pdf_dir: pdf_uv / (4.0 * PI),
            n: Vec3::ZERO,
            delta_pos: true,
            delta_dir: false,
        })
    }

    /// `4 pi I` times the image's mean (equal-area texels).
    pub fn power(&self) -> Rgb {
        self.intensity * (4.0 * PI * self.mean)
    }
}
