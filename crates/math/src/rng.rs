//! PCG32 random number generator (O'Neill 2014) and hashing for seeds.

/// PCG-XSH-RR with 64-bit state and selectable stream.
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

const MULT: u64 = 0x5851_f42d_4c95_7f2d;

impl Pcg32 {
    pub fn new(seed: u64, stream: u64) -> Pcg32 {
        let mut r = Pcg32 {
            state: 0,
            inc: (stream << 1) | 1,
        };
        r.next_u32();
        r.state = r.state.wrapping_add(seed);
        r.next_u32();
        r
    }

    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(MULT).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform in [0, 1).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }

    /// Uniform integer in [0, n).
    #[inline]
    pub fn next_below(&mut self, n: u32) -> u32 {
        ((self.next_u32() as u64 * n as u64) >> 32) as u32
    }

    /// Jump ahead by `delta` steps in O(log delta) (Brown 1994).
    pub fn advance(&mut self, delta: u64) {
        let (mut cur_mult, mut cur_plus) = (MULT, self.inc);
        let (mut acc_mult, mut acc_plus) = (1u64, 0u64);
        let mut d = delta;
        while d > 0 {
            if d & 1 == 1 {
                acc_mult = acc_mult.wrapping_mul(cur_mult);
                acc_plus = acc_plus.wrapping_mul(cur_mult).wrapping_add(cur_plus);
            }
            cur_plus = cur_mult.wrapping_add(1).wrapping_mul(cur_plus);
            cur_mult = cur_mult.wrapping_mul(cur_mult);
            d >>= 1;
        }
        self.state = acc_mult.wrapping_mul(self.state).wrapping_add(acc_plus);
    }
}

/// 64-bit mix (splitmix64 finaliser), for deriving seeds from indices.
#[inline]
pub fn mix64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// Hash of several integers.
pub fn hash(values: &[u64]) -> u64 {
    values
        .iter()
        .fold(0x243f_6a88_85a3_08d3, |h, &v| mix64(h ^ v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn advance_matches_stepping() {
        let mut a = Pcg32::new(42, 54);
        let mut b = a.clone();
        for _ in 0..1000 {
            a.next_u32();
        }
        b.advance(1000);
        assert_eq!(a.next_u32(), b.next_u32());
    }

    #[test]
    fn floats_in_unit_interval_with_right_mean() {
        let mut r = Pcg32::new(1, 2);
        let n = 100_000;
        let mut s = 0.0f64;
        for _ in 0..n {
            let v = r.next_f32();
            assert!((0.0..1.0).contains(&v));
            s += v as f64;
        }
        assert!((s / n as f64 - 0.5).abs() < 0.005);
    }
}
