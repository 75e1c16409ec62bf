//! Fixed-point sums for the film. A sample enters as an integer number of
//! units (2^-64 for values, 2^-48 for squares), rounded once, by itself,
//! to the nearest unit; from then on only integers are added, and integer
//! addition (wrapping, in 128 bits) is associative and commutative. So a
//! pixel's sums do not depend on how its samples were grouped: passes
//! rendered in separate processes or on other machines and merged give
//! the same bits as one render.
//!
//! Range: a value's units are exact from about 2^-40 up (every `f32`
//! sample of that size and above is held without rounding; below, the
//! absolute error is at most 2^-65) and one sample may reach 2^62 (values
//! beyond are held at that bound, squares beyond 2^78 likewise). A pixel's
//! sum wraps only past 2^63 in value, far beyond any radiance.

/// Fractional bits of value sums.
pub const SUM_BITS: i32 = 64;
/// Fractional bits of square sums.
pub const SQUARE_BITS: i32 = 48;

/// `v` in units of 2^-64, rounded to the nearest, held within ±2^126.
#[inline]
pub fn sum_units(v: f64) -> i128 {
    to_units(v, SUM_BITS)
}

/// `q` in units of 2^-48, rounded to the nearest, held within ±2^126.
#[inline]
pub fn square_units(q: f64) -> i128 {
    to_units(q, SQUARE_BITS)
}

/// A value sum back as a number (rounded to the nearest `f64`).
#[inline]
pub fn sum_value(s: i128) -> f64 {
    s as f64 * (-SUM_BITS as f64).exp2()
}

/// A square sum back as a number.
#[inline]
pub fn square_value(s: i128) -> f64 {
    s as f64 * (-SQUARE_BITS as f64).exp2()
}

/// `v * 2^bits` rounded to the nearest integer (halves away from zero),
/// held within ±2^126; NaN gives 0 (the driver never passes one).
#[inline]
fn to_units(v: f64, bits: i32) -> i128 {
    let b = v.to_bits();
    let exp = ((b >> 52) & 0x7ff) as i32;
    if exp == 0 || exp == 0x7ff && b & ((1 << 52) - 1) != 0 {
        // Zero, subnormals (below 2^-1022) and NaN.
        return 0;
    }
    // |v| = mant * 2^(exp - 1075), mant < 2^53.
    let mant = ((b & ((1 << 52) - 1)) | (1 << 52)) as i128;
    let shift = exp - 1075 + bits;
    let mag = if shift > 73 {
        // Beyond 2^126 units (an infinity too): held there.
        1 << 126
    } else if shift >= 0 {
        mant << shift
    } else if shift >= -53 {
        ((mant >> (-shift - 1)) + 1) >> 1
    } else {
        0
    };
    if b >> 63 == 1 {
        -mag
    } else {
        mag
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_are_exact_where_they_can_be_and_round_to_nearest_below() {
        for v in [1.0f32, 0.1, 3.75e-7, 12345.678, 1e-12, 2.5e9] {
            let u = sum_units(v as f64);
            assert_eq!(sum_value(u), v as f64, "{v}");
            assert_eq!(sum_units(-(v as f64)), -u);
        }
        assert_eq!(sum_units(0.0), 0);
        assert_eq!(sum_units(-0.0), 0);
        assert_eq!(sum_units(f64::NAN), 0);
        // Half a unit rounds away from zero, less than half to zero.
        assert_eq!(sum_units(2f64.powi(-65)), 1);
        assert_eq!(sum_units(2f64.powi(-66)), 0);
        assert_eq!(sum_units(3.0 * 2f64.powi(-65)), 2);
        // Squares: 2^-48 units.
        assert_eq!(square_units(1.5), 3 << 47);
        // Huge values are held at the bound instead of overflowing.
        assert_eq!(sum_units(1e30), sum_units(f64::INFINITY));
        assert!(sum_units(1e30) > 0 && sum_units(-1e30) < 0);
    }

    #[test]
    fn sums_do_not_depend_on_grouping() {
        let vals: Vec<f64> = (0..1000)
            .map(|i| ((i * 7919 % 1000) as f64 * 0.37).sin().abs() * 10f64.powi(i % 9 - 4))
            .collect();
        let all = vals
            .iter()
            .fold(0i128, |a, v| a.wrapping_add(sum_units(*v)));
        for split in [1, 17, 500, 999] {
            let (a, b) = vals.split_at(split);
            let sa = a.iter().fold(0i128, |s, v| s.wrapping_add(sum_units(*v)));
            let sb = b
                .iter()
                .rev()
                .fold(0i128, |s, v| s.wrapping_add(sum_units(*v)));
            assert_eq!(sb.wrapping_add(sa), all);
        }
        let mean = sum_value(all) / 1000.0;
        let direct = vals.iter().sum::<f64>() / 1000.0;
        assert!((mean / direct - 1.0).abs() < 1e-14);
    }
}
