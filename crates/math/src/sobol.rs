//! Owen-scrambled Sobol points (Burley 2020) as `sobol_burley` defines them,
//! bit for bit, with the Sobol matrix product read from tables instead of
//! walking the index's bits.
//!
//! `sobol_burley::sample` XORs one direction vector per set bit of the
//! shuffled 16-bit index: about eight dependent steps per dimension, the
//! largest part of a sampler call. Here the index is cut into four nibbles
//! and each nibble's XOR of vectors is precomputed (16 entries per nibble
//! position per set of four dimensions: 64 KiB for the 256 dimensions), so
//! the product is four independent loads. The scrambles are the crate's own
//! `parts` functions.

use sobol_burley::parts::{hash, owen_scramble_rev, sobol_rev, u32_to_f32_norm};
use sobol_burley::NUM_DIMENSIONS;
use std::sync::OnceLock;

const SETS: usize = NUM_DIMENSIONS as usize / 4;

/// `[set][nibble position][nibble value][dimension in the set]`: the Sobol
/// product of a reversed index whose only set bits are that nibble.
pub struct SobolTables {
    xor: Vec<[[[u32; 4]; 16]; 4]>,
}

impl std::fmt::Debug for SobolTables {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SobolTables({} dimensions)", 4 * self.xor.len())
    }
}

impl SobolTables {
    /// The tables, built on first use.
    pub fn get() -> &'static SobolTables {
        static TABLES: OnceLock<SobolTables> = OnceLock::new();
        TABLES.get_or_init(SobolTables::build)
    }

    fn build() -> SobolTables {
        let mut xor = vec![[[[0u32; 4]; 16]; 4]; SETS];
        for (set, per_set) in xor.iter_mut().enumerate() {
            for (q, per_nibble) in per_set.iter_mut().enumerate() {
                for (nib, lanes) in per_nibble.iter_mut().enumerate() {
                    for (sub, v) in lanes.iter_mut().enumerate() {
                        let index_rev = (nib as u32) << (28 - 4 * q);
                        *v = sobol_rev(index_rev, (4 * set + sub) as u32);
                    }
                }
            }
        }
        SobolTables { xor }
    }

    /// The Sobol product (unscrambled, bit-reversed) of dimension set `set`
    /// at the reversed shuffled index `rev` (its top 16 bits).
    #[inline(always)]
    fn product(&self, rev: u32, set: u32) -> [u32; 4] {
        let t = &self.xor[set as usize];
        let a = t[0][(rev >> 28) as usize & 15];
        let b = t[1][(rev >> 24) as usize & 15];
        let c = t[2][(rev >> 20) as usize & 15];
        let d = t[3][(rev >> 16) as usize & 15];
        std::array::from_fn(|i| a[i] ^ b[i] ^ c[i] ^ d[i])
    }

    /// `sobol_burley::sample(index, d, seed)`, given `index.reverse_bits()`.
    #[inline]
    pub fn sample(&self, index_rev: u32, d: u32, seed: u32) -> f32 {
        let rev = shuffled_rev(index_rev, seed);
        finish(self.product(rev, d >> 2)[d as usize & 3], d, seed)
    }

    /// `(sample(index_rev, d, seed), sample(index_rev, d + 1, seed))`: one
    /// shuffled index for both.
    #[inline]
    pub fn pair(&self, index_rev: u32, d: u32, seed: u32) -> (f32, f32) {
        let rev = shuffled_rev(index_rev, seed);
        let p = self.product(rev, d >> 2);
        let j = d as usize & 3;
        let y = if j == 3 {
            self.product(rev, (d + 1) >> 2)[0]
        } else {
            p[j + 1]
        };
        (finish(p[j], d, seed), finish(y, d + 1, seed))
    }
}

/// The reversed sample index, Owen-shuffled by the seed.
#[inline(always)]
fn shuffled_rev(index_rev: u32, seed: u32) -> u32 {
    debug_assert!(index_rev & 0xffff == 0, "indices stop at 2^16");
    owen_scramble_rev(index_rev, hash(seed ^ 0x79c6_8e4a))
}

/// Owen-scrambles dimension `d`'s product and maps it to [0, 1).
#[inline(always)]
fn finish(sobol: u32, d: u32, seed: u32) -> f32 {
    const LANE: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];
    let scramble = seed.wrapping_mul(0x9c8f_2d3b) ^ (d >> 2) ^ LANE[d as usize & 3];
    u32_to_f32_norm(owen_scramble_rev(sobol, hash(scramble)).reverse_bits())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_give_the_library_samples_bit_for_bit() {
        let t = SobolTables::get();
        let mut seeds = crate::Pcg32::new(3, 4);
        for d in 0..NUM_DIMENSIONS {
            for k in 0..24 {
                // all the low indices, then random ones up to 2^16
                let index = if k < 16 { k } else { seeds.next_u32() >> 16 };
                let seed = seeds.next_u32();
                let want = sobol_burley::sample(index, d, seed).to_bits();
                let rev = index.reverse_bits();
                assert_eq!(t.sample(rev, d, seed).to_bits(), want, "d {d} i {index}");
                if d + 1 < NUM_DIMENSIONS {
                    let (x, y) = t.pair(rev, d, seed);
                    assert_eq!(x.to_bits(), want);
                    let want_y = sobol_burley::sample(index, d + 1, seed).to_bits();
                    assert_eq!(y.to_bits(), want_y, "d {} i {index}", d + 1);
                }
            }
        }
        assert_eq!(
            t.sample(65_535u32.reverse_bits(), 255, u32::MAX).to_bits(),
            { sobol_burley::sample(65_535, 255, u32::MAX).to_bits() }
        );
    }
}
