use super::{TexCtx, TexRgb, Textures};
use lumis_math::Rgb;

/// pbrt-v4's `scale`: `tex * scale`.
#[derive(Clone, Copy, Debug)]
pub struct ScaleTexture {
    pub tex: TexRgb,
    pub scale: TexRgb,
}

impl ScaleTexture {
    pub fn eval(&self, t: &Textures, c: &TexCtx) -> Rgb {
        let s = self.scale.eval(t, c);
        if s.is_black() {
            return Rgb::BLACK;
        }
        self.tex.eval(t, c) * s
    }
}
