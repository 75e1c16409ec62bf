//! Image error metrics against a reference (over all channels of a region).

pub mod heatmap;

use crate::image_io::RgbImage;

/// A pixel region `[x0, x1) x [y0, y1)`: the film's pixel bounds.
pub use crate::film::PixelBounds as Region;

#[derive(Clone, Debug, PartialEq)]
pub struct Metrics {
    pub mse: f64,
    pub rmse: f64,
    /// Mean of `(t - r)^2 / (r^2 + 0.01)` (r: channel value of the reference).
    pub rel_mse: f64,
    pub mae: f64,
    pub mean_test: [f64; 3],
    pub mean_ref: [f64; 3],
    pub pixels: u64,
}

impl Metrics {
    /// Ratio of means per channel (test / reference).
    pub fn ratio(&self) -> [f64; 3] {
        [0, 1, 2].map(|c| self.mean_test[c] / self.mean_ref[c])
    }
}

/// Compares `test` with `reference` over `region` (whole image if None).
/// Errors: different sizes, an empty region, or a non-finite reference pixel.
pub fn compare(
    test: &RgbImage,
    reference: &RgbImage,
    region: Option<Region>,
) -> Result<Metrics, String> {
    compare_where(test, reference, region, |_, _| true)
}

/// Whether pixel (x, y) of `img` and its eight neighbours are all non-zero
/// (in some channel), and none is on the border: where a light tracer's
/// image is a full estimate (it is black where only a specular bounce
/// shows the camera, and its box-filtered edges mix both).
pub fn lit_interior(img: &RgbImage, x: u32, y: u32) -> bool {
    if x == 0 || y == 0 || x + 1 >= img.width || y + 1 >= img.height {
        return false;
    }
    (y - 1..=y + 1).all(|yy| (x - 1..=x + 1).all(|xx| img.pixel(xx, yy).iter().any(|&v| v != 0.0)))
}

/// [`compare`] over the pixels of `region` for which `keep(x, y)` holds.
/// Errors also when it keeps none.
pub fn compare_where(
    test: &RgbImage,
    reference: &RgbImage,
    region: Option<Region>,
    keep: impl Fn(u32, u32) -> bool,
) -> Result<Metrics, String> {
    if (test.width, test.height) != (reference.width, reference.height) {
        return Err(format!(
            "image sizes differ: test {}x{}, reference {}x{}",
            test.width, test.height, reference.width, reference.height
        ));
    }
    let r = region.unwrap_or(Region {
        x0: 0,
        x1: test.width,
        y0: 0,
        y1: test.height,
    });
    if r.x1 > test.width || r.y1 > test.height || r.x0 >= r.x1 || r.y0 >= r.y1 {
        return Err(format!(
            "region {}..{} x {}..{} is empty or outside the {}x{} image",
            r.x0, r.x1, r.y0, r.y1, test.width, test.height
        ));
    }
    let (mut se, mut rel, mut ae) = (0.0f64, 0.0f64, 0.0f64);
    let (mut mt, mut mr) = ([0.0f64; 3], [0.0f64; 3]);
    let mut pixels = 0u64;
    for y in r.y0..r.y1 {
        for x in r.x0..r.x1 {
            if !keep(x, y) {
                continue;
            }
            pixels += 1;
            let (t, f) = (test.pixel(x, y), reference.pixel(x, y));
            for c in 0..3 {
                let (tv, rv) = (t[c] as f64, f[c] as f64);
                if !rv.is_finite() {
                    return Err(format!("reference pixel ({x}, {y}) is not finite ({rv})"));
                }
                if !tv.is_finite() {
                    return Err(format!("test pixel ({x}, {y}) is not finite ({tv})"));
                }
                let d = tv - rv;
                se += d * d;
                rel += d * d / (rv * rv + 0.01);
                ae += d.abs();
                mt[c] += tv;
                mr[c] += rv;
            }
        }
    }
    if pixels == 0 {
        return Err("no pixel to compare".into());
    }
    let n = pixels as f64 * 3.0;
    Ok(Metrics {
        mse: se / n,
        rmse: (se / n).sqrt(),
        rel_mse: rel / n,
        mae: ae / n,
        mean_test: mt.map(|v| v / pixels as f64),
        mean_ref: mr.map(|v| v / pixels as f64),
        pixels,
    })
}

/// Which per-pixel error a heatmap shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelError {
    /// Mean over channels of `(t - r)^2 / (r^2 + 0.01)`: relMSE per pixel.
    Relative,
    /// Mean over channels of `|t - r|`: MAE per pixel.
    Absolute,
}

impl PixelError {
    pub fn from_name(s: &str) -> Option<PixelError> {
        match s {
            "rel" | "relative" => Some(PixelError::Relative),
            "abs" | "absolute" => Some(PixelError::Absolute),
            _ => None,
        }
    }

    /// Short label for a colour bar.
    pub fn label(self) -> &'static str {
        match self {
            PixelError::Relative => "relse",
            PixelError::Absolute => "abs",
        }
    }
}

/// Per-pixel error of `test` against `reference` (row-major, whole image):
/// the per-pixel terms whose mean over a region is `rel_mse` or `mae`.
/// Errors as [`compare`]: size mismatch or a non-finite pixel.
pub fn pixel_errors(
    test: &RgbImage,
    reference: &RgbImage,
    kind: PixelError,
) -> Result<Vec<f64>, String> {
    compare(test, reference, None)?;
    Ok(test
        .data
        .chunks_exact(3)
        .zip(reference.data.chunks_exact(3))
        .map(|(t, r)| {
            let mut e = 0.0;
            for c in 0..3 {
                let (tv, rv) = (t[c] as f64, r[c] as f64);
                e += match kind {
                    PixelError::Relative => (tv - rv) * (tv - rv) / (rv * rv + 0.01),
                    PixelError::Absolute => (tv - rv).abs(),
                };
            }
            e / 3.0
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn img(v: &[f32]) -> RgbImage {
        RgbImage::new(2, 1, v.to_vec())
    }

    #[test]
    fn lit_keeps_interior_pixels_whose_neighbourhood_is_not_black() {
        // 5x4, one black pixel at (1, 2): of the interior (1..4 x 1..3),
        // only column 3 is out of its reach.
        let mut v = vec![1.0f32; 5 * 4 * 3];
        v[(2 * 5 + 1) * 3..(2 * 5 + 1) * 3 + 3].fill(0.0);
        let t = RgbImage::new(5, 4, v);
        let kept: Vec<(u32, u32)> = (0..4)
            .flat_map(|y| (0..5).map(move |x| (x, y)))
            .filter(|&(x, y)| lit_interior(&t, x, y))
            .collect();
        assert_eq!(kept, vec![(3, 1), (3, 2)]);
        let r = RgbImage::new(5, 4, vec![0.5; 60]);
        let m = compare_where(&t, &r, None, |x, y| lit_interior(&t, x, y)).unwrap();
        assert_eq!((m.pixels, m.ratio()), (2, [2.0; 3]));
        assert!(compare_where(&t, &r, None, |_, _| false).is_err());
    }

    #[test]
    fn hand_computed_values() {
        let r = img(&[1.0, 1.0, 1.0, 0.0, 0.0, 0.0]);
        let t = img(&[2.0, 1.0, 1.0, 0.0, 0.0, 0.5]);
        let m = compare(&t, &r, None).unwrap();
        // Differences: 1, 0, 0, 0, 0, 0.5 over 6 values.
        assert!((m.mse - 1.25 / 6.0).abs() < 1e-12);
        assert!((m.rmse - (1.25f64 / 6.0).sqrt()).abs() < 1e-12);
        assert!((m.mae - 1.5 / 6.0).abs() < 1e-12);
        // relMSE: 1/(1+0.01) + 0.25/(0+0.01) over 6.
        assert!((m.rel_mse - (1.0 / 1.01 + 25.0) / 6.0).abs() < 1e-9);
        assert_eq!(m.mean_test, [1.0, 0.5, 0.75]);
        assert_eq!(m.mean_ref, [0.5, 0.5, 0.5]);
        assert_eq!(m.ratio(), [2.0, 1.0, 1.5]);
        // Region: only the first pixel.
        let m = compare(
            &t,
            &r,
            Some(Region {
                x0: 0,
                x1: 1,
                y0: 0,
                y1: 1,
            }),
        )
        .unwrap();
        assert!((m.mse - 1.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn channel_means_ratio_and_rmse_by_hand() {
        // One pixel, reference (2, 4, 0.5), test (1, 4, 1.5).
        let r = RgbImage::new(1, 1, vec![2.0, 4.0, 0.5]);
        let t = RgbImage::new(1, 1, vec![1.0, 4.0, 1.5]);
        let m = compare(&t, &r, None).unwrap();
        // Squared differences 1, 0, 1: MSE 2/3, RMSE sqrt(2/3), MAE 2/3.
        assert!((m.mse - 2.0 / 3.0).abs() < 1e-12);
        assert!((m.rmse - (2.0f64 / 3.0).sqrt()).abs() < 1e-12);
        assert!((m.mae - 2.0 / 3.0).abs() < 1e-12);
        // relMSE: 1/(4+0.01) + 0 + 1/(0.25+0.01), over 3.
        assert!((m.rel_mse - (1.0 / 4.01 + 1.0 / 0.26) / 3.0).abs() < 1e-12);
        assert_eq!(m.ratio(), [0.5, 1.0, 3.0]);
        assert_eq!(m.pixels, 1);
        // Identical images: every error is exactly zero, ratio one.
        let z = compare(&r, &r, None).unwrap();
        assert_eq!((z.mse, z.rel_mse, z.mae), (0.0, 0.0, 0.0));
        assert_eq!(z.ratio(), [1.0; 3]);
    }

    #[test]
    fn pixel_errors_by_hand_and_their_means_are_the_metrics() {
        let r = img(&[1.0, 1.0, 1.0, 0.0, 0.0, 0.0]);
        let t = img(&[2.0, 1.0, 1.0, 0.0, 0.0, 0.5]);
        let rel = pixel_errors(&t, &r, PixelError::Relative).unwrap();
        assert!((rel[0] - (1.0 / 1.01) / 3.0).abs() < 1e-12);
        assert!((rel[1] - 25.0 / 3.0).abs() < 1e-9);
        let abs = pixel_errors(&t, &r, PixelError::Absolute).unwrap();
        assert!((abs[0] - 1.0 / 3.0).abs() < 1e-12);
        assert!((abs[1] - 0.5 / 3.0).abs() < 1e-12);
        let m = compare(&t, &r, None).unwrap();
        assert!(((rel[0] + rel[1]) / 2.0 - m.rel_mse).abs() < 1e-12);
        assert!(((abs[0] + abs[1]) / 2.0 - m.mae).abs() < 1e-12);
        let bad = img(&[f32::INFINITY, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert!(pixel_errors(&t, &bad, PixelError::Absolute).is_err());
        assert_eq!(PixelError::from_name("rel"), Some(PixelError::Relative));
        assert_eq!(
            PixelError::from_name("absolute"),
            Some(PixelError::Absolute)
        );
        assert_eq!(PixelError::from_name("x"), None);
    }

    #[test]
    fn refuses_size_mismatch_and_bad_reference() {
        let a = img(&[0.0; 6]);
        let b = RgbImage::new(1, 2, vec![0.0; 6]);
        assert!(compare(&a, &b, None).unwrap_err().contains("sizes differ"));
        let nan = img(&[f32::NAN, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert!(compare(&a, &nan, None).unwrap_err().contains("not finite"));
        assert!(compare(
            &a,
            &a,
            Some(Region {
                x0: 1,
                x1: 1,
                y0: 0,
                y1: 1
            })
        )
        .is_err());
    }
}
