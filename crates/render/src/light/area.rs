//! Diffuse area light on one primitive (pbrt's "diffuse" AreaLightSource),
//! emitting a constant radiance or an image (`area_texture.rs`).

use super::area_texture::TexturedEmission;
use super::{EmitCull, LeSample, LiSample};
use crate::geometry::sample::{pdf_solid_angle, sample_area, sample_solid_angle, FlatTriangle};
use crate::geometry::square_map::{square_to_surface, surface_to_square};
use crate::geometry::{offset_ray_origin, Prim, Ray, Shapes};
use lumis_math::sampling::{
    cosine_hemisphere_pdf, disk_concentric_radius, square_to_cosine_hemisphere,
};
use lumis_math::{safe_sqrt, Frame, Rgb, Vec2, Vec3, PI};

#[derive(Clone, Debug)]
pub struct AreaLight {
    pub prim: Prim,
    /// Emitted radiance, scale included; with an image, the image's
    /// multiplier (pbrt-v4's `scale`, and the factor that `power` sets).
    pub lemit: Rgb,
    pub two_sided: bool,
    /// The image and this primitive's sampling density over it.
    pub texture: Option<Box<TexturedEmission>>,
    /// A flat triangle's sampling data (`FlatTriangle::new`), else None.
    pub flat: Option<FlatTriangle>,
}

/// A point on the light with its surface parameters and area density.
#[derive(Clone, Copy, Debug)]
pub struct LightPoint {
    pub p: Vec3,
    pub n: Vec3,
    /// Surface `(u, v)` (only computed for textured lights).
    pub uv: Vec2,
    /// Density per unit area.
    pub pdf: f32,
}

impl AreaLight {
    /// Radiance leaving the point with normal `n` and surface parameters `uv`
    /// in direction `w`.
    #[inline]
    pub fn l(&self, n: Vec3, uv: Vec2, w: Vec3) -> Rgb {
        if !self.two_sided && n.dot(w) <= 0.0 {
            return Rgb::BLACK;
        }
        match &self.texture {
            None => self.lemit,
            Some(t) => self.lemit * t.l(uv),
        }
    }

    /// A point by area: uniform, or by the image's luminance when textured.
    pub fn sample_point(&self, shapes: &Shapes, u: Vec2) -> LightPoint {
        match &self.texture {
            None => {
                let sp = match &self.flat {
                    Some(f) => f.sample(u),
                    None => sample_area(shapes, self.prim, u),
                };
                LightPoint {
                    p: sp.p,
                    n: sp.n,
                    uv: Vec2::ZERO,
                    pdf: sp.pdf,
                }
            }
            Some(t) => {
                let (x, pdf) = t.sample(u);
                let g = square_to_surface(shapes, self.prim, x);
                LightPoint {
                    p: g.p,
                    n: g.ng,
                    uv: g.uv,
                    pdf: pdf / shapes.area(self.prim),
                }
            }
        }
    }

    /// Area density of [`AreaLight::sample_point`] at the light point `p`.
    pub fn pdf_pos(&self, shapes: &Shapes, p: Vec3) -> f32 {
        let a = shapes.area(self.prim);
        match &self.texture {
            None => 1.0 / a,
            Some(t) => t.pdf(surface_to_square(shapes, self.prim, p)) / a,
        }
    }

    pub fn sample_li(&self, shapes: &Shapes, p_ref: Vec3, u: Vec2) -> Option<LiSample> {
        let (p, n, uv, pdf) = match &self.texture {
            None => {
                let sp = sample_solid_angle(shapes, self.prim, p_ref, u)?;
                (sp.p, sp.n, Vec2::ZERO, sp.pdf)
            }
            Some(_) => {
                let lp = self.sample_point(shapes, u);
                (
                    lp.p,
                    lp.n,
                    lp.uv,
                    area_to_solid_angle(lp.pdf, p_ref, lp.p, lp.n),
                )
            }
        };
        let d = p - p_ref;
        let len = d.length();
        if len == 0.0 || pdf == 0.0 || !pdf.is_finite() {
            return None;
        }
        let wi = d / len;
        let li = self.l(n, uv, -wi);
        if li.is_black() {
            return None;
        }
        Some(LiSample {
            wi,
            li,
            pdf,
            p_light: p,
            n_light: n,
            delta: false,
            infinite: false,
        })
    }

    pub fn pdf_li(&self, shapes: &Shapes, p_ref: Vec3, p: Vec3, n: Vec3) -> f32 {
        match &self.texture {
            None => pdf_solid_angle(shapes, self.prim, p_ref, p, n),
            Some(_) => area_to_solid_angle(self.pdf_pos(shapes, p), p_ref, p, n),
        }
    }

    /// Solid-angle density of [`AreaLight::sample_le_culled`]'s direction `w`
    /// from a point with normal `n` (cosine-weighted, each side half of it
    /// when two-sided; 0 behind a one-sided light).
    pub fn pdf_dir(&self, n: Vec3, w: Vec3) -> f32 {
        let cos = n.dot(w);
        if !self.two_sided && cos <= 0.0 {
            return 0.0;
        }
        cos.abs() / PI * if self.two_sided { 0.5 } else { 1.0 }
    }

    /// An emitted ray: a point by area, a cosine-weighted direction; or
    /// `None` as soon as `cull` says that no direction at the sampled polar
    /// angle can be kept, from anywhere on the light (before the point is
    /// sampled) or from the sampled point (before the direction's azimuth,
    /// frame and radiance are computed). A sample `cull` does not refuse is the one
    /// it gives without `cull`.
    pub fn sample_le_culled(
        &self,
        shapes: &Shapes,
        u1: Vec2,
        u2: Vec2,
        cull: Option<&impl EmitCull>,
    ) -> Option<LeSample> {
        let (back, u) = self.emission_side(u2);
        // The cosine-weighted direction's polar angle: its sine is the
        // concentric disc point's radius.
        let polar = cull.map(|c| {
            let sin_t = disk_concentric_radius(u);
            (c, sin_t, safe_sqrt(1.0 - sin_t * sin_t))
        });
        if polar.is_some_and(|(c, _, cos_t)| !c.polar_may_pass(back, cos_t)) {
            return None;
        }
        let sp = self.sample_point(shapes, u1);
        let n = if back { -sp.n } else { sp.n };
        let dir_pdf_scale = if self.two_sided { 0.5 } else { 1.0 };
        let o = offset_ray_origin(sp.p, n);
        if polar.is_some_and(|(c, sin_t, cos_t)| !c.cone_may_pass(o, n, sin_t, cos_t)) {
            return None;
        }
        let local = square_to_cosine_hemisphere(u);
        let d = Frame::from_normal(n).to_world(local);
        let pdf_dir = cosine_hemisphere_pdf(local.z) * dir_pdf_scale;
        if pdf_dir == 0.0 || sp.pdf == 0.0 {
            return None;
        }
        let ray = Ray::new(o, d);
        Some(LeSample {
            ray,
            le: self.l(sp.n, sp.uv, d),
            pdf_pos: sp.pdf,
            pdf_dir,
            n,
            delta_pos: false,
            delta_dir: false,
        })
    }

    /// The side a direction sample `u2` of [`AreaLight::sample_le_culled`]
    /// leaves from (true: against the normal, for two-sided lights) and
    /// the sample left for the direction about that side's normal.
    #[inline]
    pub fn emission_side(&self, mut u: Vec2) -> (bool, Vec2) {
        if !self.two_sided {
            return (false, u);
        }
        // Pick a side, reusing the sample dimension.
        if u.x < 0.5 {
            u.x *= 2.0;
            (false, u)
        } else {
            u.x = (u.x - 0.5) * 2.0;
            (true, u)
        }
    }

    /// Emitted power: `pi * sides * area` times the mean radiance over the
    /// primitive (the image's integral over it for textured lights).
    pub fn power(&self, shapes: &Shapes) -> Rgb {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        let mean = match &self.texture {
            None => self.lemit,
            Some(t) => self.lemit * t.mean,
        };
        mean * (PI * sides * shapes.area(self.prim))
    }
}

/// Solid-angle density at `p_ref` of a light point `p` (normal `n`) sampled
/// with area density `pdf_area`.
fn area_to_solid_angle(pdf_area: f32, p_ref: Vec3, p: Vec3, n: Vec3) -> f32 {
    let d = p - p_ref;
    let dist2 = d.length_squared();
    let cos = n.dot(d).abs() / dist2.sqrt();
    if cos == 0.0 || dist2 == 0.0 {
        return 0.0;
    }
    pdf_area * dist2 / cos
}
