use super::Roughness;
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
    pub fn bsdf(&self, t: &Textures, c: &TexCtx, ax: f32, ay: f32) -> Conductor {
        match self {
            ConductorSpec::EtaK { eta, k } => Conductor::new(eta.eval(t, c), k.eval(t, c), ax, ay),
            ConductorSpec::Reflectance(r) => {
                Conductor::from_reflectance(super::clamp01(r.eval(t, c)), ax, ay)
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
        let (ax, ay) = self.roughness.alphas(t, c);
        Bsdf::Conductor(self.spec.bsdf(t, c, ax, ay))
    }
}
