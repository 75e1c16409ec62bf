//! Materials: what a surface is made of, turned into a BSDF at a hit.
//!
//! To add a material: a file here with its struct and `bsdf()`, a variant in
//! [`Material`], and its parameters in `load/materials.rs`.

pub mod conductor;
mod dielectric;
mod diffuse;
mod phong;
pub mod spectra;

pub use conductor::{ConductorMaterial, ConductorSpec};
pub use dielectric::DielectricMaterial;
pub use diffuse::DiffuseMaterial;
pub use phong::PhongMaterial;

use crate::bsdf::{Bsdf, SurfaceBsdf};
use crate::geometry::SurfaceGeom;
use lumis_math::Frame;

#[derive(Clone, Debug)]
pub enum Material {
    Diffuse(DiffuseMaterial),
    Conductor(ConductorMaterial),
    Dielectric(DielectricMaterial),
    Phong(PhongMaterial),
}

impl Material {
    pub fn bsdf(&self, geom: &SurfaceGeom) -> Bsdf {
        match self {
            Material::Diffuse(m) => m.bsdf(geom),
            Material::Conductor(m) => m.bsdf(geom),
            Material::Dielectric(m) => m.bsdf(geom),
            Material::Phong(m) => m.bsdf(geom),
        }
    }

    /// Perfectly specular everywhere (smooth glass or mirror): a target for
    /// aimed caustic photons.
    pub fn is_specular(&self) -> bool {
        match self {
            Material::Dielectric(m) => m.alpha_x.max(m.alpha_y) < 1e-3,
            Material::Conductor(m) => m.alpha_x.max(m.alpha_y) < 1e-3,
            _ => false,
        }
    }

    /// The BSDF in world space at a hit, with the shading frame.
    pub fn surface_bsdf(&self, geom: &SurfaceGeom) -> SurfaceBsdf {
        SurfaceBsdf::new(
            Frame::from_normal_tangent(geom.ns, geom.dpdu),
            geom.ng,
            self.bsdf(geom),
        )
    }
}
