use crate::bsdf::{Bsdf, Phong};
use crate::texture::{TexCtx, TexRgb, Textures};

/// Energy-normalised modified Phong (Lafortune & Willems 1994): a lumis
/// extension for comparisons with classic photon-mapping work.
#[derive(Clone, Debug)]
pub struct PhongMaterial {
    pub kd: TexRgb,
    pub ks: TexRgb,
    pub exponent: f32,
}

impl PhongMaterial {
    pub fn bsdf(&self, t: &Textures, c: &TexCtx) -> Bsdf {
        Bsdf::Phong(Phong::new(
            self.kd.eval(t, c),
            self.ks.eval(t, c),
            self.exponent,
        ))
    }
}
