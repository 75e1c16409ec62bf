//! Analytic sphere with pbrt's `zmin`/`zmax`/`phimax` cuts.

use super::phi_of;
use super::{Aabb, Ray, SurfaceGeom};
use lumis_math::transform::uniform_scale;
use lumis_math::{Mat3, Transform, Vec2, Vec3, PI};

#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    pub object_to_world: Transform,
    pub radius: f32,
    pub flip_normals: bool,
    /// World-space center and radius (transforms are assumed similarity; checked at load).
    pub center: Vec3,
    pub world_radius: f32,
    /// Object-space cuts: `zmin <= z <= zmax`, `0 <= phi <= phi_max` (radians).
    pub zmin: f32,
    pub zmax: f32,
    pub phi_max: f32,
    /// A whole sphere whose transform is a similarity (rotation, uniform
    /// scale, translation): rays meet it in world space, at `center` and
    /// `world_radius`, without being transformed. The roots are the same
    /// `t`s (a similarity scales the quadratic's three coefficients alike).
    world_space: bool,
    /// `acos(zmin / radius)`, `acos(zmax / radius)`: where `v` is 0 and 1.
    theta_z: (f32, f32),
}

impl Sphere {
    pub fn new(object_to_world: Transform, radius: f32, reverse: bool) -> Sphere {
        Sphere::partial(object_to_world, radius, -radius, radius, 360.0, reverse)
    }

    /// pbrt's sphere: `zmin`, `zmax` clamped to the radius, `phimax` in degrees.
    pub fn partial(
        object_to_world: Transform,
        radius: f32,
        zmin: f32,
        zmax: f32,
        phimax_deg: f32,
        reverse: bool,
    ) -> Sphere {
        let center = object_to_world.point(Vec3::ZERO);
        let scale = lumis_math::Mat3::from_mat4(object_to_world.m)
            .determinant()
            .abs()
            .cbrt();
        let mut sphere = Sphere {
            object_to_world,
            radius,
            flip_normals: reverse ^ object_to_world.swaps_handedness(),
            center,
            world_radius: radius * scale,
            zmin: zmin.min(zmax).clamp(-radius, radius),
            zmax: zmin.max(zmax).clamp(-radius, radius),
            phi_max: phimax_deg.clamp(0.0, 360.0).to_radians(),
            world_space: false,
            theta_z: (0.0, 0.0),
        };
        // A rotation times a uniform scale, to a relative 1e-5.
        sphere.world_space = !sphere.is_partial()
            && object_to_world.is_affine()
            && uniform_scale(Mat3::from_mat4(object_to_world.m), 1e-5).is_some();
        sphere.theta_z = (
            (sphere.zmin / radius).clamp(-1.0, 1.0).acos(),
            (sphere.zmax / radius).clamp(-1.0, 1.0).acos(),
        );
        sphere
    }

    /// Whether any part is cut away.
    #[inline]
    pub fn is_partial(&self) -> bool {
        self.zmin > -self.radius || self.zmax < self.radius || self.phi_max < 2.0 * PI
    }

    pub fn bounds(&self) -> Aabb {
        if !self.is_partial() {
            let r = Vec3::splat(self.world_radius);
            return Aabb {
                min: self.center - r,
                max: self.center + r,
            };
        }
        let r = self.radius;
        let b = Aabb {
            min: Vec3::new(-r, -r, self.zmin),
            max: Vec3::new(r, r, self.zmax),
        };
        super::aabb::transform_box(&self.object_to_world, &b)
    }

    /// World-space area (similarity transform): `phi_max r (zmax - zmin)`, scaled.
    pub fn area(&self) -> f32 {
        let s = self.world_radius / self.radius;
        self.phi_max * self.radius * (self.zmax - self.zmin) * s * s
    }

    /// Whether object-space surface point `p` survives the cuts.
    #[inline]
    fn kept(&self, p: Vec3) -> bool {
        if p.z < self.zmin || p.z > self.zmax {
            return false;
        }
        self.phi_max >= 2.0 * PI || phi_of(p) <= self.phi_max
    }

    /// Closest t in (0, tmax), in the ray's parameter; on a partial sphere a
    /// hit on a cut-away part is skipped for the far root.
    #[inline]
    pub fn intersect(&self, ray: &Ray, tmax: f32) -> Option<f32> {
        if self.world_space {
            let (t0, t1) = roots(ray.o - self.center, ray.d, self.world_radius)?;
            return [t0, t1].into_iter().find(|&t| t > 0.0 && t < tmax);
        }
        let inv = &self.object_to_world.inv;
        let o = inv.transform_point3(ray.o);
        let d = inv.transform_vector3(ray.d);
        let (t0, t1) = roots(o, d, self.radius)?;
        let partial = self.is_partial();
        [t0, t1]
            .into_iter()
            .find(|&t| t > 0.0 && t < tmax && (!partial || self.kept(self.on_surface(o + t * d))))
    }

    /// Object-space point pushed onto the sphere (pbrt's refinement).
    #[inline]
    fn on_surface(&self, p: Vec3) -> Vec3 {
        p * (self.radius / p.length().max(1e-30))
    }

    /// Geometry at world point `p` (projected back onto the surface).
    pub fn geometry_at(&self, p_world: Vec3) -> SurfaceGeom {
        let po = self.on_surface(self.object_to_world.inv.transform_point3(p_world));
        self.geometry_object(po)
    }

    /// The point and normal of [`Sphere::geometry_at`] alone, without the
    /// surface parameters and their derivatives (bit for bit the same).
    pub fn point_normal_at(&self, p_world: Vec3) -> (Vec3, Vec3) {
        let po = self.on_surface(self.object_to_world.inv.transform_point3(p_world));
        self.point_normal(po)
    }

    #[inline]
    fn point_normal(&self, po: Vec3) -> (Vec3, Vec3) {
        let p = self.object_to_world.point(po);
        let n = self.object_to_world.normal(po).normalize();
        (p, if self.flip_normals { -n } else { n })
    }

    fn geometry_object(&self, po: Vec3) -> SurfaceGeom {
        let (p, n) = self.point_normal(po);
        let phi = phi_of(po);
        let theta = (po.z / self.radius).clamp(-1.0, 1.0).acos();
        // pbrt's parameterisation (v = 0 at zmin), for cut spheres too.
        let (tz0, tz1) = self.theta_z;
        let phi_max = if self.is_partial() {
            self.phi_max
        } else {
            2.0 * PI
        };
        let uv = Vec2::new(phi / phi_max, (theta - tz0) / (tz1 - tz0));
        let mut dpdu = self
            .object_to_world
            .vector(phi_max * Vec3::new(-po.y, po.x, 0.0));
        let (sin_phi, cos_phi) = phi.sin_cos();
        let mut dpdv = self.object_to_world.vector(
            (tz1 - tz0) * Vec3::new(po.z * cos_phi, po.z * sin_phi, -self.radius * theta.sin()),
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
            uv,
        }
    }

    /// Uniform point by area on the kept part: z uniform in [zmin, zmax]
    /// (Archimedes) and phi uniform in [0, phi_max]. Returns (point, normal).
    pub fn sample_area(&self, u: Vec2) -> (Vec3, Vec3) {
        let z = self.zmin + u.x * (self.zmax - self.zmin);
        let phi = u.y * self.phi_max;
        let r_xy = (self.radius * self.radius - z * z).max(0.0).sqrt();
        let po = Vec3::new(r_xy * phi.cos(), r_xy * phi.sin(), z);
        let g = self.geometry_object(po);
        (g.p, g.ng)
    }
}

/// The roots `t0 <= t1` of `|o + t d| = r`, if real: the numerically
/// robust quadratic (Hearn & Baker, pbrt-v4's discriminant form).
#[inline]
fn roots(o: Vec3, d: Vec3, r: f32) -> Option<(f32, f32)> {
    let a = d.length_squared();
    let b = 2.0 * d.dot(o);
    let c = o.length_squared() - r * r;
    let v = o - (b / (2.0 * a)) * d;
    let len = v.length();
    let disc = 4.0 * a * (r + len) * (r - len);
    if disc < 0.0 {
        return None;
    }
    let root = disc.sqrt();
    let q = if b < 0.0 {
        -0.5 * (b - root)
    } else {
        -0.5 * (b + root)
    };
    let (t0, t1) = (q / a, c / q);
    Some(if t0 > t1 { (t1, t0) } else { (t0, t1) })
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

    #[test]
    fn cut_sphere_takes_the_far_hit_or_misses() {
        // Hemisphere z >= 0 of radius 2, and a half in phi (x >= 0 side... phi in [0, 180]: y >= 0).
        let s = Sphere::partial(Transform::IDENTITY, 2.0, 0.0, 3.0, 180.0, false);
        assert_eq!((s.zmin, s.zmax), (0.0, 2.0));
        // Straight down the z axis from above: the top, at t = 3.
        let down = Ray::new(Vec3::new(0.5, 0.5, 5.0), -Vec3::Z);
        let t = s.intersect(&down, f32::INFINITY).unwrap();
        assert!((t - (5.0 - (4.0f32 - 0.5).sqrt())).abs() < 1e-5);
        // Up from below: the near hit (z < 0) is cut away, the far one is kept.
        let up = Ray::new(Vec3::new(0.5, 0.5, -5.0), Vec3::Z);
        let t = s.intersect(&up, f32::INFINITY).unwrap();
        assert!((t - (5.0 + 3.5f32.sqrt())).abs() < 1e-4);
        assert!(s.intersect(&up, 5.0).is_none(), "far hit beyond tmax");
        // Through the y < 0 half only: both hits cut away.
        let miss = Ray::new(Vec3::new(-5.0, -0.5, 0.5), Vec3::X);
        assert!(s.intersect(&miss, f32::INFINITY).is_none());
        // Along x at y > 0: the near hit at x = -sqrt(4 - 0.25 - 0.25) is kept.
        let hit = Ray::new(Vec3::new(-5.0, 0.5, 0.5), Vec3::X);
        let t = s.intersect(&hit, f32::INFINITY).unwrap();
        assert!((t - (5.0 - 3.5f32.sqrt())).abs() < 1e-5);
        // Area: phi_max r (zmax - zmin) = pi * 2 * 2.
        assert!((s.area() - 4.0 * PI).abs() < 1e-5);
        let b = s.bounds();
        assert!(b.min.z >= -1e-6 && b.max.z <= 2.0 + 1e-6);
    }

    #[test]
    fn area_samples_stay_on_the_kept_part() {
        let t = Transform::new(Mat4::from_scale(Vec3::splat(2.0))).unwrap();
        let s = Sphere::partial(t, 1.0, -0.3, 0.8, 250.0, false);
        for i in 0..64 {
            let u = Vec2::new((i % 8) as f32 / 7.0, (i / 8) as f32 / 7.0);
            let (p, n) = s.sample_area(u);
            let po = p / 2.0;
            assert!((po.length() - 1.0).abs() < 1e-5);
            assert!(po.z >= -0.3 - 1e-5 && po.z <= 0.8 + 1e-5);
            assert!(phi_of(po) <= 250f32.to_radians() + 1e-4 || po.y.abs() < 1e-5);
            assert!((n - po).length() < 1e-4);
        }
        // World area: 250° × 1 × 1.1, times scale² = 4.
        assert!((s.area() - 250f32.to_radians() * 1.1 * 4.0).abs() < 1e-4);
    }

    /// A whole sphere under a similarity meets rays in world space: the
    /// same distances as in its object space (to rounding), on rays from
    /// outside, from inside, grazing and missing; a non-uniform scale
    /// (an ellipsoid) stays in object space.
    #[test]
    fn world_space_roots_match_object_space() {
        let xf = |m: Mat4| Transform::new(m).unwrap();
        let sim = xf(Mat4::from_translation(Vec3::new(0.3, -1.0, 2.0))
            * Mat4::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.7)
            * Mat4::from_scale(Vec3::splat(1.7)));
        let s = Sphere::new(sim, 0.6, false);
        assert!(s.world_space);
        assert!(!Sphere::partial(sim, 0.6, -0.6, 0.3, 360.0, false).world_space);
        let ellipsoid = Sphere::new(xf(Mat4::from_scale(Vec3::new(1.0, 2.0, 1.0))), 1.0, false);
        assert!(!ellipsoid.world_space);
        // Along y the ellipsoid reaches 2: a ray down its y axis meets it there.
        let r = Ray::new(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y);
        assert!((ellipsoid.intersect(&r, f32::INFINITY).unwrap() - 3.0).abs() < 1e-5);
        let object = Sphere {
            world_space: false,
            ..s
        };
        let mut rng = lumis_math::Pcg32::new(5, 1);
        let mut lengths = lumis_math::Pcg32::new(6, 1);
        let mut v = || Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - 1.0;
        let (mut hits, mut misses) = (0, 0);
        for i in 0..4000 {
            let o = match i % 3 {
                0 => s.center + v() * 3.0,
                1 => s.center + v() * 0.5, // inside
                // Just off it, as a ray spawned from a hit (either side).
                _ => {
                    let off = if i % 2 == 0 { 1.001 } else { 0.999 };
                    s.center + v().normalize_or_zero() * s.world_radius * off
                }
            };
            let aim = s.center + v() * s.world_radius * 1.2 - o; // some graze or miss
            let ray = Ray::new(o, aim * (0.5 + lengths.next_f32()));
            let (a, b) = (
                s.intersect(&ray, f32::INFINITY),
                object.intersect(&ray, f32::INFINITY),
            );
            match (a, b) {
                (Some(a), Some(b)) => {
                    let scale = (ray.d.length() * a).max(1e-3);
                    assert!(
                        (a - b).abs() * ray.d.length() <= 1e-4 * scale.max(1.0),
                        "{a} {b}"
                    );
                    hits += 1;
                }
                (None, None) => misses += 1,
                // Only tangent rays may disagree on hitting at all.
                (a, b) => {
                    let t = a.or(b).unwrap();
                    let p = ray.at(t) - s.center;
                    let along = p.dot(ray.d.normalize()).abs() / s.world_radius;
                    assert!(along < 1e-2, "{a:?} {b:?}: not a grazing ray");
                }
            }
        }
        assert!(hits > 2000 && misses > 100, "{hits} hits, {misses} misses");
    }
}
