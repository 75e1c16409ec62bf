//! Perspective camera with a thin lens, as pbrt-v4's (left-handed camera
//! space: +z forward, +x towards raster right, +y towards raster up).

use crate::geometry::Ray;
use lumis_math::{sampling::square_to_disk_concentric, Transform, Vec2, Vec3};

#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub world_from_camera: Transform,
    /// Full film resolution (the crop window selects a part of it).
    pub resolution: (u32, u32),
    /// Screen window: x in [sx0, sx1], y in [sy0, sy1].
    pub screen: [f32; 4],
    pub tan_half_fov: f32,
    pub lens_radius: f32,
    pub focal_distance: f32,
}

impl Camera {
    /// `fov_deg` spans the shorter image axis, as in pbrt.
    pub fn perspective(
        world_from_camera: Transform,
        resolution: (u32, u32),
        fov_deg: f32,
        lens_radius: f32,
        focal_distance: f32,
    ) -> Camera {
        let aspect = resolution.0 as f32 / resolution.1 as f32;
        let screen = if aspect > 1.0 {
            [-aspect, aspect, -1.0, 1.0]
        } else {
            [-1.0, 1.0, -1.0 / aspect, 1.0 / aspect]
        };
        Camera {
            world_from_camera,
            resolution,
            screen,
            tan_half_fov: (fov_deg.to_radians() * 0.5).tan(),
            lens_radius,
            focal_distance,
        }
    }

    /// Ray through raster position `p_film` (pixels, y down) with lens sample `u_lens`.
    pub fn generate_ray(&self, p_film: Vec2, u_lens: Vec2) -> Ray {
        let (w, h) = (self.resolution.0 as f32, self.resolution.1 as f32);
        let sx = self.screen[0] + (p_film.x / w) * (self.screen[1] - self.screen[0]);
        let sy = self.screen[3] - (p_film.y / h) * (self.screen[3] - self.screen[2]);
        let p_cam = Vec3::new(sx * self.tan_half_fov, sy * self.tan_half_fov, 1.0);
        let mut o = Vec3::ZERO;
        let mut d = p_cam.normalize();
        if self.lens_radius > 0.0 {
            let lens = self.lens_radius * square_to_disk_concentric(u_lens);
            let ft = self.focal_distance / d.z;
            let focus = d * ft;
            o = Vec3::new(lens.x, lens.y, 0.0);
            d = (focus - o).normalize();
        }
        let o_w = self.world_from_camera.point(o);
        let d_w = self.world_from_camera.vector(d).normalize();
        Ray::new(o_w, d_w)
    }
}

/// A camera point sampled towards a scene point (light tracing's
/// connection to the camera), as pbrt-v4's `SampleWi`.
#[derive(Clone, Copy, Debug)]
pub struct CameraWi {
    /// Unit direction from the scene point to the lens point.
    pub wi: Vec3,
    /// The lens point (world space).
    pub p_lens: Vec3,
    /// Density of the lens point per unit solid angle at the scene point.
    pub pdf: f32,
    /// Importance `W_e` of the ray from the lens point to the scene point.
    pub we: f32,
    /// Where that ray meets the film (raster, pixels, y down).
    pub p_raster: Vec2,
}

impl Camera {
    /// Area of the lens (1 for a pinhole, as pbrt-v4 counts it).
    fn lens_area(&self) -> f32 {
        if self.lens_radius > 0.0 {
            std::f32::consts::PI * self.lens_radius * self.lens_radius
        } else {
            1.0
        }
    }

    /// Importance and raster position of the ray leaving the lens at
    /// `o_cam` (camera space, on the lens plane) in world direction `d`;
    /// `None` if it misses the film grown by `margin` pixels on each side
    /// (the pixel filter's radius: a point just outside the film still
    /// counts in its border pixels). `W_e = 1 / (A lens_area cos^4)`, `A`
    /// the film's area on the plane `z = 1`, so that the importance of the
    /// whole film integrates to one (pbrt-v4's `We`).
    pub fn importance(&self, o_cam: Vec3, d: Vec3, margin: Vec2) -> Option<(f32, Vec2)> {
        let d_cam = self
            .world_from_camera
            .inverse()
            .vector(d)
            .normalize_or_zero();
        let cos = d_cam.z;
        if !(cos > 0.0) {
            return None;
        }
        let t_focus = if self.lens_radius > 0.0 {
            self.focal_distance
        } else {
            1.0
        };
        let f = o_cam + d_cam * (t_focus / cos);
        let (sx, sy) = (
            f.x / (f.z * self.tan_half_fov),
            f.y / (f.z * self.tan_half_fov),
        );
        let [x0, x1, y0, y1] = self.screen;
        let (w, h) = (self.resolution.0 as f32, self.resolution.1 as f32);
        let p = Vec2::new((sx - x0) / (x1 - x0) * w, (y1 - sy) / (y1 - y0) * h);
        let inside = |v: f32, size: f32, m: f32| v > -m && v < size + m;
        if !(inside(p.x, w, margin.x) && inside(p.y, h, margin.y)) {
            return None;
        }
        let area = (x1 - x0) * (y1 - y0) * self.tan_half_fov * self.tan_half_fov;
        let cos2 = cos * cos;
        Some((1.0 / (area * self.lens_area() * cos2 * cos2), p))
    }

    /// Density per unit solid angle with which camera rays leaving the
    /// lens point `p_lens` (world space) take world direction `d`: pbrt-v4's
    /// `PDF_We` direction part, `1 / (A cos^3)` over the film grown by
    /// `margin` pixels, 0 elsewhere (the lens point's own density is
    /// `1 / lens_area`).
    pub fn pdf_dir(&self, p_lens: Vec3, d: Vec3, margin: Vec2) -> f32 {
        let o_cam = self.world_from_camera.inverse().point(p_lens);
        let Some((we, _)) = self.importance(o_cam, d, margin) else {
            return 0.0;
        };
        let forward = self.world_from_camera.vector(Vec3::Z).normalize_or_zero();
        we * self.lens_area() * forward.dot(d.normalize_or_zero())
    }

    /// A lens point seen from `p_ref` (lens sample `u_lens`), with its
    /// density per solid angle there and the importance of the ray from it
    /// to `p_ref`; `None` if that ray misses the film grown by `margin`.
    pub fn sample_wi(&self, p_ref: Vec3, u_lens: Vec2, margin: Vec2) -> Option<CameraWi> {
        let lens = self.lens_radius * square_to_disk_concentric(u_lens);
        let o_cam = Vec3::new(lens.x, lens.y, 0.0);
        let p_lens = self.world_from_camera.point(o_cam);
        let to_lens = p_lens - p_ref;
        let dist2 = to_lens.length_squared();
        if !(dist2 > 0.0) {
            return None;
        }
        let wi = to_lens / dist2.sqrt();
        let forward = self.world_from_camera.vector(Vec3::Z).normalize_or_zero();
        let cos_lens = forward.dot(wi).abs();
        let (we, p_raster) = self.importance(o_cam, -wi, margin)?;
        Some(CameraWi {
            wi,
            p_lens,
            pdf: dist2 / (cos_lens * self.lens_area()),
            we,
            p_raster,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_ray_looks_forward_and_corners_span_fov() {
        let c = Camera::perspective(Transform::IDENTITY, (200, 100), 90.0, 0.0, 1.0);
        let r = c.generate_ray(Vec2::new(100.0, 50.0), Vec2::ZERO);
        assert!((r.d - Vec3::Z).length() < 1e-6);
        // Top edge centre: shorter axis (y) spans 90 degrees, so 45 degrees up.
        let r = c.generate_ray(Vec2::new(100.0, 0.0), Vec2::ZERO);
        assert!((r.d.y.atan2(r.d.z).to_degrees() - 45.0).abs() < 1e-3);
        // Raster right is camera +x.
        let r = c.generate_ray(Vec2::new(200.0, 50.0), Vec2::ZERO);
        assert!(r.d.x > 0.0);
    }

    /// A point on a camera ray projects back to the raster position the
    /// ray was made for, through the same lens point (pinhole and thin lens).
    #[test]
    fn sample_wi_finds_the_raster_position_of_generated_rays() {
        let to_world = Transform::new(lumis_math::Mat4::look_at_lh(
            Vec3::new(1.0, 2.0, -3.0),
            Vec3::new(0.0, 0.5, 0.0),
            Vec3::Y,
        ))
        .unwrap()
        .inverse();
        for lens in [0.0, 0.2] {
            let c = Camera::perspective(to_world, (40, 30), 50.0, lens, 3.5);
            for (p, u) in [
                (Vec2::new(3.5, 7.25), Vec2::new(0.3, 0.8)),
                (Vec2::new(39.0, 0.5), Vec2::new(0.9, 0.1)),
                (Vec2::new(20.0, 15.0), Vec2::new(0.5, 0.5)),
            ] {
                let r = c.generate_ray(p, u);
                let s = c.sample_wi(r.at(2.7), u, Vec2::ZERO).expect("on the film");
                assert!(
                    (s.p_raster - p).length() < 1e-3,
                    "{lens}: {p} vs {}",
                    s.p_raster
                );
                assert!((s.wi + r.d).length() < 1e-4);
                assert!(s.we > 0.0 && s.pdf > 0.0);
            }
            // Behind the camera: no importance.
            let back = c.world_from_camera.point(Vec3::new(0.0, 0.0, -1.0));
            assert!(c.sample_wi(back, Vec2::splat(0.5), Vec2::ZERO).is_none());
        }
    }

    /// `W_e` integrates to one over the film: with raster points uniform
    /// over the film (plane area A at z = 1), `W_e cos` per solid angle
    /// times `d omega / dA = cos^3` times A is one for every sample.
    #[test]
    fn pinhole_importance_integrates_to_one_over_the_film() {
        let c = Camera::perspective(Transform::IDENTITY, (64, 48), 70.0, 0.0, 1.0);
        let area =
            (c.screen[1] - c.screen[0]) * (c.screen[3] - c.screen[2]) * c.tan_half_fov.powi(2);
        let mut rng = lumis_math::Pcg32::new(1, 2);
        let n = 1000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let p = Vec2::new(rng.next_f32() * 64.0, rng.next_f32() * 48.0);
            let r = c.generate_ray(p, Vec2::ZERO);
            let (we, _) = c.importance(Vec3::ZERO, r.d, Vec2::ZERO).unwrap();
            let cos = r.d.z;
            sum += (we * cos * cos.powi(3) * area) as f64;
        }
        assert!((sum / n as f64 - 1.0).abs() < 1e-4, "{}", sum / n as f64);
    }

    #[test]
    fn thin_lens_rays_meet_at_focal_plane() {
        let c = Camera::perspective(Transform::IDENTITY, (64, 64), 40.0, 0.5, 3.0);
        let a = c.generate_ray(Vec2::new(10.0, 20.0), Vec2::new(0.1, 0.9));
        let b = c.generate_ray(Vec2::new(10.0, 20.0), Vec2::new(0.8, 0.3));
        let pa = a.at((3.0 - a.o.z) / a.d.z);
        let pb = b.at((3.0 - b.o.z) / b.d.z);
        assert!((pa - pb).length() < 1e-4);
    }
}
