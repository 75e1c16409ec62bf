use crate::bsdf::microfacet::{Microfacet, MicrofacetModel};
use crate::texture::{TexCtx, TexFloat, Textures};

/// pbrt-v4's `uroughness` / `vroughness` (or `roughness`) and `remaproughness`:
/// Trowbridge-Reitz alphas, possibly textured.
#[derive(Clone, Copy, Debug)]
pub struct Roughness {
    pub u: TexFloat,
    pub v: TexFloat,
    /// Map roughness to alpha by `sqrt` (pbrt-v4's `RoughnessToAlpha`).
    pub remap: bool,
    /// The normal distribution (lumis' `"string distribution"` extension;
    /// pbrt-v4 has only Trowbridge-Reitz).
    pub model: MicrofacetModel,
}

impl Roughness {
    pub const SMOOTH: Roughness = Roughness {
        u: TexFloat::Const(0.0),
        v: TexFloat::Const(0.0),
        remap: false,
        model: MicrofacetModel::TrowbridgeReitz,
    };

    fn alpha(&self, r: f32) -> f32 {
        if self.remap {
            r.max(0.0).sqrt()
        } else {
            r.max(0.0)
        }
    }

    /// The microfacet distribution at a shading point.
    pub fn microfacet(&self, t: &Textures, c: &TexCtx) -> Microfacet {
        let (ax, ay) = (self.alpha(self.u.eval(t, c)), self.alpha(self.v.eval(t, c)));
        Microfacet::new(self.model, ax, ay)
    }

    /// The larger alpha when both are constants.
    pub fn const_max_alpha(&self) -> Option<f32> {
        Some(
            self.alpha(self.u.constant()?)
                .max(self.alpha(self.v.constant()?)),
        )
    }
}
