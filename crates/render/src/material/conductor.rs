use super::Roughness;
use crate::bsdf::microfacet::Microfacet;
use crate::bsdf::{Bsdf, Conductor};
use crate::texture::{TexCtx, TexRgb, Textures};

#[derive(Clone, Debug)]
pub enum ConductorSpec {
    /// Complex index of refraction per channel.
    EtaK { eta: TexRgb, k: TexRgb },
    /// Normal-incidence reflectance (pbrt-v4's `reflectance` parameter).
    Reflectance(TexRgb),
}

impl ConductorSpec {
    pub fn bsdf(&self, t: &Textures, c: &TexCtx, m: Microfacet) -> Conductor {
        match self {
            ConductorSpec::EtaK { eta, k } => {
                Conductor::with_microfacet(eta.eval(t, c), k.eval(t, c), m)
            }
            ConductorSpec::Reflectance(r) => {
                Conductor::from_reflectance_with(super::clamp01(r.eval(t, c)), m)
            }
        }
    }
}

#[derive(Clone, Debug)]
pub struct ConductorMaterial {
    pub spec: ConductorSpec,
    pub roughness: Roughness,
}

impl ConductorMaterial {
    pub fn bsdf(&self, t: &Textures, c: &TexCtx) -> Bsdf {
        Bsdf::Conductor(self.spec.bsdf(t, c, self.roughness.microfacet(t, c)))
    }
}
