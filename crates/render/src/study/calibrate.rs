//! Time budgets for a renderer without a time limit: measure its wall time
//! at a few sample counts (1, 4, then 4x more until the times spread), and
//! give each budget the largest spp whose predicted time fits, predicted by
//! `seconds = t0 + k * spp` through the two measured runs around the budget
//! (the last two beyond the longest run). The line over all runs is kept
//! for the report; a single line misplaces renderers whose cost per sample
//! changes, such as pbrt-v4's `sppm`, whose iterations get cheaper as its
//! radius shrinks.

use super::error::{bail, Result};
use super::fit;
use serde::{Deserialize, Serialize};

/// The first two sample counts; then 4x more until the times spread enough.
const FIRST: [u32; 2] = [1, 4];
/// (spp, wall seconds) of calibration runs.
pub type Points = Vec<(u32, f64)>;

/// The largest sample count a calibration tries.
const MAX_SPP: u32 = 1 << 16;

/// One setting's calibration on one scene, stored so that a rerun of the
/// study does not calibrate again.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Calibration {
    pub scene: String,
    pub setting: String,
    pub threads: usize,
    /// The command with `{spp}`, `{seed}` and `{out}` left as placeholders;
    /// a stored calibration of another command is stale.
    pub command: Vec<String>,
    /// (spp, wall seconds) of every calibration run, in increasing spp.
    pub points: Vec<(u32, f64)>,
    /// The least-squares line over all runs: fixed seconds (start-up, scene
    /// loading, writing the image) ...
    pub t0: f64,
    /// ... and seconds per sample (per iteration for `sppm`).
    pub k: f64,
}

impl Calibration {
    /// The line that predicts the time of a budget of `seconds`: through the
    /// two runs around it (the last two beyond the longest), or the line
    /// over all runs where that segment does not rise.
    pub fn line_for(&self, seconds: f64) -> fit::Line {
        let p = &self.points;
        let overall = fit::Line {
            intercept: self.t0,
            slope: self.k,
        };
        if p.len() < 2 {
            return overall;
        }
        let i = (1..p.len())
            .find(|&i| p[i].1 >= seconds)
            .unwrap_or(p.len() - 1);
        let ((n0, t0), (n1, t1)) = (p[i - 1], p[i]);
        let k = (t1 - t0) / (n1 as f64 - n0 as f64);
        if k > 0.0 && k.is_finite() {
            fit::Line {
                intercept: t0 - k * n0 as f64,
                slope: k,
            }
        } else {
            overall
        }
    }

    /// The sample count for a budget of `seconds`.
    pub fn spp_for(&self, seconds: f64) -> u32 {
        let l = self.line_for(seconds);
        spp_for(seconds, l.intercept, l.slope)
    }
}

/// `max(1, floor((budget - t0) / k))`, at most `u32::MAX`.
pub fn spp_for(budget: f64, t0: f64, k: f64) -> u32 {
    let n = ((budget - t0) / k).floor();
    if n.is_nan() || n < 1.0 {
        1
    } else {
        n.min(u32::MAX as f64) as u32
    }
}

/// Measures `time(spp)` at 1 and 4 spp, then at 4x the last spp until the
/// slowest run is `spread` seconds slower than the first, and fits the line
/// through every point (its slope must be positive). `time` returns None
/// when interrupted.
pub fn calibrate(
    spread: f64,
    mut time: impl FnMut(u32) -> Result<Option<f64>>,
) -> Result<Option<(Points, fit::Line)>> {
    let mut points = Vec::new();
    let mut spp = FIRST[0];
    loop {
        let Some(t) = time(spp)? else {
            return Ok(None);
        };
        points.push((spp, t));
        let widened = t - points[0].1 >= spread;
        if points.len() >= FIRST.len() && (widened || spp >= MAX_SPP) {
            break;
        }
        spp = if points.len() < FIRST.len() {
            FIRST[points.len()]
        } else {
            spp * 4
        };
    }
    let xy: Vec<(f64, f64)> = points.iter().map(|&(n, t)| (n as f64, t)).collect();
    match fit::line(&xy) {
        Some(l) if l.slope > 0.0 => Ok(Some((points, l))),
        _ => bail!(
            "calibration: the wall time does not grow with the sample count ({})",
            points
                .iter()
                .map(|(n, t)| format!("{n} spp: {t:.3} s"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spp_for_budgets() {
        // 0.5 s to start, 0.25 s per sample.
        assert_eq!(spp_for(3.0, 0.5, 0.25), 10);
        assert_eq!(spp_for(3.1, 0.5, 0.25), 10);
        assert_eq!(spp_for(120.0, 0.5, 0.25), 478);
        assert_eq!(spp_for(0.6, 0.5, 0.25), 1, "at least one");
        assert_eq!(spp_for(0.1, 0.5, 0.25), 1, "budget below the fixed time");
        assert_eq!(spp_for(1e30, 0.0, 1e-9), u32::MAX);
    }

    #[test]
    fn calibrates_an_exact_line_and_widens_for_fast_renderers() {
        let mut asked = Vec::new();
        let (points, l) = calibrate(1.0, |n| {
            asked.push(n);
            Ok(Some(0.4 + 0.01 * n as f64))
        })
        .unwrap()
        .unwrap();
        // 1 -> 4 -> 16 -> 64 -> 256: 2.96 - 0.41 s is the first spread >= 1 s.
        assert_eq!(asked, [1, 4, 16, 64, 256]);
        assert_eq!(points.len(), 5);
        assert!((l.slope - 0.01).abs() < 1e-12 && (l.intercept - 0.4).abs() < 1e-12);
        // A slow renderer: 1 and 4 spp are enough.
        let (p, l) = calibrate(1.0, |n| Ok(Some(2.0 + 1.5 * n as f64)))
            .unwrap()
            .unwrap();
        assert_eq!(p, [(1, 3.5), (4, 8.0)]);
        assert_eq!(spp_for(30.0, l.intercept, l.slope), 18);
    }

    fn cal(points: Vec<(u32, f64)>) -> Calibration {
        let xy: Vec<(f64, f64)> = points.iter().map(|&(n, t)| (n as f64, t)).collect();
        let l = fit::line(&xy).unwrap();
        Calibration {
            scene: "s".into(),
            setting: "x".into(),
            threads: 2,
            command: vec![],
            points,
            t0: l.intercept,
            k: l.slope,
        }
    }

    #[test]
    fn budgets_use_the_segment_around_them() {
        // Iterations get cheaper: 0.5, then 0.25, then 0.125 s each.
        let c = cal(vec![(1, 1.5), (4, 3.0), (16, 6.0), (64, 12.0)]);
        // 2 s: between 1 and 4 spp, 0.5 s each from t0 = 1 s.
        assert_eq!(
            c.line_for(2.0),
            fit::Line {
                intercept: 1.0,
                slope: 0.5
            }
        );
        assert_eq!(c.spp_for(2.0), 2);
        assert_eq!(c.spp_for(1.0), 1, "below the first run");
        // 10 s: 16 spp + (10 - 6) / 0.125 = 48.
        assert_eq!(c.spp_for(10.0), 48);
        // 120 s: the last segment, extended: 64 + 108 / 0.125 = 928.
        assert_eq!(c.spp_for(120.0), 928);
        // The single line over all points would give far fewer.
        assert!(spp_for(120.0, c.t0, c.k) < 800);
        // A segment that does not rise (a noisy machine): the overall line.
        let c = cal(vec![(1, 1.5), (4, 1.4), (16, 6.0)]);
        assert_eq!(c.spp_for(1.3), spp_for(1.3, c.t0, c.k));
    }

    #[test]
    fn a_flat_or_interrupted_calibration() {
        let e = calibrate(1.0, |_| Ok(Some(0.3))).unwrap_err().to_string();
        assert!(
            e.contains("does not grow") && e.contains("65536 spp"),
            "{e}"
        );
        assert!(calibrate(1.0, |n| Ok((n < 4).then_some(1.0)))
            .unwrap()
            .is_none());
    }
}
