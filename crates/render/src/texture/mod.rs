//! Textures: float and spectrum values that vary over surfaces.
//!
//! A closed set: one variant of [`Texture`] per file. Textures live in the
//! scene's [`Textures`] and are referenced by `u32` ids; image pyramids are
//! shared by id (one per file and encoding). Float textures are the same
//! variants evaluated to grey (`r == g == b`); [`TexFloat`] reads the first
//! channel.

mod bilerp;
mod checkerboard;
mod directionmix;
mod dots;
mod fbm;
mod footprint;
pub mod image;
mod imagemap;
pub mod mapping;
mod marble;
pub mod mipmap;
mod mix;
pub mod noise;
mod scale;
pub mod tga;
mod windy;
mod wrinkled;

pub use bilerp::BilerpTexture;
pub use checkerboard::CheckerboardTexture;
pub use directionmix::DirectionMixTexture;
pub use dots::DotsTexture;
pub use fbm::FbmTexture;
pub use footprint::Footprint;
pub use imagemap::ImageTexture;
pub use mapping::{Mapping2D, Mapping3D};
pub use marble::MarbleTexture;
pub use mipmap::{FilterKind, MipMap, WrapMode};
pub use mix::MixTexture;
pub use scale::ScaleTexture;
pub use windy::WindyTexture;
pub use wrinkled::WrinkledTexture;

use lumis_math::{Rgb, Vec2, Vec3};

#[derive(Clone, Copy, Debug)]
pub enum Texture {
    Constant(Rgb),
    Image(ImageTexture),
    Checkerboard(CheckerboardTexture),
    Scale(ScaleTexture),
    Mix(MixTexture),
    DirectionMix(DirectionMixTexture),
    Bilerp(BilerpTexture),
    Dots(DotsTexture),
    Fbm(FbmTexture),
    Wrinkled(WrinkledTexture),
    Windy(WindyTexture),
    Marble(MarbleTexture),
}

/// Where a texture is evaluated: the shading point with its screen-space
/// footprint (pbrt-v4's TextureEvalContext).
#[derive(Clone, Copy, Debug)]
pub struct TexCtx {
    pub p: Vec3,
    /// Shading normal.
    pub n: Vec3,
    pub uv: Vec2,
    pub dpdx: Vec3,
    pub dpdy: Vec3,
    pub dudx: f32,
    pub dudy: f32,
    pub dvdx: f32,
    pub dvdy: f32,
}

impl TexCtx {
    /// A context without footprint (lookups read the finest level).
    pub fn at(p: Vec3, n: Vec3, uv: Vec2) -> TexCtx {
        TexCtx {
            p,
            n,
            uv,
            dpdx: Vec3::ZERO,
            dpdy: Vec3::ZERO,
            dudx: 0.0,
            dudy: 0.0,
            dvdx: 0.0,
            dvdy: 0.0,
        }
    }
}

/// A spectrum (or float) parameter: a constant or a texture id.
#[derive(Clone, Copy, Debug)]
pub enum TexRgb {
    Const(Rgb),
    Tex(u32),
}

impl TexRgb {
    #[inline]
    pub fn eval(&self, t: &Textures, c: &TexCtx) -> Rgb {
        match *self {
            TexRgb::Const(v) => v,
            TexRgb::Tex(id) => t.eval(id, c),
        }
    }

    pub fn constant(&self) -> Option<Rgb> {
        match *self {
            TexRgb::Const(v) => Some(v),
            TexRgb::Tex(_) => None,
        }
    }
}

/// A float parameter: a constant or a (float) texture id.
#[derive(Clone, Copy, Debug)]
pub enum TexFloat {
    Const(f32),
    Tex(u32),
}

impl TexFloat {
    #[inline]
    pub fn eval(&self, t: &Textures, c: &TexCtx) -> f32 {
        match *self {
            TexFloat::Const(v) => v,
            TexFloat::Tex(id) => t.eval(id, c).r,
        }
    }

    pub fn constant(&self) -> Option<f32> {
        match *self {
            TexFloat::Const(v) => Some(v),
            TexFloat::Tex(_) => None,
        }
    }
}

/// All textures and image pyramids of a scene, and how footprints are found.
#[derive(Clone, Debug, Default)]
pub struct Textures {
    pub textures: Vec<Texture>,
    pub mipmaps: Vec<MipMap>,
    /// Normal-map images (linear, unfiltered bilinear lookups), by id.
    pub normal_maps: Vec<mipmap::Level>,
    pub footprint: Footprint,
}

impl Textures {
    pub fn eval(&self, id: u32, c: &TexCtx) -> Rgb {
        match &self.textures[id as usize] {
            Texture::Constant(v) => *v,
            Texture::Image(t) => t.eval(self, c),
            Texture::Checkerboard(t) => t.eval(self, c),
            Texture::Scale(t) => t.eval(self, c),
            Texture::Mix(t) => t.eval(self, c),
            Texture::DirectionMix(t) => t.eval(self, c),
            Texture::Bilerp(t) => t.eval(c),
            Texture::Dots(t) => t.eval(self, c),
            Texture::Fbm(t) => t.eval(c),
            Texture::Wrinkled(t) => t.eval(c),
            Texture::Windy(t) => t.eval(c),
            Texture::Marble(t) => t.eval(c),
        }
    }

    pub fn push(&mut self, t: Texture) -> u32 {
        self.textures.push(t);
        (self.textures.len() - 1) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::mipmap::Level;
    use super::*;

    fn ctx(uv: Vec2) -> TexCtx {
        TexCtx::at(Vec3::ZERO, Vec3::Z, uv)
    }

    #[test]
    fn nested_textures() {
        let mut t = Textures::default();
        let c1 = t.push(Texture::Constant(Rgb::new(1.0, 0.5, 0.25)));
        let half = t.push(Texture::Constant(Rgb::splat(0.5)));
        let s = t.push(Texture::Scale(ScaleTexture {
            tex: TexRgb::Tex(c1),
            scale: TexRgb::Tex(half),
        }));
        assert_eq!(t.eval(s, &ctx(Vec2::ZERO)), Rgb::new(0.5, 0.25, 0.125));
        let m = t.push(Texture::Mix(MixTexture {
            tex1: TexRgb::Const(Rgb::BLACK),
            tex2: TexRgb::Tex(c1),
            amount: TexRgb::Const(Rgb::splat(0.25)),
        }));
        assert_eq!(t.eval(m, &ctx(Vec2::ZERO)), Rgb::new(0.25, 0.125, 0.0625));
        let d = t.push(Texture::DirectionMix(DirectionMixTexture {
            tex1: TexRgb::Const(Rgb::WHITE),
            tex2: TexRgb::Const(Rgb::BLACK),
            dir: Vec3::new(0.0, 0.6, 0.8),
        }));
        assert!((t.eval(d, &ctx(Vec2::ZERO)).g - 0.8).abs() < 1e-6);
        assert_eq!(TexFloat::Tex(half).eval(&t, &ctx(Vec2::ZERO)), 0.5);
    }

    #[test]
    fn checkerboard_squares() {
        let mut t = Textures::default();
        let uv = Mapping2D::Uv {
            su: 4.0,
            sv: 4.0,
            du: 0.0,
            dv: 0.0,
        };
        let id = t.push(Texture::Checkerboard(CheckerboardTexture {
            mapping: uv,
            map3d: None,
            tex1: TexRgb::Const(Rgb::splat(1.0)),
            tex2: TexRgb::Const(Rgb::splat(0.0)),
        }));
        assert_eq!(t.eval(id, &ctx(Vec2::new(0.1, 0.1))).r, 1.0);
        assert_eq!(t.eval(id, &ctx(Vec2::new(0.3, 0.1))).r, 0.0);
        assert_eq!(t.eval(id, &ctx(Vec2::new(0.3, 0.3))).r, 1.0);
        // A footprint covering many squares averages to one half.
        let mut c = ctx(Vec2::new(0.3, 0.3));
        c.dudx = 2.0;
        c.dvdy = 2.0;
        assert!((t.eval(id, &c).r - 0.5).abs() < 0.05);
    }

    #[test]
    fn image_texture_orientation_scale_invert() {
        // 1x2 image: top row white, bottom row black.
        let mut t = Textures::default();
        t.mipmaps.push(MipMap::new(Level {
            width: 1,
            height: 2,
            texels: vec![Rgb::WHITE, Rgb::new(0.0, 0.2, 0.4)],
        }));
        let img = ImageTexture {
            mipmap: 0,
            mapping: Mapping2D::Uv {
                su: 1.0,
                sv: 1.0,
                du: 0.0,
                dv: 0.0,
            },
            filter: FilterKind::Bilinear,
            wrap: WrapMode::Clamp,
            scale: 2.0,
            invert: false,
            float: false,
        };
        let a = t.push(Texture::Image(img));
        // v near 0 is the bottom row.
        assert_eq!(
            t.eval(a, &ctx(Vec2::new(0.5, 0.1))),
            Rgb::new(0.0, 0.4, 0.8)
        );
        assert_eq!(t.eval(a, &ctx(Vec2::new(0.5, 0.9))), Rgb::splat(2.0));
        let b = t.push(Texture::Image(ImageTexture {
            scale: 1.0,
            invert: true,
            float: true,
            ..img
        }));
        // Float: first channel only; inverted: 1 - 0; negative results clamp to zero.
        assert_eq!(t.eval(b, &ctx(Vec2::new(0.5, 0.1))), Rgb::splat(1.0));
        assert_eq!(t.eval(b, &ctx(Vec2::new(0.5, 0.9))), Rgb::splat(0.0));
    }
}
