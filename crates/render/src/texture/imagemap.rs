use super::mapping::Mapping2D;
use super::mipmap::{FilterKind, WrapMode};
use super::{TexCtx, Textures};
use lumis_math::{Rgb, Vec2};

/// pbrt-v4's `imagemap`: a filtered lookup in a shared image pyramid.
#[derive(Clone, Copy, Debug)]
pub struct ImageTexture {
    /// Index into [`Textures::mipmaps`].
    pub mipmap: u32,
    pub mapping: Mapping2D,
    pub filter: FilterKind,
    pub wrap: WrapMode,
    pub scale: f32,
    pub invert: bool,
    /// A float texture reads the first channel only.
    pub float: bool,
}

impl ImageTexture {
    pub fn eval(&self, t: &Textures, c: &TexCtx) -> Rgb {
        let tc = self.mapping.map(c);
        // Image rows run top to bottom; t = 0 is the bottom row.
        let st = Vec2::new(tc.st.x, 1.0 - tc.st.y);
        let (d0, d1) = (
            Vec2::new(tc.dst_dx.x, -tc.dst_dx.y),
            Vec2::new(tc.dst_dy.x, -tc.dst_dy.y),
        );
        let mut v =
            t.mipmaps[self.mipmap as usize].filter(st, d0, d1, self.filter, self.wrap) * self.scale;
        if self.float {
            v = Rgb::splat(v.r);
        }
        if self.invert {
            v = Rgb::WHITE - v;
        }
        v.map(|x| x.max(0.0))
    }
}
