use super::{TexCtx, TexRgb, Textures};
use lumis_math::Rgb;

/// pbrt-v4's `mix`: `(1 - amount) tex1 + amount tex2`.
#[derive(Clone, Copy, Debug)]
pub struct MixTexture {
    pub tex1: TexRgb,
    pub tex2: TexRgb,
    /// A float texture (its first channel is used).
    pub amount: TexRgb,
}

impl MixTexture {
    pub fn eval(&self, t: &Textures, c: &TexCtx) -> Rgb {
        let a = self.amount.eval(t, c).r;
        let t1 = if a != 1.0 {
            self.tex1.eval(t, c)
        } else {
            Rgb::BLACK
        };
        let t2 = if a != 0.0 {
            self.tex2.eval(t, c)
        } else {
            Rgb::BLACK
        };
        t1 * (1.0 - a) + t2 * a
    }
}
