use super::coat::Coat;
use crate::bsdf::layered::Base;
use crate::bsdf::{Bsdf, Diffuse};
use crate::texture::{TexCtx, TexRgb, Textures};

/// pbrt-v4's `coateddiffuse`: a dielectric coat over a Lambertian base.
#[derive(Clone, Debug)]
pub struct CoatedDiffuseMaterial {
    pub reflectance: TexRgb,
    pub coat: Coat,
}

impl CoatedDiffuseMaterial {
    pub fn bsdf(&self, t: &Textures, c: &TexCtx) -> Bsdf {
        let r = super::clamp01(self.reflectance.eval(t, c));
        self.coat.bsdf(t, c, Base::Diffuse(Diffuse::new(r)))
    }
}
