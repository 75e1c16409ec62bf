use crate::bsdf::{Bsdf, Dielectric};
use crate::geometry::SurfaceGeom;

#[derive(Clone, Debug)]
pub struct DielectricMaterial {
    pub eta: f32,
    pub alpha_x: f32,
    pub alpha_y: f32,
}

impl DielectricMaterial {
    pub fn bsdf(&self, _g: &SurfaceGeom) -> Bsdf {
        Bsdf::Dielectric(Dielectric::new(self.eta, self.alpha_x, self.alpha_y))
    }
}
