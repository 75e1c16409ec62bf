//! Analytic disk at height `h` in its object space, normal +z.

use super::{Aabb, Ray, SurfaceGeom};
use lumis_math::{Transform, Vec2, Vec3, PI};

#[derive(Clone, Copy, Debug)]
pub struct Disk {
    pub object_to_world: Transform,
    pub height: f32,
    pub radius: f32,
    pub inner_radius: f32,
    pub flip_normals: bool,
}

impl Disk {
    pub fn new(
        object_to_world: Transform,
        height: f32,
        radius: f32,
        inner_radius: f32,
        reverse: bool,
    ) -> Disk {
        Disk {
            object_to_world,
            height,
            radius,
            inner_radius,
            flip_normals: reverse ^ object_to_world.swaps_handedness(),
        }
    }

    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for &(x, y) in &[(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            b.grow(self.object_to_world.point(Vec3::new(
                x * self.radius,
                y * self.radius,
                self.height,
            )));
        }
        b
    }

    /// World-space area (assumes a similarity transform).
    pub fn area(&self) -> f32 {
        let s = lumis_math::Mat3::from_mat4(self.object_to_world.m)
            .determinant()
            .abs()
            .cbrt();
        PI * (self.radius * self.radius - self.inner_radius * self.inner_radius) * s * s
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray, tmax: f32) -> Option<f32> {
        let inv = &self.object_to_world.inv;
        let o = inv.transform_point3(ray.o);
        let d = inv.transform_vector3(ray.d);
        if d.z == 0.0 {
            return None;
        }
        let t = (self.height - o.z) / d.z;
        if !(t > 0.0 && t < tmax) {
            return None;
        }
        let p = o + t * d;
        let r2 = p.x * p.x + p.y * p.y;
        if r2 > self.radius * self.radius || r2 < self.inner_radius * self.inner_radius {
            return None;
        }
        Some(t)
    }

    pub fn normal(&self) -> Vec3 {
        let n = self.object_to_world.normal(Vec3::Z).normalize();
        if self.flip_normals {
            -n
        } else {
            n
        }
    }

    pub fn geometry_at(&self, p_world: Vec3) -> SurfaceGeom {
        let mut po = self.object_to_world.inv.transform_point3(p_world);
        po.z = self.height;
        let p = self.object_to_world.point(po);
        let n = self.normal();
        let r = (po.x * po.x + po.y * po.y).sqrt();
        let phi = po.y.atan2(po.x);
        let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
        let v = (self.radius - r) / (self.radius - self.inner_radius).max(1e-12);
        let mut dpdu = self
            .object_to_world
            .vector(2.0 * PI * Vec3::new(-po.y, po.x, 0.0));
        let mut dpdv = self.object_to_world.vector(
            Vec3::new(po.x, po.y, 0.0) * ((self.inner_radius - self.radius) / r.max(1e-12)),
        );
        if dpdu.length_squared() < 1e-20 || dpdv.length_squared() < 1e-20 {
            let f = lumis_math::Frame::from_normal(n);
            (dpdu, dpdv) = (f.s, f.t);
        }
        SurfaceGeom {
            p,
            ng: n,
            ns: n,
            dpdu,
            dpdv,
            uv: Vec2::new(phi / (2.0 * PI), v),
        }
    }

    /// Uniform point by area: (point, normal).
    pub fn sample_area(&self, u: Vec2) -> (Vec3, Vec3) {
        let d = lumis_math::sampling::square_to_disk_concentric(u);
        let ri = self.inner_radius / self.radius;
        // Map the unit disk to the annulus by radius remapping preserving uniformity.
        let r = d.length();
        let scale = if r > 0.0 {
            (ri * ri + (1.0 - ri * ri) * r * r).sqrt() / r
        } else {
            0.0
        };
        let po = Vec3::new(
            d.x * scale * self.radius,
            d.y * scale * self.radius,
            self.height,
        );
        (self.object_to_world.point(po), self.normal())
    }
}
