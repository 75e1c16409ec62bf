//! Conductors: complex Fresnel reflectance, either a perfect mirror or an
//! anisotropic Trowbridge-Reitz microfacet surface (pbrt-v4 §9.6).

use super::fresnel::fr_complex_rgb;
use super::microfacet::Microfacet;
use super::{reflect_z, same_hemisphere, BsdfSample};
use lumis_math::{Rgb, Vec2, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor {
    /// Real part of the complex IOR, per channel.
    pub eta: Rgb,
    /// Absorption coefficient (imaginary part of the IOR), per channel.
    pub k: Rgb,
    pub distrib: Microfacet,
}

impl Conductor {
    /// `alpha_x`, `alpha_y`: GGX roughness along the shading frame's tangents;
    /// below 1e-3 the surface is a perfect (delta) mirror.
    pub fn new(eta: Rgb, k: Rgb, alpha_x: f32, alpha_y: f32) -> Self {
        Self::with_microfacet(eta, k, Microfacet::trowbridge_reitz(alpha_x, alpha_y))
    }

    /// A conductor with any microfacet distribution.
    pub fn with_microfacet(eta: Rgb, k: Rgb, distrib: Microfacet) -> Self {
        Conductor { eta, k, distrib }
    }

    /// A conductor whose normal-incidence reflectance is `r`: `eta = 1`,
    /// `k = 2 sqrt(r) / sqrt(1 - r)` with `r` clamped below 0.9999 (as pbrt-v4).
    pub fn from_reflectance(r: Rgb, alpha_x: f32, alpha_y: f32) -> Self {
        Self::from_reflectance_with(r, Microfacet::trowbridge_reitz(alpha_x, alpha_y))
    }

    /// [`Self::from_reflectance`] with any microfacet distribution.
    pub fn from_reflectance_with(r: Rgb, distrib: Microfacet) -> Self {
        let k = r.map(|v| {
            let v = v.clamp(0.0, 0.9999);
            2.0 * v.sqrt() / (1.0 - v).sqrt()
        });
        Conductor::with_microfacet(Rgb::WHITE, k, distrib)
    }

    pub fn is_delta(&self) -> bool {
        self.distrib.effectively_smooth()
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if self.is_delta() || !same_hemisphere(wo, wi) {
            return Rgb::BLACK;
        }
        let (cos_o, cos_i) = (wo.z.abs(), wi.z.abs());
        let wm = wi + wo;
        if wm.length_squared() == 0.0 {
            return Rgb::BLACK;
        }
        let wm = wm.normalize();
        let fr = fr_complex_rgb(wo.dot(wm).abs(), self.eta, self.k);
        fr * (self.distrib.d(wm) * self.distrib.g(wo, wi) / (4.0 * cos_i * cos_o))
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if self.is_delta() || !same_hemisphere(wo, wi) {
            return 0.0;
        }
        let wm = wi + wo;
        if wm.length_squared() == 0.0 {
            return 0.0;
        }
        // Visible normals live in the upper hemisphere.
        let wm = wm.normalize() * wm.z.signum();
        self.distrib.pdf(wo, wm) / (4.0 * wo.dot(wm).abs())
    }

    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        if self.is_delta() {
            let wi = reflect_z(wo);
            let cos = wi.z.abs();
            return Some(BsdfSample {
                wi,
                f: fr_complex_rgb(cos, self.eta, self.k) / cos,
                pdf: 1.0,
                delta: true,
                transmission: false,
                eta: 1.0,
            });
        }
        let wm = self.distrib.sample_wm(wo, u)?;
        let wi = super::fresnel::reflect(wo, wm);
        if !same_hemisphere(wo, wi) {
            return None;
        }
        let pdf = self.distrib.pdf(wo, wm) / (4.0 * wo.dot(wm).abs());
        let (cos_o, cos_i) = (wo.z.abs(), wi.z.abs());
        if cos_i == 0.0 || pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        let fr = fr_complex_rgb(wo.dot(wm).abs(), self.eta, self.k);
        let f = fr * (self.distrib.d(wm) * self.distrib.g(wo, wi) / (4.0 * cos_i * cos_o));
        Some(BsdfSample {
            wi,
            f,
            pdf,
            delta: false,
            transmission: false,
            eta: 1.0,
        })
    }
}
