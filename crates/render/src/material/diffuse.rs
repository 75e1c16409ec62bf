use crate::bsdf::{Bsdf, Diffuse};
use crate::geometry::SurfaceGeom;
use lumis_math::Rgb;

#[derive(Clone, Debug)]
pub struct DiffuseMaterial {
    pub reflectance: Rgb,
}

impl DiffuseMaterial {
    pub fn bsdf(&self, _g: &SurfaceGeom) -> Bsdf {
        Bsdf::Diffuse(Diffuse::new(self.reflectance))
    }
}
