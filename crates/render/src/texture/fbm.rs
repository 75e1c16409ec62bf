use super::mapping::Mapping3D;
use super::noise::fbm;
use super::TexCtx;
use lumis_math::Rgb;

/// pbrt-v4's `fbm` (a float texture; as a spectrum, grey as in pbrt-v3):
/// fractional Brownian motion of the point in texture space, `octaves`
/// octaves of weight `roughness^i`.
#[derive(Clone, Copy, Debug)]
pub struct FbmTexture {
    pub mapping: Mapping3D,
    pub octaves: u32,
    pub omega: f32,
}

impl FbmTexture {
    pub fn eval(&self, c: &TexCtx) -> Rgb {
        let m = self.mapping.map(c);
        Rgb::splat(fbm(m.p, m.dpdx, m.dpdy, self.omega, self.octaves))
    }
}
