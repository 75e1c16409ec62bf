use crate::bsdf::{Bsdf, DiffuseTransmission};
use crate::texture::{TexCtx, TexRgb, Textures};

/// pbrt-v4's `diffusetransmission`: Lambertian reflection and transmission,
/// `scale * reflectance` and `scale * transmittance` clamped to [0, 1].
#[derive(Clone, Debug)]
pub struct DiffuseTransmissionMaterial {
    pub reflectance: TexRgb,
    pub transmittance: TexRgb,
    pub scale: f32,
}

impl DiffuseTransmissionMaterial {
    pub fn bsdf(&self, t: &Textures, c: &TexCtx) -> Bsdf {
        let r = super::clamp01(self.reflectance.eval(t, c) * self.scale);
        let tr = super::clamp01(self.transmittance.eval(t, c) * self.scale);
        Bsdf::DiffuseTransmission(DiffuseTransmission::new(r, tr))
    }
}
