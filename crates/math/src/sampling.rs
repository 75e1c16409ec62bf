//! Warps from the unit square to common domains, each with its density.

use crate::{safe_sqrt, Vec2, Vec3, INV_2PI, INV_4PI, INV_PI, PI};

mod piecewise;
mod sphere_maps;

pub use piecewise::{PiecewiseConstant1D, PiecewiseConstant2D};
pub use sphere_maps::{
    equal_area_sphere_to_square, equal_area_square_to_sphere, latlong_to_sphere, sphere_to_latlong,
    wrap_equal_area_pixel,
};

/// Concentric map of the unit square to the unit disk (Shirley & Chiu).
pub fn square_to_disk_concentric(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, std::f32::consts::FRAC_PI_4 * (o.y / o.x))
    } else {
        (
            o.y,
            std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (o.x / o.y),
        )
    };
    r * Vec2::new(theta.cos(), theta.sin())
}

/// The radius of [`square_to_disk_concentric`]'s point (without its angle):
/// the sine of [`square_to_cosine_hemisphere`]'s polar angle.
#[inline]
pub fn disk_concentric_radius(u: Vec2) -> f32 {
    let o = 2.0 * u - Vec2::ONE;
    o.x.abs().max(o.y.abs())
}

/// Cosine-weighted hemisphere around +z; density `cos(theta)/pi`.
pub fn square_to_cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = square_to_disk_concentric(u);
    let z = safe_sqrt(1.0 - d.x * d.x - d.y * d.y);
    Vec3::new(d.x, d.y, z)
}

#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * INV_PI
}

/// Uniform direction on the unit sphere; density `1/(4 pi)`.
pub fn square_to_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = safe_sqrt(1.0 - z * z);
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

pub const UNIFORM_SPHERE_PDF: f32 = INV_4PI;

/// Uniform direction on the +z hemisphere; density `1/(2 pi)`.
pub fn square_to_uniform_hemisphere(u: Vec2) -> Vec3 {
    let z = u.x;
    let r = safe_sqrt(1.0 - z * z);
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

pub const UNIFORM_HEMISPHERE_PDF: f32 = INV_2PI;

/// Uniform direction in the cone around +z with half-angle `acos(cos_max)`.
pub fn square_to_uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    let cos_theta = (1.0 - u.x) + u.x * cos_max;
    let sin_theta = safe_sqrt(1.0 - cos_theta * cos_theta);
    let phi = 2.0 * PI * u.y;
    Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta)
}

#[inline]
pub fn uniform_cone_pdf(cos_max: f32) -> f32 {
    1.0 / (2.0 * PI * (1.0 - cos_max))
}

/// Uniform barycentrics `(b0, b1)` on a triangle (b2 = 1 - b0 - b1).
pub fn square_to_uniform_triangle(u: Vec2) -> (f32, f32) {
    // Heitz 2019 low-distortion map: keeps strata of `u` apart.
    let (b0, b1);
    if u.x < u.y {
        b0 = u.x / 2.0;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2.0;
        b0 = u.x - b1;
    }
    (b0, b1)
}

/// Spherical direction from angles (z up).
#[inline]
pub fn spherical_direction(sin_theta: f32, cos_theta: f32, phi: f32) -> Vec3 {
    Vec3::new(
        sin_theta.clamp(-1.0, 1.0) * phi.cos(),
        sin_theta.clamp(-1.0, 1.0) * phi.sin(),
        cos_theta.clamp(-1.0, 1.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Pcg32;

    /// Monte Carlo integral of a density over the sphere must be one.
    fn integrates_to_one(pdf: impl Fn(Vec3) -> f32) {
        let mut rng = Pcg32::new(7, 0);
        let n = 200_000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let d = square_to_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            sum += (pdf(d) / UNIFORM_SPHERE_PDF) as f64;
        }
        let mean = sum / n as f64;
        assert!((mean - 1.0).abs() < 0.02, "integral {mean}");
    }

    #[test]
    fn cosine_pdf_normalised() {
        integrates_to_one(|d| cosine_hemisphere_pdf(d.z));
    }

    #[test]
    fn cone_pdf_normalised() {
        let c = 0.7f32;
        integrates_to_one(|d| if d.z >= c { uniform_cone_pdf(c) } else { 0.0 });
    }

    #[test]
    fn warps_land_in_domain() {
        let mut rng = Pcg32::new(3, 1);
        for _ in 0..10_000 {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            assert!(square_to_disk_concentric(u).length() <= 1.0 + 1e-6);
            let r = disk_concentric_radius(u);
            assert!(
                (square_to_disk_concentric(u).length() - r).abs() <= 1e-6,
                "{u:?}"
            );
            let h = square_to_cosine_hemisphere(u);
            assert!(h.z >= 0.0 && (h.length() - 1.0).abs() < 1e-4);
            assert!((square_to_uniform_sphere(u).length() - 1.0).abs() < 1e-4);
            let c = square_to_uniform_cone(u, 0.9);
            assert!(c.z >= 0.9 - 1e-5);
            let (b0, b1) = square_to_uniform_triangle(u);
            assert!(b0 >= 0.0 && b1 >= 0.0 && b0 + b1 <= 1.0 + 1e-6);
        }
    }
}
