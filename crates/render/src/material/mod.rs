//! Materials: what a surface is made of, turned into a BSDF at a hit.
//!
//! To add a material: a file here with its struct and `bsdf()`, a variant in
//! [`MaterialKind`], and its parameters in a file of `load/material/`.
//! Parameters that pbrt-v4 allows to be textures are
//! [`TexRgb`](crate::texture::TexRgb) / [`TexFloat`](crate::texture::TexFloat).

mod coat;
mod coated_conductor;
mod coated_diffuse;
pub mod conductor;
mod dielectric;
mod diffuse;
mod diffuse_transmission;
mod interface;
mod mix;
mod phong;
mod roughness;
pub mod shading;
pub mod spectra;
mod thin_dielectric;

pub use coat::Coat;
pub use coated_conductor::CoatedConductorMaterial;
pub use coated_diffuse::CoatedDiffuseMaterial;
pub use conductor::{ConductorMaterial, ConductorSpec};
pub use dielectric::DielectricMaterial;
pub use diffuse::DiffuseMaterial;
pub use diffuse_transmission::DiffuseTransmissionMaterial;
pub use interface::InterfaceMaterial;
pub use mix::MixMaterial;
pub use phong::PhongMaterial;
pub use roughness::Roughness;
pub use shading::Shading;
pub use thin_dielectric::ThinDielectricMaterial;

use crate::bsdf::{Bsdf, SurfaceBsdf};
use crate::geometry::SurfaceGeom;
use crate::texture::{TexCtx, Textures};
use lumis_math::{Frame, Rgb, Vec3};

#[derive(Clone, Debug)]
pub enum MaterialKind {
    Diffuse(DiffuseMaterial),
    Conductor(ConductorMaterial),
    Dielectric(DielectricMaterial),
    Phong(PhongMaterial),
    Mix(MixMaterial),
    Interface(InterfaceMaterial),
    ThinDielectric(ThinDielectricMaterial),
    DiffuseTransmission(DiffuseTransmissionMaterial),
    CoatedDiffuse(CoatedDiffuseMaterial),
    CoatedConductor(CoatedConductorMaterial),
}

/// A material and how it bends the shading normal (bump or normal map).
#[derive(Clone, Debug)]
pub struct Material {
    pub kind: MaterialKind,
    pub shading: Shading,
    /// The media on the surface's two sides, for shapes whose
    /// `MediumInterface` changes the medium (the loader gives each such
    /// material and interface pair its own id); `None` elsewhere.
    pub media: Option<crate::media::MediumInterface>,
    /// The shape's `alpha` cutout (pbrt-v4): where it is below 1 the
    /// surface is there for only that fraction of rays. The loader gives
    /// each shape with one its own copy of the material.
    pub alpha: Option<crate::texture::TexFloat>,
}

impl From<MaterialKind> for Material {
    fn from(kind: MaterialKind) -> Self {
        Material {
            kind,
            shading: Shading::Smooth,
            media: None,
            alpha: None,
        }
    }
}

impl Material {
    /// The BSDF in the local shading frame for a texture context.
    pub fn bsdf(&self, t: &Textures, c: &TexCtx) -> Bsdf {
        match &self.kind {
            MaterialKind::Diffuse(m) => m.bsdf(t, c),
            MaterialKind::Conductor(m) => m.bsdf(t, c),
            MaterialKind::Dielectric(m) => m.bsdf(t, c),
            MaterialKind::Phong(m) => m.bsdf(t, c),
            MaterialKind::Interface(m) => m.bsdf(),
            MaterialKind::ThinDielectric(m) => m.bsdf(),
            MaterialKind::DiffuseTransmission(m) => m.bsdf(t, c),
            MaterialKind::CoatedDiffuse(m) => m.bsdf(t, c),
            MaterialKind::CoatedConductor(m) => m.bsdf(t, c),
            // Resolved by `surface_bsdf` before a BSDF is asked for.
            MaterialKind::Mix(_) => Bsdf::Diffuse(crate::bsdf::Diffuse::new(Rgb::BLACK)),
        }
    }

    /// Perfectly specular everywhere (smooth glass or mirror): a target for
    /// aimed caustic photons.
    pub fn is_specular(&self) -> bool {
        let smooth = |r: &Roughness| r.const_max_alpha().is_some_and(|a| a < 1e-3);
        match &self.kind {
            MaterialKind::Dielectric(m) => smooth(&m.roughness),
            MaterialKind::Conductor(m) => smooth(&m.roughness),
            MaterialKind::ThinDielectric(_) => true,
            _ => false,
        }
    }

    /// No BSDF of this material is delta or has a delta lobe, wherever it
    /// is hit (a photon's specular chain ends on it).
    pub fn never_delta(&self) -> bool {
        match &self.kind {
            MaterialKind::Diffuse(_)
            | MaterialKind::Phong(_)
            | MaterialKind::DiffuseTransmission(_) => true,
            // A conductor is delta where its alpha is below `SMOOTH_ALPHA`.
            MaterialKind::Conductor(m) => m
                .roughness
                .const_max_alpha()
                .is_some_and(|a| a >= crate::bsdf::microfacet::SMOOTH_ALPHA),
            _ => false,
        }
    }

    /// The albedo of a diffuse material with a constant reflectance,
    /// clamped as its BSDF's is; `None` for any other material.
    pub fn constant_diffuse(&self) -> Option<Rgb> {
        match &self.kind {
            MaterialKind::Diffuse(m) => m.reflectance.constant().map(clamp01),
            _ => None,
        }
    }

    pub fn is_interface(&self) -> bool {
        matches!(self.kind, MaterialKind::Interface(_))
    }
}

/// The BSDF in world space at a hit with material `id`: mix materials are
/// resolved (deterministically per point and direction `wo`), textures
/// evaluated over the hit's footprint, bump and normal maps applied.
pub fn surface_bsdf(
    materials: &[Material],
    t: &Textures,
    mut id: u32,
    geom: &SurfaceGeom,
    wo: Vec3,
) -> SurfaceBsdf {
    // Only textures read the footprint: a scene without any skips it
    // (callgrind: 5.9% fewer instructions on a small untextured scene).
    let mut c = if t.textures.is_empty() {
        TexCtx::at(geom.p, geom.ns, geom.uv)
    } else {
        t.footprint.context(geom)
    };
    // Mixes of mixes: bounded, as a cycle cannot be built by the loader.
    for _ in 0..64 {
        match &materials[id as usize].kind {
            MaterialKind::Mix(m) => id = m.choose(t, &c, wo),
            _ => break,
        }
    }
    let m = &materials[id as usize];
    let (ns, dpdu) = m.shading.apply(t, geom, &c);
    c.n = ns;
    SurfaceBsdf::new(Frame::from_normal_tangent(ns, dpdu), geom.ng, m.bsdf(t, &c))
}

/// Reflectances are clamped to [0, 1] as pbrt-v4's albedo spectra are.
pub(crate) fn clamp01(c: Rgb) -> Rgb {
    c.map(|v| v.clamp(0.0, 1.0))
}
