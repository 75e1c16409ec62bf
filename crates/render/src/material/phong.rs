use crate::bsdf::{Bsdf, Phong};
use crate::geometry::SurfaceGeom;
use lumis_math::Rgb;

/// Energy-normalised modified Phong (Lafortune & Willems 1994): a lumis
/// extension for comparisons with classic photon-mapping work.
#[derive(Clone, Debug)]
pub struct PhongMaterial {
    pub kd: Rgb,
    pub ks: Rgb,
    pub exponent: f32,
}

impl PhongMaterial {
    pub fn bsdf(&self, _g: &SurfaceGeom) -> Bsdf {
        Bsdf::Phong(Phong::new(self.kd, self.ks, self.exponent))
    }
}
