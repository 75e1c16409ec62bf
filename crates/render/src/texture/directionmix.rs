use super::{TexCtx, TexRgb, Textures};
use lumis_math::{Rgb, Vec3};

/// pbrt-v4's `directionmix`: `tex1` where the shading normal faces `dir`
/// (weight `|n . dir|`), `tex2` where it is perpendicular.
#[derive(Clone, Copy, Debug)]
pub struct DirectionMixTexture {
    pub tex1: TexRgb,
    pub tex2: TexRgb,
    /// Unit direction in world space.
    pub dir: Vec3,
}

impl DirectionMixTexture {
    pub fn eval(&self, t: &Textures, c: &TexCtx) -> Rgb {
        let a = c.n.dot(self.dir).abs().min(1.0);
        let t1 = if a != 0.0 {
            self.tex1.eval(t, c)
        } else {
            Rgb::BLACK
        };
        let t2 = if a != 1.0 {
            self.tex2.eval(t, c)
        } else {
            Rgb::BLACK
        };
        t1 * a + t2 * (1.0 - a)
    }
}
