use super::coat::Coat;
use super::{ConductorSpec, Roughness};
use crate::bsdf::layered::Base;
use crate::bsdf::Bsdf;
use crate::texture::{TexCtx, Textures};

/// pbrt-v4's `coatedconductor`: a dielectric coat over a (rough) conductor
/// whose optical constants are taken relative to the coat's index.
#[derive(Clone, Debug)]
pub struct CoatedConductorMaterial {
    pub spec: ConductorSpec,
    pub roughness: Roughness,
    pub coat: Coat,
}

impl CoatedConductorMaterial {
    pub fn bsdf(&self, t: &Textures, c: &TexCtx) -> Bsdf {
        let mut base = self.spec.bsdf(t, c, self.roughness.microfacet(t, c));
        let eta = self.coat.eta();
        base.eta /= eta;
        base.k /= eta;
        self.coat.bsdf(t, c, Base::Conductor(base))
    }
}
