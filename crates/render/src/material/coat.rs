//! What pbrt-v4's two coated materials share: the dielectric coat and the
//! slab under it, turned into a [`Layered`] BSDF over a given base.

use super::Roughness;
use crate::bsdf::layered::{Base, Layered};
use crate::bsdf::{Bsdf, Dielectric};
use crate::texture::{TexCtx, TexFloat, TexRgb, Textures};

#[derive(Clone, Debug)]
pub struct Coat {
    pub roughness: Roughness,
    /// Index of refraction of the coat (0 reads as 1, as in pbrt-v4).
    pub eta: f32,
    /// Slab thickness in mean free paths.
    pub thickness: TexFloat,
    pub albedo: TexRgb,
    pub g: TexFloat,
    pub max_depth: u32,
    pub n_samples: u32,
}

impl Coat {
    /// The coat's index of refraction as the BSDF sees it.
    pub fn eta(&self) -> f32 {
        if self.eta == 0.0 {
            1.0
        } else {
            self.eta
        }
    }

    pub fn bsdf(&self, t: &Textures, c: &TexCtx, base: Base) -> Bsdf {
        Bsdf::Layered(Layered::new(
            Dielectric::with_microfacet(self.eta(), self.roughness.microfacet(t, c)),
            base,
            self.thickness.eval(t, c),
            super::clamp01(self.albedo.eval(t, c)),
            self.g.eval(t, c),
            self.max_depth,
            self.n_samples,
        ))
    }
}
