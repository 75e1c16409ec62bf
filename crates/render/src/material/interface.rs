use crate::bsdf::{Bsdf, Dielectric};

/// pbrt-v4's `interface`: no surface, only a boundary between media. Shapes
/// made of it are left out of the scene when they do not emit (lumis renders
/// no media yet, so they could change nothing); an emitting one lets rays
/// through unchanged (a smooth boundary with relative IOR 1).
#[derive(Clone, Debug)]
pub struct InterfaceMaterial;

impl InterfaceMaterial {
    pub fn bsdf(&self) -> Bsdf {
        Bsdf::Dielectric(Dielectric::new(1.0, 0.0, 0.0))
    }
}
