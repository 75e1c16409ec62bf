//! Diffuse area light on one primitive (pbrt's "diffuse" AreaLightSource).

use super::shape_sample::{pdf_solid_angle, sample_area, sample_solid_angle};
use super::{LeSample, LiSample};
use crate::geometry::{offset_ray_origin, Prim, Ray};
use crate::scene::Shapes;
use lumis_math::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use lumis_math::{Frame, Rgb, Vec2, Vec3, PI};

#[derive(Clone, Debug)]
pub struct AreaLight {
    pub prim: Prim,
    /// Emitted radiance, scale included.
    pub lemit: Rgb,
    pub two_sided: bool,
}

impl AreaLight {
    #[inline]
    pub fn l(&self, n: Vec3, w: Vec3) -> Rgb {
        if !self.two_sided && n.dot(w) <= 0.0 {
            return Rgb::BLACK;
        }
        self.lemit
    }

    pub fn sample_li(&self, shapes: &Shapes, p_ref: Vec3, u: Vec2) -> Option<LiSample> {
        let sp = sample_solid_angle(shapes, self.prim, p_ref, u)?;
        let d = sp.p - p_ref;
        let len = d.length();
        if len == 0.0 || sp.pdf == 0.0 || !sp.pdf.is_finite() {
            return None;
        }
        let wi = d / len;
        let li = self.l(sp.n, -wi);
        if li.is_black() {
            return None;
        }
        Some(LiSample {
            wi,
            li,
            pdf: sp.pdf,
            p_light: sp.p,
            n_light: sp.n,
            delta: false,
            infinite: false,
        })
    }

    pub fn pdf_li(&self, shapes: &Shapes, p_ref: Vec3, p: Vec3, n: Vec3) -> f32 {
        pdf_solid_angle(shapes, self.prim, p_ref, p, n)
    }

    pub fn sample_le(&self, shapes: &Shapes, u1: Vec2, u2: Vec2) -> Option<LeSample> {
        let sp = sample_area(shapes, self.prim, u1);
        let mut n = sp.n;
        let mut u = u2;
        let mut dir_pdf_scale = 1.0;
        if self.two_sided {
            // Pick a side, reusing the sample dimension.
            if u.x < 0.5 {
                u.x *= 2.0;
            } else {
                u.x = (u.x - 0.5) * 2.0;
                n = -n;
            }
            dir_pdf_scale = 0.5;
        }
        let local = square_to_cosine_hemisphere(u);
        let d = Frame::from_normal(n).to_world(local);
        let pdf_dir = cosine_hemisphere_pdf(local.z) * dir_pdf_scale;
        if pdf_dir == 0.0 {
            return None;
        }
        let ray = Ray::new(offset_ray_origin(sp.p, n), d);
        Some(LeSample {
            ray,
            le: self.lemit,
            pdf_pos: sp.pdf,
            pdf_dir,
            n,
            delta_pos: false,
            delta_dir: false,
        })
    }

    pub fn power(&self, shapes: &Shapes) -> Rgb {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        self.lemit * (PI * sides * shapes.area(self.prim))
    }
}
