//! The seed's multiple-importance weights for caustics (appendix A.8-A.10):
//! `w_i = q_i / (q_1 + q_2)` with
//! `q_1 = N L_e cos(theta) DeltaA / (Phi alpha)` (photon density technique)
//! and `q_2 = m_2 p_2` (final-gather rays sampled from the BSDF).

/// How the two caustic techniques are combined.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CausticMode {
    /// The seed's weights.
    Mis,
    /// Photon map only: `w_1 = 1`, `w_2 = 0`.
    Photons,
    /// Final-gather rays only: `w_1 = 0`, `w_2 = 1`.
    Gather,
}

impl CausticMode {
    pub fn from_name(s: &str) -> Option<CausticMode> {
        match s {
            "mis" => Some(CausticMode::Mis),
            "photons" => Some(CausticMode::Photons),
            "gather" => Some(CausticMode::Gather),
            _ => None,
        }
    }
    pub fn name(&self) -> &'static str {
        match self {
            CausticMode::Mis => "mis",
            CausticMode::Photons => "photons",
            CausticMode::Gather => "gather",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Heuristic {
    /// `w_i = q_i / (q_1 + q_2)` (the seed's Equation 1).
    Balance,
    /// `w_i = q_i^2 / (q_1^2 + q_2^2)`.
    Power,
}

impl Heuristic {
    pub fn from_name(s: &str) -> Option<Heuristic> {
        match s {
            "balance" => Some(Heuristic::Balance),
            "power" => Some(Heuristic::Power),
            _ => None,
        }
    }
    pub fn name(&self) -> &'static str {
        match self {
            Heuristic::Balance => "balance",
            Heuristic::Power => "power",
        }
    }
}

/// How `alpha` of `q_1` is set at the camera path's first non-delta hit
/// (elsewhere it is 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AlphaMode {
    /// The seed's: the samples per pixel. It assumes every sample of a pixel
    /// reads the same photons, so the photon estimate counts once per pixel
    /// while the gather rays count `spp` times.
    Spp,
    /// The samples per pixel discounted by how many different photon
    /// neighbourhoods the pixel's samples read (see [`Alpha::effective`]):
    /// the seed's value where a pixel's footprint is small against the query
    /// disc, tending to 1 where it is large.
    Footprint,
    /// 1.
    One,
}

impl AlphaMode {
    pub fn from_name(s: &str) -> Option<AlphaMode> {
        match s {
            "footprint" | "auto" => Some(AlphaMode::Footprint),
            "spp" => Some(AlphaMode::Spp),
            "1" => Some(AlphaMode::One),
            _ => None,
        }
    }
    pub fn name(&self) -> &'static str {
        match self {
            AlphaMode::Spp => "spp",
            AlphaMode::Footprint => "footprint",
            AlphaMode::One => "1",
        }
    }
    pub const NAMES: &'static str = "footprint (or auto), spp, 1";
}

/// `alpha` at a shading point: the pixel's sample count and the area its
/// samples spread over there (0: unknown, the seed's `alpha = spp`), and
/// the gather rays' gain (`gathergain`, 1 for the seed's weights).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Alpha {
    pub spp: f32,
    pub pixel_area: f32,
    pub gain: f32,
}

impl Alpha {
    pub const ONE: Alpha = Alpha {
        spp: 1.0,
        pixel_area: 0.0,
        gain: 1.0,
    };

    /// `alpha` for a caustic query of disc area `delta_a`. The pixel value
    /// averages `spp` photon estimates; two of them share photons as their
    /// query discs overlap, on average `rho = DeltaA / (DeltaA + A_pix)` for
    /// points spread over the pixel's footprint `A_pix` (1 for a footprint
    /// inside one disc, `DeltaA / A_pix` for a large one). The average then
    /// has the variance of `spp / (1 + (spp - 1) rho)` independent estimates,
    /// so the gather rays' `spp` samples stand against that many photon
    /// estimates: `alpha = 1 + (spp - 1) rho`, times `gain`: the balance
    /// heuristic compares densities, as if every sample were independent,
    /// while a pixel's Sobol samples can make the gather rays' average many
    /// times better than that and the photons' hardly (docs/integrators.md,
    /// "Why the large light resists").
    pub fn effective(&self, delta_a: f32) -> f32 {
        let rho = if self.pixel_area > 0.0 && self.pixel_area.is_finite() && delta_a > 0.0 {
            delta_a / (delta_a + self.pixel_area)
        } else {
            1.0
        };
        (1.0 + (self.spp - 1.0).max(0.0) * rho) * self.gain
    }
}

/// `q_1 = N L_e cos(theta) DeltaA / (Phi alpha)` (A.10). `L_e = infinity`
/// (delta lights) gives infinity.
#[inline]
pub fn q1(n_emitted: f64, le: f32, cos_theta: f32, delta_a: f32, phi: f32, alpha: f32) -> f32 {
    if le.is_infinite() {
        return f32::INFINITY;
    }
    (n_emitted * le as f64 * cos_theta.abs() as f64 * delta_a as f64 / (phi as f64 * alpha as f64))
        as f32
}

/// `q_2 = m_2 p_2` (A.9): `p_2` is the BSDF sampling density of the direction.
#[inline]
pub fn q2(m2: u32, p2: f32) -> f32 {
    m2 as f32 * p2.max(0.0)
}

/// Weight of the photon technique for a sample with these `q`s.
#[inline]
pub fn w1(q1: f32, q2: f32, mode: CausticMode, h: Heuristic) -> f32 {
    match mode {
        CausticMode::Photons => 1.0,
        CausticMode::Gather => 0.0,
        CausticMode::Mis => {
            if q1.is_infinite() || q2 <= 0.0 {
                // Delta lights (gather rays never reach them) and directions the
                // BSDF cannot sample: only photons can carry them.
                return 1.0;
            }
            match h {
                Heuristic::Balance => q1 / (q1 + q2),
                Heuristic::Power => {
                    let r = q2 / q1.max(f32::MIN_POSITIVE);
                    1.0 / (1.0 + r * r)
                }
            }
        }
    }
}

/// Weight of the final-gather technique: `1 - w1` for the same sample.
#[inline]
pub fn w2(q1: f32, q2: f32, mode: CausticMode, h: Heuristic) -> f32 {
    1.0 - w1(q1, q2, mode, h)
}

/// The weights `[w_1, w_2, w_3]` of a caustic path at a camera ray's first
/// hit when the caustic photons are also connected to the camera (a third
/// technique, `q_3 = N L_e cos(theta) / (Phi S J)`: the light tracer's
/// paths per camera sample, `J` the pixels per unit area at the hit and `S`
/// the samples per pixel that share the photons, in the same measure as
/// the seed's `q_1` and `q_2`). A delta light (`q_1` and `q_3` infinite) is
/// found by the photons and the connections only, in the ratio `r3 = q_3 /
/// q_1` (finite). The three sum to one whatever the inputs.
#[inline]
pub fn mis3(q1: f32, q2: f32, q3: f32, r3: f32, h: Heuristic) -> [f32; 3] {
    let p = |q: f32| match h {
        Heuristic::Balance => q as f64,
        Heuristic::Power => q as f64 * q as f64,
    };
    let (a, b, c) = if q1.is_infinite() || q3.is_infinite() {
        (1.0, 0.0, p(r3))
    } else {
        (p(q1), p(q2), p(q3))
    };
    let sum = a + b + c;
    if !(sum > 0.0 && sum.is_finite()) {
        // Nothing to weigh (a zero contribution) or an infinite `r3`.
        return [0.0, 0.0, 1.0];
    }
    [(a / sum) as f32, (b / sum) as f32, (c / sum) as f32]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn effective_alpha_spans_one_to_spp() {
        let a = |spp: f32, area: f32| Alpha {
            spp,
            pixel_area: area,
            gain: 1.0,
        };
        // Unknown footprint: the seed's alpha.
        assert_eq!(a(64.0, 0.0).effective(1e-3), 64.0);
        // A footprint far inside the disc: every sample reads the same photons.
        assert!((a(64.0, 1e-9).effective(1e-3) - 64.0).abs() < 1e-3);
        // Equal areas: rho = 1/2.
        assert!((a(65.0, 1e-3).effective(1e-3) - 33.0).abs() < 1e-4);
        // A footprint of 1000 discs: close to 1 + 63/1001.
        assert!((a(64.0, 1.0).effective(1e-3) - (1.0 + 63.0 / 1001.0)).abs() < 1e-4);
        assert_eq!(Alpha::ONE.effective(1e-3), 1.0);
        // The gain multiplies whatever the footprint gives.
        let g = Alpha {
            gain: 3.0,
            ..a(65.0, 1e-3)
        };
        assert!((g.effective(1e-3) - 99.0).abs() < 1e-3);
        assert_eq!(AlphaMode::from_name("auto"), Some(AlphaMode::Footprint));
        for m in [AlphaMode::Spp, AlphaMode::Footprint, AlphaMode::One] {
            assert_eq!(AlphaMode::from_name(m.name()), Some(m));
        }
    }

    #[test]
    fn q1_and_q2_match_hand_computed_values() {
        // N = 1e5, L_e = 20, cos = 0.5, DeltaA = pi 0.01^2, Phi = 300, alpha = 4:
        // q1 = 1e5 * 20 * 0.5 * 3.14159e-4 / (300 * 4) = 0.261799
        let v = q1(1e5, 20.0, 0.5, std::f32::consts::PI * 1e-4, 300.0, 4.0);
        assert!((v - 0.261_799).abs() < 1e-5, "{v}");
        assert_eq!(q2(16, 0.25), 4.0);
        // Balance: w1 = 0.261799 / (0.261799 + 4)
        let w = w1(v, 4.0, CausticMode::Mis, Heuristic::Balance);
        assert!((w - 0.061_429).abs() < 1e-5, "{w}");
        // Power: w1 = q1^2 / (q1^2 + q2^2)
        let w = w1(v, 4.0, CausticMode::Mis, Heuristic::Power);
        assert!((w - 0.068_539 / (0.068_539 + 16.0)).abs() < 1e-6, "{w}");
    }

    #[test]
    fn weights_sum_to_one() {
        for &(a, b) in &[
            (0.1f32, 3.0f32),
            (5.0, 0.2),
            (1.0, 1.0),
            (1e-8, 1e8),
            (1e30, 1e-30),
        ] {
            for h in [Heuristic::Balance, Heuristic::Power] {
                for m in [CausticMode::Mis, CausticMode::Photons, CausticMode::Gather] {
                    let s = w1(a, b, m, h) + w2(a, b, m, h);
                    assert!((s - 1.0).abs() < 1e-6, "{a} {b} {h:?} {m:?}");
                }
            }
        }
    }

    #[test]
    fn delta_lights_and_unsampleable_directions_go_to_photons() {
        let inf = q1(1e5, f32::INFINITY, 0.7, 0.01, 10.0, 1.0);
        assert!(inf.is_infinite());
        assert_eq!(w1(inf, 3.0, CausticMode::Mis, Heuristic::Balance), 1.0);
        assert_eq!(w1(inf, 3.0, CausticMode::Mis, Heuristic::Power), 1.0);
        assert_eq!(
            w1(0.5, q2(16, 0.0), CausticMode::Mis, Heuristic::Balance),
            1.0
        );
        assert_eq!(w2(0.5, 0.0, CausticMode::Mis, Heuristic::Power), 0.0);
    }

    #[test]
    fn baselines_select_one_technique() {
        assert_eq!(w1(0.3, 0.7, CausticMode::Photons, Heuristic::Balance), 1.0);
        assert_eq!(w2(0.3, 0.7, CausticMode::Gather, Heuristic::Balance), 1.0);
    }

    #[test]
    fn alpha_scales_q1_only() {
        let a1 = q1(1e4, 2.0, 1.0, 0.1, 5.0, 1.0);
        let a8 = q1(1e4, 2.0, 1.0, 0.1, 5.0, 8.0);
        assert!((a1 / a8 - 8.0).abs() < 1e-4);
    }
}
