//! Image error metrics against a reference (over all channels of a region).

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
    for y in r.y0..r.y1 {
        for x in r.x0..r.x1 {
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
    let pixels = (r.x1 - r.x0) as u64 * (r.y1 - r.y0) as u64;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn img(v: &[f32]) -> RgbImage {
        RgbImage::new(2, 1, v.to_vec())
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
