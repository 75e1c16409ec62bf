use super::Roughness;
use crate::bsdf::{Bsdf, Dielectric};
use crate::texture::{TexCtx, Textures};

#[derive(Clone, Debug)]
pub struct DielectricMaterial {
    pub eta: f32,
    pub roughness: Roughness,
}

impl DielectricMaterial {
    pub fn bsdf(&self, t: &Textures, c: &TexCtx) -> Bsdf {
        Bsdf::Dielectric(Dielectric::with_microfacet(
            self.eta,
            self.roughness.microfacet(t, c),
        ))
    }
}
