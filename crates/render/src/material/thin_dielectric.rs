use crate::bsdf::{Bsdf, ThinDielectric};

/// pbrt-v4's `thindielectric`: a thin sheet of glass (see
/// [`ThinDielectric`]), perfectly specular on both sides.
#[derive(Clone, Debug)]
pub struct ThinDielectricMaterial {
    pub eta: f32,
}

impl ThinDielectricMaterial {
    pub fn bsdf(&self) -> Bsdf {
        Bsdf::ThinDielectric(ThinDielectric::new(self.eta))
    }
}
