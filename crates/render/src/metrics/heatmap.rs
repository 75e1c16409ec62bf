//! False-colour error maps: per-pixel error on a log scale through viridis,
//! with a colour bar and its numeric range drawn under the image.

use super::{pixel_errors, PixelError};
use crate::image_io::{write_srgb8_png, RgbImage};
use std::path::Path;

/// Viridis at 0, 1/8, ..., 1 (matplotlib's `viridis(9)` in sRGB), linearly
/// interpolated between anchors: perceptually ordered, readable in grey.
const VIRIDIS: [[u8; 3]; 9] = [
    [0x44, 0x01, 0x54],
    [0x47, 0x2c, 0x7a],
    [0x3b, 0x51, 0x8b],
    [0x2c, 0x71, 0x8e],
    [0x21, 0x90, 0x8d],
    [0x27, 0xad, 0x81],
    [0x5c, 0xc8, 0x63],
    [0xaa, 0xdc, 0x32],
    [0xfd, 0xe7, 0x25],
];

/// Colour of `t` in [0, 1] (clamped).
pub fn viridis(t: f64) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) } * 8.0;
    let i = (t.floor() as usize).min(7);
    let f = t - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    [0, 1, 2].map(|c| (a[c] as f64 + (b[c] as f64 - a[c] as f64) * f).round() as u8)
}

/// Position of `v` on the log scale `[lo, hi]`, in [0, 1]; zero and below map to 0.
pub fn log_position(v: f64, lo: f64, hi: f64) -> f64 {
    if !(v > 0.0) {
        return 0.0;
    }
    ((v.log10() - lo.log10()) / (hi.log10() - lo.log10())).clamp(0.0, 1.0)
}

/// Default range: four decades below the largest error.
pub fn auto_range(errors: &[f64]) -> (f64, f64) {
    let hi = errors.iter().cloned().fold(0.0f64, f64::max);
    if hi > 0.0 && hi.is_finite() {
        (hi * 1e-4, hi)
    } else {
        (1e-6, 1.0)
    }
}

/// 3x5 glyphs, one row per entry, bit 2 = left column.
fn glyph(c: char) -> [u8; 5] {
    match c {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 7, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 1, 1],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        '.' => [0, 0, 0, 0, 2],
        '-' => [0, 0, 7, 0, 0],
        '+' => [0, 2, 7, 2, 0],
        'e' => [0, 2, 7, 4, 3],
        'r' => [0, 5, 6, 4, 4],
        'l' => [6, 2, 2, 2, 7],
        'a' => [0, 3, 5, 5, 3],
        'b' => [4, 6, 5, 5, 6],
        's' => [0, 3, 6, 1, 6],
        'o' => [0, 2, 5, 5, 2],
        'g' => [3, 5, 3, 1, 6],
        _ => [0; 5],
    }
}

/// An 8-bit sRGB canvas.
struct Canvas {
    w: u32,
    h: u32,
    px: Vec<u8>,
}

impl Canvas {
    fn set(&mut self, x: u32, y: u32, c: [u8; 3]) {
        if x < self.w && y < self.h {
            let i = 3 * (y * self.w + x) as usize;
            self.px[i..i + 3].copy_from_slice(&c);
        }
    }

    fn text(&mut self, x: u32, y: u32, s: &str, scale: u32) {
        for (k, ch) in s.chars().enumerate() {
            let g = glyph(ch);
            let x0 = x + k as u32 * 4 * scale;
            for (row, bits) in g.iter().enumerate() {
                for col in 0..3u32 {
                    if bits & (4 >> col) != 0 {
                        for dy in 0..scale {
                            for dx in 0..scale {
                                let (px, py) = (x0 + col * scale + dx, y + row as u32 * scale + dy);
                                self.set(px, py, [235, 235, 235]);
                            }
                        }
                    }
                }
            }
        }
    }
}

fn text_width(s: &str, scale: u32) -> u32 {
    (s.chars().count() as u32 * 4).saturating_sub(1) * scale
}

/// The heatmap of `errors` (`w * h`, row-major) on the log range `[lo, hi]`,
/// with a colour bar and the range printed under it: (width, height, sRGB bytes).
pub fn render_heatmap(
    errors: &[f64],
    w: u32,
    h: u32,
    (lo, hi): (f64, f64),
    label: &str,
) -> (u32, u32, Vec<u8>) {
    let scale = if w >= 256 { 2 } else { 1 };
    let (lo_s, hi_s) = (format!("{lo:.1e}"), format!("{hi:.1e}"));
    let label = format!("{label} log");
    let need = text_width(&lo_s, scale) + text_width(&label, scale) + text_width(&hi_s, scale);
    let cw = w.max(need + 12 * scale);
    let bar_h = 8 * scale;
    let ch = h + 3 * scale + bar_h + 2 * scale + 5 * scale + 2 * scale;
    let mut c = Canvas {
        w: cw,
        h: ch,
        px: vec![32; (cw * ch * 3) as usize],
    };
    let x_off = (cw - w) / 2;
    for y in 0..h {
        for x in 0..w {
            let e = errors[(y * w + x) as usize];
            c.set(x_off + x, y, viridis(log_position(e, lo, hi)));
        }
    }
    let (bx0, bx1) = (2 * scale, cw - 2 * scale);
    let by = h + 3 * scale;
    for x in bx0..bx1 {
        let col = viridis((x - bx0) as f64 / (bx1 - bx0 - 1).max(1) as f64);
        for y in by..by + bar_h {
            c.set(x, y, col);
        }
    }
    let ty = by + bar_h + 2 * scale;
    c.text(bx0, ty, &lo_s, scale);
    c.text((cw - text_width(&label, scale)) / 2, ty, &label, scale);
    c.text(bx1 - text_width(&hi_s, scale), ty, &hi_s, scale);
    (cw, ch, c.px)
}

/// Writes the error heatmap of `test` against `reference`; `range` None: [`auto_range`].
/// Returns the range used.
pub fn write_heatmap(
    path: &Path,
    test: &RgbImage,
    reference: &RgbImage,
    kind: PixelError,
    range: Option<(f64, f64)>,
) -> Result<(f64, f64), String> {
    let e = pixel_errors(test, reference, kind)?;
    let range = range.unwrap_or_else(|| auto_range(&e));
    let (w, h, px) = render_heatmap(&e, test.width, test.height, range, kind.label());
    write_srgb8_png(path, w, h, &px).map_err(|e| e.to_string())?;
    Ok(range)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_ends_and_monotone_lightness() {
        assert_eq!(viridis(0.0), [0x44, 0x01, 0x54]);
        assert_eq!(viridis(1.0), [0xfd, 0xe7, 0x25]);
        assert_eq!(viridis(0.5), [0x21, 0x90, 0x8d]);
        assert_eq!(viridis(-3.0), viridis(0.0));
        // Lightness (Rec. 709 luma of sRGB values) rises along the map.
        let luma = |c: [u8; 3]| 0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64;
        for i in 0..100 {
            assert!(luma(viridis((i + 1) as f64 / 100.0)) >= luma(viridis(i as f64 / 100.0)));
        }
    }

    #[test]
    fn log_scale_positions() {
        assert_eq!(log_position(1e-3, 1e-4, 1e0), 0.25);
        assert_eq!(log_position(1e-2, 1e-4, 1e0), 0.5);
        assert_eq!(log_position(0.0, 1e-4, 1e0), 0.0);
        assert_eq!(log_position(1e3, 1e-4, 1e0), 1.0);
        assert_eq!(auto_range(&[0.0, 2.0, 1.0]), (2e-4, 2.0));
    }

    #[test]
    fn heatmap_has_bar_and_image_pixels() {
        let e = vec![1e-4, 1e-2, 1.0, 0.0];
        let (w, h, px) = render_heatmap(&e, 2, 2, (1e-4, 1.0), "relse");
        assert!(w >= 2 && h > 2 + 8);
        assert_eq!(px.len(), (w * h * 3) as usize);
        let x_off = (w - 2) / 2;
        let at = |x: u32, y: u32| {
            let i = 3 * (y * w + x) as usize;
            [px[i], px[i + 1], px[i + 2]]
        };
        assert_eq!(at(x_off, 0), viridis(0.0));
        assert_eq!(at(x_off + 1, 0), viridis(0.5));
        assert_eq!(at(x_off, 1), viridis(1.0));
        // The bar runs from the low to the high colour.
        assert_eq!(at(2, 2 + 3), viridis(0.0));
        assert_eq!(at(w - 3, 2 + 3), viridis(1.0));
    }
}
