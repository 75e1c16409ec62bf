//! Image pyramids and their lookups (pbrt-v4's MIPMap): point, bilinear and
//! trilinear filtering with repeat, black and clamp wrap modes.

use lumis_math::{Rgb, Vec2};

/// What a lookup outside [0, 1]^2 reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WrapMode {
    Repeat,
    Black,
    Clamp,
}

impl WrapMode {
    pub fn parse(s: &str) -> Option<WrapMode> {
        Some(match s {
            "repeat" => WrapMode::Repeat,
            "black" => WrapMode::Black,
            "clamp" => WrapMode::Clamp,
            _ => return None,
        })
    }
}

/// pbrt-v4's `filter` parameter (EWA is read as trilinear by the loader).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterKind {
    /// Nearest texel of the mip level chosen by the footprint.
    Point,
    /// Bilinear interpolation in the mip level chosen by the footprint
    /// (rounded down), as pbrt-v4's `bilinear`.
    Bilinear,
    /// Bilinear in the two neighbouring levels, blended linearly.
    Trilinear,
}

/// One level: RGB texels in rows, row 0 at the top of the image.
#[derive(Clone, Debug)]
pub struct Level {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<Rgb>,
}

impl Level {
    /// Texel `(x, y)` with the wrap mode applied.
    #[inline]
    pub fn texel(&self, x: i64, y: i64, wrap: WrapMode) -> Rgb {
        let (w, h) = (self.width as i64, self.height as i64);
        let (x, y) = match wrap {
            WrapMode::Repeat => (x.rem_euclid(w), y.rem_euclid(h)),
            WrapMode::Clamp => (x.clamp(0, w - 1), y.clamp(0, h - 1)),
            WrapMode::Black => {
                if x < 0 || y < 0 || x >= w || y >= h {
                    return Rgb::BLACK;
                }
                (x, y)
            }
        };
        self.texels[(y * w + x) as usize]
    }

    /// Bilinear interpolation at `st` in [0, 1]^2 (texel centres at half-integers).
    pub fn bilerp(&self, st: Vec2, wrap: WrapMode) -> Rgb {
        let x = st.x * self.width as f32 - 0.5;
        let y = st.y * self.height as f32 - 0.5;
        let (xf, yf) = (x.floor(), y.floor());
        let (dx, dy) = (x - xf, y - yf);
        let (xi, yi) = (xf as i64, yf as i64);
        self.texel(xi, yi, wrap) * ((1.0 - dx) * (1.0 - dy))
            + self.texel(xi + 1, yi, wrap) * (dx * (1.0 - dy))
            + self.texel(xi, yi + 1, wrap) * ((1.0 - dx) * dy)
            + self.texel(xi + 1, yi + 1, wrap) * (dx * dy)
    }

    /// Half resolution (rounded up), each texel the mean of its 2x2 parents
    /// (edge texels repeated for odd sizes).
    fn downsample(&self) -> Level {
        let (w, h) = (
            self.width.div_ceil(2).max(1),
            self.height.div_ceil(2).max(1),
        );
        let mut texels = Vec::with_capacity((w * h) as usize);
        for y in 0..h as i64 {
            for x in 0..w as i64 {
                let c = WrapMode::Clamp;
                let sum = self.texel(2 * x, 2 * y, c)
                    + self.texel(2 * x + 1, 2 * y, c)
                    + self.texel(2 * x, 2 * y + 1, c)
                    + self.texel(2 * x + 1, 2 * y + 1, c);
                texels.push(sum * 0.25);
            }
        }
        Level {
            width: w,
            height: h,
            texels,
        }
    }
}

/// A pyramid of levels, level 0 the full image, the last 1x1.
#[derive(Clone, Debug)]
pub struct MipMap {
    pub levels: Vec<Level>,
}

impl MipMap {
    /// Builds the pyramid. Sizes halve (rounded up) down to 1x1, so a
    /// power-of-two image has pbrt-v4's `1 + log2(max(w, h))` levels; other
    /// sizes are not resampled to a power of two first (pbrt-v4 does).
    pub fn new(base: Level) -> MipMap {
        let mut levels = vec![base];
        loop {
            let l = levels.last().unwrap();
            if l.width == 1 && l.height == 1 {
                break;
            }
            let next = l.downsample();
            levels.push(next);
        }
        MipMap { levels }
    }

    /// The (fractional) level pbrt-v4 reads for a footprint with the given
    /// st derivatives: `levels - 1 + log2(2 max |d|)`.
    pub fn level_for(&self, dst0: Vec2, dst1: Vec2) -> f32 {
        let width = 2.0
            * dst0
                .x
                .abs()
                .max(dst0.y.abs())
                .max(dst1.x.abs())
                .max(dst1.y.abs());
        (self.levels.len() - 1) as f32 + width.max(1e-8).log2()
    }

    /// Filtered lookup at `st` with footprint derivatives `dst0 = (dsdx, dtdx)`
    /// and `dst1 = (dsdy, dtdy)`.
    pub fn filter(
        &self,
        st: Vec2,
        dst0: Vec2,
        dst1: Vec2,
        filter: FilterKind,
        wrap: WrapMode,
    ) -> Rgb {
        let n = self.levels.len();
        let level = self.level_for(dst0, dst1);
        if level >= (n - 1) as f32 {
            return self.levels[n - 1].texel(0, 0, wrap);
        }
        let i = level.max(0.0).floor() as usize;
        match filter {
            FilterKind::Point => {
                let l = &self.levels[i];
                let x = (st.x * l.width as f32 - 0.5).round() as i64;
                let y = (st.y * l.height as f32 - 0.5).round() as i64;
                l.texel(x, y, wrap)
            }
            FilterKind::Bilinear => self.levels[i].bilerp(st, wrap),
            FilterKind::Trilinear => {
                if level <= 0.0 {
                    return self.levels[0].bilerp(st, wrap);
                }
                let d = level - i as f32;
                self.levels[i].bilerp(st, wrap) * (1.0 - d)
                    + self.levels[i + 1].bilerp(st, wrap) * d
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2x2 image: a b / c d (row 0 on top).
    fn two_by_two() -> Level {
        Level {
            width: 2,
            height: 2,
            texels: vec![
                Rgb::splat(1.0),
                Rgb::splat(2.0),
                Rgb::splat(3.0),
                Rgb::splat(4.0),
            ],
        }
    }

    #[test]
    fn bilerp_by_hand() {
        let l = two_by_two();
        // Texel centres are exact.
        assert_eq!(l.bilerp(Vec2::new(0.25, 0.25), WrapMode::Clamp).r, 1.0);
        assert_eq!(l.bilerp(Vec2::new(0.75, 0.75), WrapMode::Clamp).r, 4.0);
        // Centre of the image: mean of the four.
        assert!((l.bilerp(Vec2::new(0.5, 0.5), WrapMode::Clamp).r - 2.5).abs() < 1e-6);
        // A quarter of the way from texel a to texel b: 1 + 0.5 * (2 - 1) ... x = 0.5*2-0.5 = 0.5.
        let v = l.bilerp(Vec2::new(0.5, 0.25), WrapMode::Clamp).r;
        assert!((v - 1.5).abs() < 1e-6);
        // x = 0.375 * 2 - 0.5 = 0.25: 0.75 a + 0.25 b.
        let v = l.bilerp(Vec2::new(0.375, 0.25), WrapMode::Clamp).r;
        assert!((v - 1.25).abs() < 1e-6);
    }

    #[test]
    fn wrap_modes() {
        let l = two_by_two();
        // At s = 0 (x = -0.5): half of the left column and half of what lies beyond it.
        let st = Vec2::new(0.0, 0.25);
        assert!((l.bilerp(st, WrapMode::Clamp).r - 1.0).abs() < 1e-6);
        assert!((l.bilerp(st, WrapMode::Repeat).r - 1.5).abs() < 1e-6);
        assert!((l.bilerp(st, WrapMode::Black).r - 0.5).abs() < 1e-6);
        assert_eq!(l.texel(-1, 0, WrapMode::Repeat).r, 2.0);
        assert_eq!(l.texel(5, 3, WrapMode::Repeat).r, 4.0);
        assert_eq!(l.texel(-1, 0, WrapMode::Black).r, 0.0);
        assert_eq!(l.texel(-7, 9, WrapMode::Clamp).r, 3.0);
    }

    #[test]
    fn pyramid_and_level_selection() {
        let texels = (0..16).map(|i| Rgb::splat(i as f32)).collect();
        let m = MipMap::new(Level {
            width: 4,
            height: 4,
            texels,
        });
        assert_eq!(m.levels.len(), 3);
        assert_eq!((m.levels[1].width, m.levels[1].height), (2, 2));
        // Top-left 2x2 block of the 4x4: 0 1 4 5.
        assert_eq!(m.levels[1].texels[0].r, 2.5);
        assert_eq!(m.levels[2].texels[0].r, 7.5);
        // A footprint of one texel of level 0 (1/4 of the image): width 2 * 1/4 = 1/2,
        // level 2 + log2(1/2) = 1; a tiny footprint: negative (clamped to 0).
        let d = Vec2::new(0.125, 0.0);
        assert!((m.level_for(d, Vec2::ZERO) - 0.0).abs() < 1e-6);
        assert!((m.level_for(Vec2::new(0.25, 0.0), Vec2::ZERO) - 1.0).abs() < 1e-6);
        assert!(m.level_for(Vec2::new(1e-4, 0.0), Vec2::ZERO) < 0.0);
        // Trilinear halfway between level 0 and 1 at the centre of texel (0,0) of level 1.
        let st = Vec2::new(0.25, 0.25);
        let half = Vec2::new(0.125 * 2f32.sqrt(), 0.0); // level 0.5
        let l0 = m.levels[0].bilerp(st, WrapMode::Clamp).r;
        let l1 = m.levels[1].bilerp(st, WrapMode::Clamp).r;
        let tri = m
            .filter(st, half, Vec2::ZERO, FilterKind::Trilinear, WrapMode::Clamp)
            .r;
        assert!((tri - 0.5 * (l0 + l1)).abs() < 1e-5, "{tri} {l0} {l1}");
        // Bilinear reads the floor level only; a huge footprint reads the 1x1 level.
        let bil = m
            .filter(st, half, Vec2::ZERO, FilterKind::Bilinear, WrapMode::Clamp)
            .r;
        assert_eq!(bil, l0);
        let big = Vec2::new(10.0, 0.0);
        assert_eq!(
            m.filter(st, big, big, FilterKind::Trilinear, WrapMode::Clamp)
                .r,
            7.5
        );
        // Point: nearest texel of level 0.
        let p = m
            .filter(
                Vec2::new(0.6, 0.1),
                Vec2::ZERO,
                Vec2::ZERO,
                FilterKind::Point,
                WrapMode::Clamp,
            )
            .r;
        assert_eq!(p, 2.0);
    }
}
