use crate::bsdf::{Bsdf, Conductor};
use crate::geometry::SurfaceGeom;
use lumis_math::Rgb;

#[derive(Clone, Debug)]
pub enum ConductorSpec {
    /// Complex index of refraction per channel.
    EtaK { eta: Rgb, k: Rgb },
    /// Normal-incidence reflectance (pbrt-v4's `reflectance` parameter).
    Reflectance(Rgb),
}

#[derive(Clone, Debug)]
pub struct ConductorMaterial {
    pub spec: ConductorSpec,
    /// Trowbridge-Reitz alphas (already remapped from roughness if asked).
    pub alpha_x: f32,
    pub alpha_y: f32,
}

impl ConductorMaterial {
    pub fn bsdf(&self, _g: &SurfaceGeom) -> Bsdf {
        Bsdf::Conductor(match self.spec {
            ConductorSpec::EtaK { eta, k } => Conductor::new(eta, k, self.alpha_x, self.alpha_y),
            ConductorSpec::Reflectance(r) => {
                Conductor::from_reflectance(r, self.alpha_x, self.alpha_y)
            }
        })
    }
}
