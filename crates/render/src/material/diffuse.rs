use crate::bsdf::{Bsdf, Diffuse};
use crate::texture::{TexCtx, TexRgb, Textures};

#[derive(Clone, Debug)]
pub struct DiffuseMaterial {
    pub reflectance: TexRgb,
}

impl DiffuseMaterial {
    pub fn bsdf(&self, t: &Textures, c: &TexCtx) -> Bsdf {
        Bsdf::Diffuse(Diffuse::new(super::clamp01(self.reflectance.eval(t, c))))
    }
}
