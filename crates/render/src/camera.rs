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
