//! Least-squares lines: wall time against spp (the calibration of external
//! runs) and log error against log time (the convergence slopes).

use super::config::Config;
use super::store::RunResult;
use serde::Serialize;

/// `y = intercept + slope * x`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    pub intercept: f64,
    pub slope: f64,
}

impl Line {
    pub fn at(&self, x: f64) -> f64 {
        self.intercept + self.slope * x
    }
}

/// The least-squares line through `points`; None with fewer than two
/// distinct x values or a non-finite point.
pub fn line(points: &[(f64, f64)]) -> Option<Line> {
    if points.iter().any(|p| !(p.0.is_finite() && p.1.is_finite())) {
        return None;
    }
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if !(sxx > 1e-12 * (1.0 + mx * mx)) {
        return None;
    }
    let slope = sxy / sxx;
    Some(Line {
        intercept: my - slope * mx,
        slope,
    })
}

/// The least-squares line of ln y against ln x over the points with both
/// positive: the exponent of a power law `y = e^intercept * x^slope`.
pub fn log_log(points: &[(f64, f64)]) -> Option<Line> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .map(|p| (p.0.ln(), p.1.ln()))
        .collect();
    line(&logs)
}

/// The slopes of one scene and setting over all its runs (budgets and seeds).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Slope {
    pub scene: String,
    pub setting: String,
    pub runs: usize,
    /// Slope of ln relMSE against ln seconds.
    pub relmse: Option<f64>,
    /// Slope of ln MSE against ln seconds.
    pub mse: Option<f64>,
}

/// The fitted power law of `metric` against seconds over `runs`.
pub fn metric_fit<'a>(runs: impl Iterator<Item = &'a RunResult>, metric: &str) -> Option<Line> {
    let pts: Vec<(f64, f64)> = runs.map(|r| (r.seconds, r.metric(metric))).collect();
    log_log(&pts)
}

/// A [`Slope`] per scene and setting that has finished runs.
pub fn slopes(c: &Config, results: &[RunResult]) -> Vec<Slope> {
    let mut v = Vec::new();
    for scene in c.scenes.iter().map(|s| s.name.as_str()) {
        for setting in c.settings.iter().map(|s| s.name.as_str()) {
            let of = || {
                results
                    .iter()
                    .filter(move |r| r.scene == scene && r.setting == setting)
            };
            let runs = of().count();
            if runs == 0 {
                continue;
            }
            v.push(Slope {
                scene: scene.into(),
                setting: setting.into(),
                runs,
                relmse: metric_fit(of(), "relmse").map(|l| l.slope),
                mse: metric_fit(of(), "mse").map(|l| l.slope),
            });
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_through_exact_points() {
        let l = line(&[(1.0, 5.0), (2.0, 7.0), (4.0, 11.0)]).unwrap();
        assert!((l.slope - 2.0).abs() < 1e-12 && (l.intercept - 3.0).abs() < 1e-12);
        assert!((l.at(10.0) - 23.0).abs() < 1e-9);
        assert_eq!(line(&[(1.0, 1.0), (1.0, 2.0)]), None, "one x value");
        assert_eq!(line(&[(1.0, 1.0)]), None);
        assert_eq!(line(&[]), None);
    }

    #[test]
    fn least_squares_of_noisy_points() {
        // Residuals +1, -1, -1, +1 around y = 1 + 0.5x cancel in both sums.
        let p = [(0.0, 2.0), (1.0, 0.5), (3.0, 1.5), (4.0, 4.0)];
        let l = line(&p).unwrap();
        assert!((l.slope - 0.5).abs() < 1e-12, "{l:?}");
        assert!((l.intercept - 1.0).abs() < 1e-12, "{l:?}");
    }

    #[test]
    fn log_log_slope_of_a_power_law() {
        // relMSE = 0.3 t^-0.8 with a seed-to-seed factor that is symmetric in log.
        let mut p = Vec::new();
        for t in [3.0, 10.0, 30.0, 120.0] {
            for f in [1.25, 0.8] {
                p.push((t, 0.3 * f64::powf(t, -0.8) * f));
            }
        }
        p.push((5.0, 0.0)); // a zero error has no logarithm: left out
        let l = log_log(&p).unwrap();
        assert!((l.slope + 0.8).abs() < 1e-12, "{l:?}");
        assert!((l.intercept - 0.3f64.ln()).abs() < 1e-12, "{l:?}");
    }
}
