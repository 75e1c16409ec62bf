//! Environment light from an image: pbrt-v4's equal-area octahedral square
//! maps, or pbrt-v3's latitude-longitude maps. Radiance is the nearest texel
//! (as pbrt-v4's `ImageInfiniteLight`), so importance sampling by a
//! piecewise-constant distribution over texels matches it exactly.

use super::{LeSample, LiSample};
use crate::geometry::{Aabb, Ray};
use lumis_math::sampling::{
    equal_area_sphere_to_square, equal_area_square_to_sphere, latlong_to_sphere, sphere_to_latlong,
    square_to_disk_concentric, wrap_equal_area_pixel, PiecewiseConstant2D,
};
use lumis_math::{Frame, Mat3, Rgb, Vec2, Vec3, PI};

/// How image coordinates map to directions (in the light's space).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EnvMapping {
    /// pbrt-v4: Clarberg's equal-area octahedral map of a square image.
    EqualArea,
    /// pbrt-v3: `u = phi / 2 pi`, `v = theta / pi`, `+z` at the top row.
    LatLong,
}

#[derive(Clone, Debug)]
pub struct ImageInfiniteLight {
    width: u32,
    height: u32,
    /// Radiance per texel (scale included, negatives clamped), top row first.
    texels: Vec<Rgb>,
    mapping: EnvMapping,
    /// Rotation (or reflection) from light space to world space, and back.
    to_world: Mat3,
    to_light: Mat3,
    /// Over texels, proportional to luminance times the texel's solid angle
    /// per unit square area (1 for equal-area, `sin theta` for lat-long).
    distribution: PiecewiseConstant2D,
    /// `∫ L dω` over the sphere.
    radiant_integral: Rgb,
    pub scene_center: Vec3,
    pub scene_radius: f32,
}

impl ImageInfiniteLight {
    /// `texels`: `width * height` linear RGB values, top row first.
    /// `to_world` must be orthogonal (a rotation or reflection).
    pub fn new(
        width: u32,
        height: u32,
        texels: Vec<Rgb>,
        mapping: EnvMapping,
        to_world: Mat3,
    ) -> ImageInfiniteLight {
        assert_eq!(texels.len(), width as usize * height as usize);
        let texels: Vec<Rgb> = texels.into_iter().map(|t| t.map(|c| c.max(0.0))).collect();
        let (w, h) = (width as usize, height as usize);
        let mut weights = Vec::with_capacity(w * h);
        let mut integral = [0f64; 3];
        for y in 0..h {
            let (jac, solid) = match mapping {
                EnvMapping::EqualArea => (1.0, 4.0 * std::f64::consts::PI / (w * h) as f64),
                EnvMapping::LatLong => {
                    let t0 = std::f64::consts::PI * y as f64 / h as f64;
                    let t1 = std::f64::consts::PI * (y + 1) as f64 / h as f64;
                    let mid = (PI * (y as f32 + 0.5) / h as f32).sin();
                    (
                        mid,
                        2.0 * std::f64::consts::PI / w as f64 * (t0.cos() - t1.cos()),
                    )
                }
            };
            for x in 0..w {
                let t = texels[y * w + x];
                weights.push(t.luminance().max(0.0) * jac);
                for (c, v) in t.to_array().into_iter().enumerate() {
                    integral[c] += v as f64 * solid;
                }
            }
        }
        ImageInfiniteLight {
            width,
            height,
            texels,
            mapping,
            to_world,
            to_light: to_world.transpose(),
            distribution: PiecewiseConstant2D::new(&weights, w, h),
            radiant_integral: Rgb::new(integral[0] as f32, integral[1] as f32, integral[2] as f32),
            scene_center: Vec3::ZERO,
            scene_radius: 1.0,
        }
    }

    pub fn preprocess(&mut self, b: &Aabb) {
        let (c, r) = b.bounding_sphere();
        self.scene_center = c;
        self.scene_radius = r.max(1e-3);
    }

    pub fn mapping(&self) -> EnvMapping {
        self.mapping
    }

    /// Texel holding image point `uv` in [0,1]².
    fn texel_of(&self, uv: Vec2) -> (usize, usize) {
        let (w, h) = (self.width as i32, self.height as i32);
        let x = (uv.x * w as f32).floor() as i32;
        let y = (uv.y * h as f32).floor() as i32;
        let (x, y) = match self.mapping {
            EnvMapping::EqualArea => wrap_equal_area_pixel(x, y, w, h),
            EnvMapping::LatLong => (x.rem_euclid(w), y.clamp(0, h - 1)),
        };
        (x as usize, y as usize)
    }

    fn texel(&self, (x, y): (usize, usize)) -> Rgb {
        self.texels[y * self.width as usize + x]
    }

    /// Light-space direction of image point `uv`, and the solid angle per
    /// unit image area there (`dω = J du dv`).
    fn direction(&self, uv: Vec2) -> (Vec3, f32) {
        match self.mapping {
            EnvMapping::EqualArea => (equal_area_square_to_sphere(uv), 4.0 * PI),
            EnvMapping::LatLong => {
                let (d, sin_theta) = latlong_to_sphere(uv);
                (d, 2.0 * PI * PI * sin_theta)
            }
        }
    }

    /// Image point of a world direction, and `J` there.
    fn image_point(&self, w: Vec3) -> (Vec2, f32) {
        let wl = (self.to_light * w).normalize_or_zero();
        match self.mapping {
            EnvMapping::EqualArea => (equal_area_sphere_to_square(wl), 4.0 * PI),
            EnvMapping::LatLong => {
                let sin_theta = wl.x.hypot(wl.y); // accurate near the poles
                (sphere_to_latlong(wl), 2.0 * PI * PI * sin_theta)
            }
        }
    }

    /// Radiance arriving along an escaped ray with direction `d`.
    pub fn le(&self, d: Vec3) -> Rgb {
        let (uv, _) = self.image_point(d);
        self.texel(self.texel_of(uv))
    }

    /// Solid-angle density of `sample_li` (and of `sample_le`'s reversed direction).
    pub fn pdf_li(&self, wi: Vec3) -> f32 {
        let (uv, jac) = self.image_point(wi);
        if jac <= 0.0 {
            return 0.0;
        }
        let (x, y) = self.texel_of(uv);
        self.distribution.pdf_bin(x, y) / jac
    }

    /// Samples an image point by luminance: world direction towards the
    /// light, radiance, solid-angle density.
    fn sample_direction(&self, u: Vec2) -> Option<(Vec3, Rgb, f32)> {
        let (uv, pdf_uv, cell) = self.distribution.sample(u);
        let (wl, jac) = self.direction(uv);
        if jac <= 0.0 || pdf_uv <= 0.0 {
            return None;
        }
        let wi = (self.to_world * wl).normalize_or_zero();
        if wi == Vec3::ZERO {
            return None;
        }
        Some((wi, self.texel(cell), pdf_uv / jac))
    }

    pub fn sample_li(&self, p_ref: Vec3, u: Vec2) -> Option<LiSample> {
        let (wi, li, pdf) = self.sample_direction(u)?;
        Some(LiSample {
            wi,
            li,
            pdf,
            p_light: p_ref + wi * (2.0 * self.scene_radius),
            n_light: Vec3::ZERO,
            delta: false,
            infinite: true,
        })
    }

    /// Photon emission: a direction by luminance, then a point on the disk
    /// of the scene's bounding sphere facing it, as the uniform light does.
    pub fn sample_le(&self, u1: Vec2, u2: Vec2) -> Option<LeSample> {
        let (wi, le, pdf_dir) = self.sample_direction(u1)?;
        let w = -wi; // direction of travel
        let frame = Frame::from_normal(w);
        let d = square_to_disk_concentric(u2) * self.scene_radius;
        let p = self.scene_center - w * self.scene_radius + frame.s * d.x + frame.t * d.y;
        Some(LeSample {
            ray: Ray::new(p, w),
            le,
            pdf_pos: 1.0 / (PI * self.scene_radius * self.scene_radius),
            pdf_dir,
            n: Vec3::ZERO,
            delta_pos: false,
            delta_dir: false,
        })
    }

    /// Power through the disk of the scene's bounding sphere: `pi r² ∫ L dω`.
    pub fn power(&self) -> Rgb {
        self.radiant_integral * (PI * self.scene_radius * self.scene_radius)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gradient(w: u32, h: u32, mapping: EnvMapping) -> ImageInfiniteLight {
        let texels = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                Rgb::new(1.0 + x as f32, 0.5, 1.0 + 3.0 * y as f32)
            })
            .collect();
        ImageInfiniteLight::new(w, h, texels, mapping, Mat3::IDENTITY)
    }

    #[test]
    fn sampled_radiance_is_the_radiance_in_the_sampled_direction() {
        for (light, _) in [
            (gradient(16, 16, EnvMapping::EqualArea), 0),
            (gradient(32, 16, EnvMapping::LatLong), 1),
        ] {
            let mut rng = lumis_math::Pcg32::new(1, 1);
            for _ in 0..10_000 {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                let s = light.sample_li(Vec3::ZERO, u).unwrap();
                assert_eq!(s.li, light.le(s.wi), "{:?}", light.mapping);
                let pdf = light.pdf_li(s.wi);
                assert!(
                    (pdf - s.pdf).abs() <= 1e-3 * s.pdf,
                    "{:?}: {pdf} vs {}",
                    light.mapping,
                    s.pdf
                );
            }
        }
    }

    #[test]
    fn transform_rotates_the_map() {
        // A map bright only near light-space +z, rotated so +z goes to world +x.
        let (w, h) = (8u32, 8u32);
        let texels = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                let c = equal_area_square_to_sphere(Vec2::new(
                    (x as f32 + 0.5) / w as f32,
                    (y as f32 + 0.5) / h as f32,
                ));
                Rgb::splat(if c.z > 0.9 { 1.0 } else { 0.0 })
            })
            .collect();
        let rot = Mat3::from_cols(Vec3::NEG_Z, Vec3::Y, Vec3::X);
        let light = ImageInfiniteLight::new(w, h, texels, EnvMapping::EqualArea, rot);
        assert!(light.le(Vec3::X).luminance() > 0.5);
        assert_eq!(light.le(Vec3::Z).luminance(), 0.0);
        let s = light.sample_li(Vec3::ZERO, Vec2::new(0.3, 0.6)).unwrap();
        assert!(s.wi.x > 0.8, "{}", s.wi);
    }
}
