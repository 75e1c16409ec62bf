//! Linear RGB (sRGB / Rec.709 primaries) radiometric quantities.

use std::ops::{Add, AddAssign, Div, DivAssign, Index, Mul, MulAssign, Sub};

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgb {
    pub r: f32,
    pub g: f32,
    pub b: f32,
}

impl Rgb {
    pub const BLACK: Rgb = Rgb::splat(0.0);
    pub const WHITE: Rgb = Rgb::splat(1.0);

    #[inline]
    pub const fn new(r: f32, g: f32, b: f32) -> Self {
        Rgb { r, g, b }
    }
    #[inline]
    pub const fn splat(v: f32) -> Self {
        Rgb { r: v, g: v, b: v }
    }
    pub fn from_slice(v: &[f32]) -> Self {
        Rgb::new(v[0], v[1], v[2])
    }
    /// Luminance (Y of CIE XYZ) for linear sRGB primaries.
    #[inline]
    pub fn luminance(self) -> f32 {
        0.212_671 * self.r + 0.715_160 * self.g + 0.072_169 * self.b
    }
    #[inline]
    pub fn max_component(self) -> f32 {
        self.r.max(self.g).max(self.b)
    }
    #[inline]
    pub fn min_component(self) -> f32 {
        self.r.min(self.g).min(self.b)
    }
    #[inline]
    pub fn average(self) -> f32 {
        (self.r + self.g + self.b) / 3.0
    }
    #[inline]
    pub fn is_black(self) -> bool {
        self.r == 0.0 && self.g == 0.0 && self.b == 0.0
    }
    #[inline]
    pub fn is_finite(self) -> bool {
        self.r.is_finite() && self.g.is_finite() && self.b.is_finite()
    }
    #[inline]
    pub fn map(self, f: impl Fn(f32) -> f32) -> Self {
        Rgb::new(f(self.r), f(self.g), f(self.b))
    }
    #[inline]
    pub fn sqrt(self) -> Self {
        self.map(|v| v.max(0.0).sqrt())
    }
    #[inline]
    pub fn to_array(self) -> [f32; 3] {
        [self.r, self.g, self.b]
    }
}

impl Index<usize> for Rgb {
    type Output = f32;
    fn index(&self, i: usize) -> &f32 {
        match i {
            0 => &self.r,
            1 => &self.g,
            _ => &self.b,
        }
    }
}

macro_rules! rgb_binop {
    ($tr:ident, $f:ident, $tra:ident, $fa:ident, $op:tt) => {
        impl $tr for Rgb {
            type Output = Rgb;
            #[inline]
            fn $f(self, o: Rgb) -> Rgb {
                Rgb::new(self.r $op o.r, self.g $op o.g, self.b $op o.b)
            }
        }
        impl $tr<f32> for Rgb {
            type Output = Rgb;
            #[inline]
            fn $f(self, s: f32) -> Rgb {
                Rgb::new(self.r $op s, self.g $op s, self.b $op s)
            }
        }
        impl $tra for Rgb {
            #[inline]
            fn $fa(&mut self, o: Rgb) {
                *self = *self $op o;
            }
        }
        impl $tra<f32> for Rgb {
            #[inline]
            fn $fa(&mut self, s: f32) {
                *self = *self $op s;
            }
        }
    };
}
rgb_binop!(Add, add, AddAssign, add_assign, +);
rgb_binop!(Mul, mul, MulAssign, mul_assign, *);
rgb_binop!(Div, div, DivAssign, div_assign, /);

impl Sub for Rgb {
    type Output = Rgb;
    #[inline]
    fn sub(self, o: Rgb) -> Rgb {
        Rgb::new(self.r - o.r, self.g - o.g, self.b - o.b)
    }
}

impl Mul<Rgb> for f32 {
    type Output = Rgb;
    #[inline]
    fn mul(self, c: Rgb) -> Rgb {
        c * self
    }
}

impl std::iter::Sum for Rgb {
    fn sum<I: Iterator<Item = Rgb>>(iter: I) -> Rgb {
        iter.fold(Rgb::BLACK, |a, b| a + b)
    }
}

/// sRGB transfer function (linear to display-encoded), for 8-bit output.
pub fn linear_to_srgb(v: f32) -> f32 {
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// Inverse sRGB transfer function (display-encoded to linear).
pub fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luminance_of_white_is_one() {
        assert!((Rgb::WHITE.luminance() - 1.0).abs() < 1e-5);
    }

    #[test]
    fn srgb_round_trip() {
        for i in 0..=100 {
            let v = i as f32 / 100.0;
            assert!((srgb_to_linear(linear_to_srgb(v)) - v).abs() < 1e-5);
        }
    }
}
