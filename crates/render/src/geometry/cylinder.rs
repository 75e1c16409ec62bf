//! pbrt's cylinder: radius `r` about the object-space z axis between `zmin`
//! and `zmax`, swept to `phimax`; open at both ends.

use super::phi_of;
use super::{Aabb, Ray, SurfaceGeom};
use lumis_math::{Transform, Vec2, Vec3, PI};

#[derive(Clone, Copy, Debug)]
pub struct Cylinder {
    pub object_to_world: Transform,
    pub radius: f32,
    pub zmin: f32,
    pub zmax: f32,
    /// Radians.
    pub phi_max: f32,
    pub flip_normals: bool,
}

impl Cylinder {
    pub fn new(
        object_to_world: Transform,
        radius: f32,
        zmin: f32,
        zmax: f32,
        phimax_deg: f32,
        reverse: bool,
    ) -> Cylinder {
        Cylinder {
            object_to_world,
            radius,
            zmin: zmin.min(zmax),
            zmax: zmin.max(zmax),
            phi_max: phimax_deg.clamp(0.0, 360.0).to_radians(),
            flip_normals: reverse ^ object_to_world.swaps_handedness(),
        }
    }

    pub fn bounds(&self) -> Aabb {
        let r = self.radius;
        let b = Aabb {
            min: Vec3::new(-r, -r, self.zmin),
            max: Vec3::new(r, r, self.zmax),
        };
        super::aabb::transform_box(&self.object_to_world, &b)
    }

    /// World-space area (similarity transform assumed, as for spheres and disks).
    pub fn area(&self) -> f32 {
        let s = lumis_math::Mat3::from_mat4(self.object_to_world.m)
            .determinant()
            .abs()
            .cbrt();
        (self.zmax - self.zmin) * self.radius * self.phi_max * s * s
    }

    #[inline]
    fn kept(&self, p: Vec3) -> bool {
        p.z >= self.zmin
            && p.z <= self.zmax
            && (self.phi_max >= 2.0 * PI || phi_of(p) <= self.phi_max)
    }

    /// Closest t in (0, tmax); a root on a cut-away part falls through to the far root.
    #[inline]
    pub fn intersect(&self, ray: &Ray, tmax: f32) -> Option<f32> {
        let inv = &self.object_to_world.inv;
        let o = inv.transform_point3(ray.o);
        let d = inv.transform_vector3(ray.d);
        let a = d.x * d.x + d.y * d.y;
        if a == 0.0 {
            return None;
        }
        let b = 2.0 * (d.x * o.x + d.y * o.y);
        // Discriminant in pbrt-v4's cancellation-free form: 4a (r² - |o_perp|²) with o_perp
        // the closest approach of the xy projection to the axis.
        let f = b / (2.0 * a);
        let (vx, vy) = (o.x - f * d.x, o.y - f * d.y);
        let len = (vx * vx + vy * vy).sqrt();
        let disc = 4.0 * a * (self.radius + len) * (self.radius - len);
        if disc < 0.0 {
            return None;
        }
        let c = o.x * o.x + o.y * o.y - self.radius * self.radius;
        let root = disc.sqrt();
        let q = if b < 0.0 {
            -0.5 * (b - root)
        } else {
            -0.5 * (b + root)
        };
        let (mut t0, mut t1) = (q / a, if q != 0.0 { c / q } else { q / a });
        if t0 > t1 {
            std::mem::swap(&mut t0, &mut t1);
        }
        [t0, t1]
            .into_iter()
            .find(|&t| t > 0.0 && t < tmax && self.kept(self.on_surface(o + t * d)))
    }

    #[inline]
    fn on_surface(&self, p: Vec3) -> Vec3 {
        let r = (p.x * p.x + p.y * p.y).sqrt().max(1e-30);
        Vec3::new(p.x * self.radius / r, p.y * self.radius / r, p.z)
    }

    pub fn geometry_at(&self, p_world: Vec3) -> SurfaceGeom {
        let po = self.on_surface(self.object_to_world.inv.transform_point3(p_world));
        self.geometry_object(po)
    }

    fn geometry_object(&self, po: Vec3) -> SurfaceGeom {
        let mut n = self
            .object_to_world
            .normal(Vec3::new(po.x, po.y, 0.0))
            .normalize();
        if self.flip_normals {
            n = -n;
        }
        let phi = phi_of(po);
        SurfaceGeom {
            p: self.object_to_world.point(po),
            ng: n,
            ns: n,
            dpdu: self
                .object_to_world
                .vector(self.phi_max * Vec3::new(-po.y, po.x, 0.0)),
            dpdv: self
                .object_to_world
                .vector(Vec3::new(0.0, 0.0, self.zmax - self.zmin)),
            uv: Vec2::new(
                phi / self.phi_max,
                (po.z - self.zmin) / (self.zmax - self.zmin).max(1e-30),
            ),
        }
    }

    /// Uniform point by area: z and phi uniform. Returns (point, normal).
    pub fn sample_area(&self, u: Vec2) -> (Vec3, Vec3) {
        let z = self.zmin + u.x * (self.zmax - self.zmin);
        let phi = u.y * self.phi_max;
        let po = Vec3::new(self.radius * phi.cos(), self.radius * phi.sin(), z);
        let g = self.geometry_object(po);
        (g.p, g.ng)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::Mat4;

    #[test]
    fn hits_match_the_analytic_answers() {
        let c = Cylinder::new(Transform::IDENTITY, 1.0, -1.0, 2.0, 360.0, false);
        // From outside along x: enters at x = -1.
        let r = Ray::new(Vec3::new(-4.0, 0.0, 0.5), Vec3::X);
        assert!((c.intersect(&r, f32::INFINITY).unwrap() - 3.0).abs() < 1e-6);
        let g = c.geometry_at(r.at(3.0));
        assert!((g.ng - (-Vec3::X)).length() < 1e-6);
        // Oblique ray from inside: exits where x² + y² = 1.
        let d = Vec3::new(0.6, 0.0, 0.8);
        let r = Ray::new(Vec3::new(0.0, 0.0, 0.0), d);
        let t = c.intersect(&r, f32::INFINITY).unwrap();
        assert!((t - 1.0 / 0.6).abs() < 1e-5);
        // Above zmax at the wall: the ray passes the open top.
        let r = Ray::new(Vec3::new(0.0, 0.0, 1.9), Vec3::new(0.6, 0.0, 0.8));
        assert!(c.intersect(&r, f32::INFINITY).is_none());
        // Along the axis: never hits the wall.
        assert!(c
            .intersect(&Ray::new(Vec3::ZERO, Vec3::Z), f32::INFINITY)
            .is_none());
        // Quarter cylinder (phi in [0, 90°]): the near side at x = -1 is cut, the far side at x = 1
        // is phi = 0 at y = 0... use y = 0.5: near (-0.866, 0.5) has phi 150° (cut), far (0.866, 0.5) 30°.
        let q = Cylinder::new(Transform::IDENTITY, 1.0, -1.0, 1.0, 90.0, false);
        let r = Ray::new(Vec3::new(-4.0, 0.5, 0.0), Vec3::X);
        let t = q.intersect(&r, f32::INFINITY).unwrap();
        assert!((t - (4.0 + 0.75f32.sqrt())).abs() < 1e-5);
        assert!((q.area() - 2.0 * PI / 2.0).abs() < 1e-5);
        // Scaled by 2: area x4.
        let s = Transform::new(Mat4::from_scale(Vec3::splat(2.0))).unwrap();
        let c2 = Cylinder::new(s, 1.0, 0.0, 1.0, 360.0, false);
        assert!((c2.area() - 4.0 * 2.0 * PI).abs() < 1e-4);
        let b = c2.bounds();
        assert!((b.max - Vec3::new(2.0, 2.0, 2.0)).length() < 1e-5);
    }

    #[test]
    fn area_samples_lie_on_the_surface() {
        let c = Cylinder::new(Transform::IDENTITY, 0.5, 1.0, 3.0, 200.0, true);
        for i in 0..50 {
            let u = Vec2::new((i % 10) as f32 / 9.0, (i / 10) as f32 / 4.0);
            let (p, n) = c.sample_area(u);
            assert!(((p.x * p.x + p.y * p.y).sqrt() - 0.5).abs() < 1e-5);
            assert!(p.z >= 1.0 && p.z <= 3.0);
            assert!(
                (n + Vec3::new(p.x, p.y, 0.0) / 0.5).length() < 1e-4,
                "reversed: inward"
            );
        }
    }
}
