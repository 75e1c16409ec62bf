//! The progressive mode (METHOD.md §7; Knaus & Zwicker 2011): the render
//! runs in iterations; iteration `i` traces fresh photons from a random
//! stream keyed by `(seed, i)` only, renders `S` samples per pixel with its
//! maps and frees them. Its caustic and global estimates use discs of radii
//! fixed before the iteration, `r_{i+1}^2 = r_i^2 (i + a) / (i + 1)`, so bias
//! and variance both vanish as iterations accumulate. This module holds the
//! settings, the radius sequence, the per-iteration seed and the iteration
//! state a checkpoint stores; `radius_field.rs` holds `r_0` point by point,
//! `run.rs` drives the iterations and `budget.rs` chooses the photon counts
//! under a time budget.

/// Settings of the progressive mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progressive {
    /// `S`: samples per pixel rendered with each iteration's maps.
    pub iteration_spp: u32,
    /// `a` of the radius sequence, in (0, 1].
    pub shrink: f32,
    /// `r_0` of the caustic estimate everywhere; 0: from the first
    /// iteration's caustic photons, point by point (`radius_field.rs`).
    pub initial_radius: f32,
    /// Iterations to render (0: as many as the sample count or the time
    /// budget gives).
    pub iterations: u32,
    /// Under a time budget, the share of each iteration's time given to
    /// photon tracing when the photon counts are not set (0: keep them).
    pub photon_share: f32,
}

impl Default for Progressive {
    fn default() -> Self {
        Progressive {
            iteration_spp: 1,
            shrink: 0.5,
            initial_radius: 0.0,
            iterations: 0,
            photon_share: 0.25,
        }
    }
}

/// `r_{i+1}^2` from `r_i^2` (Knaus & Zwicker 2011, eq. 15).
pub fn next_radius2(r2: f64, i: u64, a: f64) -> f64 {
    r2 * (i as f64 + a) / (i as f64 + 1.0)
}

/// Under a time budget, whether to stop after `done` iterations although
/// the time left would reach `reachable`: at a power of two (from 4 on)
/// when going on would add at most a quarter. The Sobol sampler's points
/// are balanced at powers of two, and so is the progressive image, whose
/// iteration `i` takes each pixel's sample `i`: on the default scene
/// (docs/measured.md, "Powers of two") 16 iterations have 2.27e-3 MSE, 17
/// have 2.93e-3 and 20 have 2.44e-3; 24 again less (1.74e-3). Up to 64
/// iterations: at hundreds the step is lost in the noise (256 against 288
/// on the caustic set), and stopping would only give time away.
pub fn stop_at_power_of_two(done: u64, reachable: u64) -> bool {
    (4..=64).contains(&done) && done.is_power_of_two() && reachable <= done + done / 4
}

/// The seed of iteration `i`'s photon streams: depends on `(seed, i)` only.
pub fn iteration_seed(seed: u64, i: u64) -> u64 {
    mix(seed ^ mix(i.wrapping_add(1)))
}

/// SplitMix64's finaliser.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Where a progressive render is, as a checkpoint stores it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IterState {
    /// The current iteration `i`.
    pub index: u64,
    /// Samples per pixel done when it began, and done so far.
    pub start_spp: u32,
    pub spp_done: u32,
    /// `r_i^2 / r_0^2` = `prod_{j<i} (j + a) / (j + 1)`, the same for every
    /// point's radius (see `radius_field.rs`); 0 before iteration 0.
    pub scale2: f64,
    /// Photons emitted per iteration for the global and the caustic map
    /// (0 until chosen: the settings', or the time rule's).
    pub global_photons: u64,
    pub caustic_photons: u64,
}

impl IterState {
    /// Moves on to the next iteration if this one has had its `s_iter`
    /// samples per pixel (radius by [`next_radius2`] with `a`); `true` if it did.
    pub fn next_if_done(&mut self, s_iter: u32, a: f64) -> bool {
        if self.spp_done < self.start_spp.saturating_add(s_iter) {
            return false;
        }
        self.scale2 = next_radius2(self.scale2, self.index, a);
        self.index += 1;
        self.start_spp = self.spp_done;
        true
    }

    /// Sets the photon counts when none are set yet (the first iteration;
    /// every iteration if both are 0), and with them the first radius.
    pub fn choose_counts(&mut self, counts: (u64, u64)) {
        if self.global_photons == 0 && self.caustic_photons == 0 {
            (self.global_photons, self.caustic_photons) = counts;
            self.scale2 = 1.0;
        }
    }

    /// The state after the passes of a render without a time budget
    /// reach `spp` samples per pixel: the driver's passes of `per_pass`
    /// samples (the last cut at `target`, 0: none) replayed, with the
    /// steps the render takes before each pass.
    pub fn replay(
        spp: u32,
        per_pass: u32,
        target: u32,
        s_iter: u32,
        a: f64,
        counts: (u64, u64),
    ) -> IterState {
        let mut it = IterState::default();
        let target = if target == 0 { u32::MAX } else { target };
        while it.spp_done < spp {
            it.next_if_done(s_iter, a);
            it.choose_counts(counts);
            it.spp_done += per_pass.max(1).min(target - it.spp_done);
        }
        it
    }

    pub const BYTES: usize = 8 + 4 + 4 + 8 + 8 + 8;

    pub fn encode(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.index.to_le_bytes());
        out.extend_from_slice(&self.start_spp.to_le_bytes());
        out.extend_from_slice(&self.spp_done.to_le_bytes());
        out.extend_from_slice(&self.scale2.to_bits().to_le_bytes());
        out.extend_from_slice(&self.global_photons.to_le_bytes());
        out.extend_from_slice(&self.caustic_photons.to_le_bytes());
    }

    pub fn decode(b: &[u8]) -> Option<IterState> {
        if b.len() != Self::BYTES {
            return None;
        }
        let u32_at = |i: usize| u32::from_le_bytes(b[i..i + 4].try_into().unwrap());
        let u64_at = |i: usize| u64::from_le_bytes(b[i..i + 8].try_into().unwrap());
        Some(IterState {
            index: u64_at(0),
            start_spp: u32_at(8),
            spp_done: u32_at(12),
            scale2: f64::from_bits(u64_at(16)),
            global_photons: u64_at(24),
            caustic_photons: u64_at(32),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radius_sequence_follows_knaus_zwicker() {
        // r_n^2 / r_0^2 = prod_{i<n} (i + a) / (i + 1) = Gamma(n + a) / (Gamma(a) n!).
        let a = 2.0 / 3.0;
        let mut r2 = 1.0;
        for i in 0..3 {
            r2 = next_radius2(r2, i, a);
        }
        let expected = (a / 1.0) * ((1.0 + a) / 2.0) * ((2.0 + a) / 3.0);
        assert!((r2 - expected).abs() < 1e-15);
        // a = 1 keeps the radius.
        assert_eq!(next_radius2(0.25, 7, 1.0), 0.25);
        // For large n the ratio tends to n^(a - 1) / Gamma(a) (Gamma(2/3) = 1.354118).
        let mut r2 = 1.0;
        for i in 0..10_000 {
            r2 = next_radius2(r2, i, a);
        }
        let asymptote = 10_000f64.powf(a - 1.0) / 1.354_117_939;
        assert!((r2 / asymptote - 1.0).abs() < 1e-3, "{r2} vs {asymptote}");
    }

    #[test]
    fn time_budgets_stop_at_a_power_of_two_a_quarter_short() {
        assert!(stop_at_power_of_two(16, 16));
        assert!(stop_at_power_of_two(16, 17));
        assert!(stop_at_power_of_two(16, 20));
        assert!(!stop_at_power_of_two(16, 21));
        assert!(!stop_at_power_of_two(17, 18));
        assert!(!stop_at_power_of_two(24, 25));
        assert!(stop_at_power_of_two(64, 80));
        assert!(!stop_at_power_of_two(64, 81));
        // Too few or too many iterations to care: the budget decides.
        assert!(!stop_at_power_of_two(2, 2));
        assert!(!stop_at_power_of_two(256, 257));
    }

    #[test]
    fn iteration_seeds_differ_and_depend_on_seed_and_index_only() {
        let s: Vec<u64> = (0..100).map(|i| iteration_seed(7, i)).collect();
        let mut d = s.clone();
        d.sort();
        d.dedup();
        assert_eq!(d.len(), 100);
        assert_eq!(iteration_seed(7, 3), s[3]);
        assert_ne!(iteration_seed(8, 3), s[3]);
    }

    #[test]
    fn replay_follows_the_iterations_over_pass_boundaries() {
        let a = 0.5;
        let counts = (10, 20);
        // Iterations of 2 samples, passes of 1: at 5, iteration 2 began at 4.
        let it = IterState::replay(5, 1, 8, 2, a, counts);
        let r2 = next_radius2(next_radius2(1.0, 0, a), 1, a);
        let expect = IterState {
            index: 2,
            start_spp: 4,
            spp_done: 5,
            scale2: r2,
            global_photons: 10,
            caustic_photons: 20,
        };
        assert_eq!(it, expect);
        // Passes of 3 samples overrun iterations of 2: they begin at 0, 3, 6.
        let it = IterState::replay(9, 3, 0, 2, a, counts);
        assert_eq!((it.index, it.start_spp, it.spp_done), (2, 6, 9));
        // Nothing done: the fresh state.
        assert_eq!(
            IterState::replay(0, 1, 8, 2, a, counts),
            IterState::default()
        );
    }

    #[test]
    fn state_round_trips() {
        let st = IterState {
            index: 12,
            start_spp: 48,
            spp_done: 50,
            scale2: 0.125,
            global_photons: 20_000,
            caustic_photons: 123_000,
        };
        let mut b = Vec::new();
        st.encode(&mut b);
        assert_eq!(b.len(), IterState::BYTES);
        assert_eq!(IterState::decode(&b), Some(st));
        assert_eq!(IterState::decode(&b[1..]), None);
    }
}
