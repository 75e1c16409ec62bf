//! Pixel samplers. Each pixel sample is seeded from (seed, pixel, sample index)
//! alone, so images do not depend on thread count or scheduling.

use crate::rng::{hash, Pcg32};
use crate::sobol::SobolTables;
use crate::{Vec2, ONE_MINUS_EPSILON};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerKind {
    /// Independent uniform random numbers (PCG32).
    Independent,
    /// Owen-scrambled Sobol (Burley 2020), padded per dimension; falls back
    /// to independent numbers past the tables' 256 dimensions.
    Sobol,
}

#[derive(Clone, Debug)]
pub struct Sampler {
    kind: SamplerKind,
    seed: u64,
    pixel_hash: u32,
    index: u32,
    /// `index.reverse_bits()`, as the Sobol points take it.
    index_rev: u32,
    dim: u32,
    rng: Pcg32,
    sobol: &'static SobolTables,
}

impl Sampler {
    pub fn new(kind: SamplerKind, seed: u64) -> Sampler {
        Sampler {
            kind,
            seed,
            pixel_hash: 0,
            index: 0,
            index_rev: 0,
            dim: 0,
            rng: Pcg32::new(seed, 0),
            sobol: SobolTables::get(),
        }
    }

    pub fn kind(&self) -> SamplerKind {
        self.kind
    }

    /// Start sample `index` of pixel `(x, y)`.
    pub fn start_pixel_sample(&mut self, x: u32, y: u32, index: u32) {
        let h = hash(&[self.seed, x as u64, y as u64]);
        self.pixel_hash = h as u32;
        self.index = index;
        self.index_rev = index.reverse_bits();
        self.dim = 0;
        self.rng = Pcg32::new(hash(&[h, index as u64]), h >> 1);
    }

    /// Start an unstructured stream (photon paths and the like) keyed by `key`.
    pub fn start_stream(&mut self, key: u64, index: u32) {
        self.start_pixel_sample(key as u32, (key >> 32) as u32, index);
    }

    #[inline]
    pub fn get_1d(&mut self) -> f32 {
        let d = self.dim;
        self.dim += 1;
        match self.kind {
            SamplerKind::Sobol if d < sobol_burley::NUM_DIMENSIONS && self.index < (1 << 16) => {
                let seed = self.pixel_hash ^ (d.wrapping_mul(0x9e37_79b9));
                self.sobol
                    .sample(self.index_rev, d, seed)
                    .min(ONE_MINUS_EPSILON)
            }
            _ => self.rng.next_f32(),
        }
    }

    #[inline]
    pub fn get_2d(&mut self) -> Vec2 {
        match self.kind {
            SamplerKind::Sobol
                if self.dim + 1 < sobol_burley::NUM_DIMENSIONS && self.index < (1 << 16) =>
            {
                // Consecutive Sobol dimensions (0,1), (2,3), ... are well stratified in 2D
                // only when scrambled with the same seed.
                let d = self.dim;
                self.dim += 2;
                let seed = self.pixel_hash ^ (d.wrapping_mul(0x9e37_79b9));
                let (x, y) = self.sobol.pair(self.index_rev, d, seed);
                Vec2::new(x.min(ONE_MINUS_EPSILON), y.min(ONE_MINUS_EPSILON))
            }
            // Past the Sobol points' indices (photon streams beyond the
            // first 2^16): both numbers from the stream, as two `get_1d`
            // calls would give them, without their tests.
            SamplerKind::Sobol if self.index >= (1 << 16) => self.next_pair(),
            SamplerKind::Independent => self.next_pair(),
            _ => Vec2::new(self.get_1d(), self.get_1d()),
        }
    }

    #[inline(always)]
    fn next_pair(&mut self) -> Vec2 {
        self.dim += 2;
        let x = self.rng.next_f32();
        Vec2::new(x, self.rng.next_f32())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_pixel_same_numbers() {
        for kind in [SamplerKind::Independent, SamplerKind::Sobol] {
            let mut a = Sampler::new(kind, 9);
            let mut b = Sampler::new(kind, 9);
            a.start_pixel_sample(3, 4, 5);
            let _ = b.get_2d();
            b.start_pixel_sample(3, 4, 5);
            for _ in 0..300 {
                assert_eq!(a.get_1d(), b.get_1d());
            }
        }
    }

    #[test]
    fn a_pair_is_two_single_numbers() {
        // Where a pair is not one 2D Sobol point: independent numbers, Sobol
        // indices past the tables' (2^16) and dimensions across their end
        // (256), pairs starting at odd dimensions too.
        let cases = [
            (SamplerKind::Independent, 0, 0),
            (SamplerKind::Independent, 3_000_000, 0),
            (SamplerKind::Sobol, 1 << 16, 0),
            (SamplerKind::Sobol, 3_000_000, 0),
            (SamplerKind::Sobol, 7, 254),
        ];
        for (kind, index, skip) in cases {
            let (mut a, mut b) = (Sampler::new(kind, 4), Sampler::new(kind, 4));
            a.start_stream(0x1234_5678_9abc, index);
            b.start_stream(0x1234_5678_9abc, index);
            for _ in 0..skip + 1 {
                assert_eq!(a.get_1d().to_bits(), b.get_1d().to_bits());
            }
            for _ in 0..150 {
                let p = a.get_2d();
                let (x, y) = (b.get_1d(), b.get_1d());
                assert_eq!((p.x.to_bits(), p.y.to_bits()), (x.to_bits(), y.to_bits()));
            }
            assert_eq!(a.get_1d().to_bits(), b.get_1d().to_bits());
        }
    }

    #[test]
    fn sobol_first_dims_are_stratified() {
        // 16 samples of one pixel: each of 16 strata of [0,1) gets exactly one.
        let mut s = Sampler::new(SamplerKind::Sobol, 1);
        let mut seen = [0u32; 16];
        for i in 0..16 {
            s.start_pixel_sample(10, 20, i);
            let v = s.get_1d();
            seen[(v * 16.0) as usize] += 1;
        }
        assert!(seen.iter().all(|&c| c == 1), "{seen:?}");
    }

    #[test]
    fn values_in_unit_interval() {
        let mut s = Sampler::new(SamplerKind::Sobol, 2);
        for i in 0..64 {
            s.start_pixel_sample(1, 2, i);
            for _ in 0..300 {
                let v = s.get_1d();
                assert!((0.0..1.0).contains(&v));
            }
        }
    }
}
