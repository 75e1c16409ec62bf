//! Screen-space footprints at any hit, as pbrt-v4's
//! `Camera::Approximate_dp_dxy`: the camera's smallest ray differentials,
//! re-aimed at the hit point and intersected with its tangent plane, scaled
//! by `max(1/8, 1/sqrt(spp))`.

use super::TexCtx;
use crate::camera::Camera;
use crate::geometry::SurfaceGeom;
use lumis_math::{Transform, Vec2, Vec3};

#[derive(Clone, Copy, Debug)]
pub struct Footprint {
    camera_from_world: Transform,
    world_from_camera: Transform,
    /// Smallest direction differentials over the film, camera space.
    dir_dx: Vec3,
    dir_dy: Vec3,
    spp_scale: f32,
}

impl Default for Footprint {
    /// No footprint: every lookup reads the finest level.
    fn default() -> Self {
        Footprint {
            camera_from_world: Transform::IDENTITY,
            world_from_camera: Transform::IDENTITY,
            dir_dx: Vec3::ZERO,
            dir_dy: Vec3::ZERO,
            spp_scale: 0.0,
        }
    }
}

impl Footprint {
    pub fn new(camera: &Camera, spp: u32) -> Footprint {
        let (w, h) = (camera.resolution.0 as f32, camera.resolution.1 as f32);
        let dir = |x: f32, y: f32| {
            let r = camera.generate_ray(Vec2::new(x, y), Vec2::splat(0.5));
            camera.world_from_camera.inverse().vector(r.d).normalize()
        };
        let (mut dx, mut dy) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::INFINITY));
        let n = 32;
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (w * i as f32 / n as f32, h * j as f32 / n as f32);
                let d = dir(x, y);
                let ddx = dir(x + 1.0, y) - d;
                let ddy = dir(x, y + 1.0) - d;
                if ddx.length_squared() < dx.length_squared() {
                    dx = ddx;
                }
                if ddy.length_squared() < dy.length_squared() {
                    dy = ddy;
                }
            }
        }
        Footprint {
            camera_from_world: camera.world_from_camera.inverse(),
            world_from_camera: camera.world_from_camera,
            dir_dx: dx,
            dir_dy: dy,
            spp_scale: (1.0 / (spp.max(1) as f32).sqrt()).max(0.125),
        }
    }

    /// Approximate dp/dx and dp/dy at point `p` with normal `n` (world space).
    pub fn dp_dxy(&self, p: Vec3, n: Vec3) -> (Vec3, Vec3) {
        let (px, py) = self.pixel_dp_dxy(p, n);
        (px * self.spp_scale, py * self.spp_scale)
    }

    /// Area of one pixel's footprint on the tangent plane at `p` (normal
    /// `n`): the camera's differentials without the sample-count scale. 0
    /// without a camera.
    pub fn pixel_area(&self, p: Vec3, n: Vec3) -> f32 {
        let (dx, dy) = self.pixel_dp_dxy(p, n);
        dx.cross(dy).length()
    }

    /// One pixel's dp/dx, dp/dy (world space); zero without a camera.
    fn pixel_dp_dxy(&self, p: Vec3, n: Vec3) -> (Vec3, Vec3) {
        if self.spp_scale == 0.0 {
            return (Vec3::ZERO, Vec3::ZERO);
        }
        let pc = self.camera_from_world.point(p);
        let nc = self.camera_from_world.normal(n).normalize_or_zero();
        let z = pc.normalize_or_zero();
        // The minimal rotation taking +z to the direction of p, applied to the differentials.
        let rot = |v: Vec3| {
            let c = z.z;
            if c < -0.9999 {
                return Vec3::new(-v.x, v.y, -v.z);
            }
            let a = Vec3::Z.cross(z);
            v * c + a.cross(v) + a * (a.dot(v) / (1.0 + c))
        };
        let d = nc.dot(pc);
        let hit = |dd: Vec3| {
            let dir = z + rot(dd);
            let den = nc.dot(dir);
            if den.abs() < 1e-12 {
                return Vec3::ZERO;
            }
            dir * (d / den) - pc
        };
        let (px, py) = (hit(self.dir_dx), hit(self.dir_dy));
        (
            self.world_from_camera.vector(px),
            self.world_from_camera.vector(py),
        )
    }

    /// The texture context at a hit: footprint and uv derivatives by least
    /// squares from dp/du and dp/dv (pbrt-v4's `ComputeDifferentials`).
    pub fn context(&self, g: &SurfaceGeom) -> TexCtx {
        let (dpdx, dpdy) = self.dp_dxy(g.p, g.ng);
        let (a00, a01, a11) = (g.dpdu.dot(g.dpdu), g.dpdu.dot(g.dpdv), g.dpdv.dot(g.dpdv));
        let inv = 1.0 / (a00 * a11 - a01 * a01);
        let inv = if inv.is_finite() { inv } else { 0.0 };
        let solve = |d: Vec3| {
            let (b0, b1) = (g.dpdu.dot(d), g.dpdv.dot(d));
            let du = (a11 * b0 - a01 * b1) * inv;
            let dv = (a00 * b1 - a01 * b0) * inv;
            let f = |x: f32| {
                if x.is_finite() {
                    x.clamp(-1e8, 1e8)
                } else {
                    0.0
                }
            };
            (f(du), f(dv))
        };
        let (dudx, dvdx) = solve(dpdx);
        let (dudy, dvdy) = solve(dpdy);
        TexCtx {
            p: g.p,
            n: g.ns,
            uv: g.uv,
            dpdx,
            dpdy,
            dudx,
            dudy,
            dvdx,
            dvdy,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn footprint_of_a_facing_plane_is_one_pixel() {
        // 100x100 pixels, 90 degree fov: a plane at distance 1 facing the camera
        // spans 2 units, one pixel is 0.02 near the centre (slightly less at the
        // corners, where pbrt takes its minimum).
        let cam = Camera::perspective(Transform::IDENTITY, (100, 100), 90.0, 0.0, 1.0);
        let f = Footprint::new(&cam, 1);
        let (dx, dy) = f.dp_dxy(Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.0, -1.0));
        assert!(dx.length() > 0.005 && dx.length() <= 0.0201, "{dx:?}");
        assert!(dy.length() > 0.005 && dy.length() <= 0.0201, "{dy:?}");
        // Twice as far: twice as large; 64 spp: an eighth.
        let (dx2, _) = f.dp_dxy(Vec3::new(0.0, 0.0, 2.0), Vec3::new(0.0, 0.0, -1.0));
        assert!((dx2.length() / dx.length() - 2.0).abs() < 1e-3);
        let f64spp = Footprint::new(&cam, 64);
        let (dx3, _) = f64spp.dp_dxy(Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.0, -1.0));
        assert!((dx3.length() / dx.length() - 0.125).abs() < 1e-4);
        // uv derivatives reproduce the in-plane footprint: dp/du du/dx + dp/dv dv/dx = dp/dx.
        let g = SurfaceGeom {
            p: Vec3::new(0.0, 0.0, 1.0),
            ng: Vec3::new(0.0, 0.0, -1.0),
            ns: Vec3::new(0.0, 0.0, -1.0),
            dpdu: Vec3::new(4.0, 0.0, 0.0),
            dpdv: Vec3::new(0.0, 2.0, 0.0),
            uv: Vec2::ZERO,
        };
        let c = f.context(&g);
        let rx = g.dpdu * c.dudx + g.dpdv * c.dvdx;
        let ry = g.dpdu * c.dudy + g.dpdv * c.dvdy;
        assert!(
            (rx - c.dpdx).length() < 1e-6 && (ry - c.dpdy).length() < 1e-6,
            "{c:?}"
        );
    }
}
