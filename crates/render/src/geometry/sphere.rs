//! Analytic sphere (full; pbrt's zmin/zmax/phimax come with the scene-loading issue).

use super::{Aabb, Ray, SurfaceGeom};
use lumis_math::{Transform, Vec2, Vec3, PI};

#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    pub object_to_world: Transform,
    pub radius: f32,
    pub flip_normals: bool,
    /// World-space center and radius (transforms are assumed similarity; checked at load).
    pub center: Vec3,
    pub world_radius: f32,
}

impl Sphere {
    pub fn new(object_to_world: Transform, radius: f32, reverse: bool) -> Sphere {
        let center = object_to_world.point(Vec3::ZERO);
        let scale = lumis_math::Mat3::from_mat4(object_to_world.m)
            .determinant()
            .abs()
            .cbrt();
        Sphere {
            object_to_world,
            radius,
            flip_normals: reverse ^ object_to_world.swaps_handedness(),
            center,
            world_radius: radius * scale,
        }
    }

    pub fn bounds(&self) -> Aabb {
        let r = Vec3::splat(self.world_radius);
        Aabb {
            min: self.center - r,
            max: self.center + r,
        }
    }

    pub fn area(&self) -> f32 {
        4.0 * PI * self.world_radius * self.world_radius
    }

    /// Closest t in (0, tmax), in the ray's parameter.
    #[inline]
    pub fn intersect(&self, ray: &Ray, tmax: f32) -> Option<f32> {
        let inv = &self.object_to_world.inv;
        let o = inv.transform_point3(ray.o);
        let d = inv.transform_vector3(ray.d);
        // Numerically robust quadratic (Hearn & Baker / pbrt-v4 discriminant form).
        let a = d.length_squared();
        let b = 2.0 * d.dot(o);
        let c = o.length_squared() - self.radius * self.radius;
        let v = o - (b / (2.0 * a)) * d;
        let len = v.length();
        let disc = 4.0 * a * (self.radius + len) * (self.radius - len);
        if disc < 0.0 {
            return None;
        }
        let root = disc.sqrt();
        let q = if b < 0.0 {
            -0.5 * (b - root)
        } else {
            -0.5 * (b + root)
        };
        let (mut t0, mut t1) = (q / a, c / q);
        if t0 > t1 {
            std::mem::swap(&mut t0, &mut t1);
        }
        if t0 > 0.0 && t0 < tmax {
            Some(t0)
        } else if t1 > 0.0 && t1 < tmax {
            Some(t1)
        } else {
            None
        }
    }

    /// Geometry at world point `p` (projected back onto the surface).
    pub fn geometry_at(&self, p_world: Vec3) -> SurfaceGeom {
        let mut po = self.object_to_world.inv.transform_point3(p_world);
        po *= self.radius / po.length().max(1e-30);
        let p = self.object_to_world.point(po);
        let mut n = self.object_to_world.normal(po).normalize();
        if self.flip_normals {
            n = -n;
        }
        let phi = po.y.atan2(po.x);
        let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
        let cos_theta = (po.z / self.radius).clamp(-1.0, 1.0);
        let uv = Vec2::new(phi / (2.0 * PI), (cos_theta.acos()) / PI);
        let mut dpdu = self.object_to_world.vector(Vec3::new(-po.y, po.x, 0.0));
        if dpdu.length_squared() < 1e-20 {
            dpdu = lumis_math::Frame::from_normal(n).s;
        }
        SurfaceGeom {
            p,
            ng: n,
            ns: n,
            dpdu,
            uv,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::Mat4;

    #[test]
    fn ray_hits_translated_sphere() {
        let t = Transform::new(Mat4::from_translation(Vec3::new(0.0, 0.0, 5.0))).unwrap();
        let s = Sphere::new(t, 1.0, false);
        let r = Ray::new(Vec3::ZERO, Vec3::Z);
        assert!((s.intersect(&r, f32::INFINITY).unwrap() - 4.0).abs() < 1e-5);
        let g = s.geometry_at(r.at(4.0));
        assert!((g.ng - (-Vec3::Z)).length() < 1e-5);
        // From inside, the far side.
        let r = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::Z);
        assert!((s.intersect(&r, f32::INFINITY).unwrap() - 1.0).abs() < 1e-5);
    }
}
