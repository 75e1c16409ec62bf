//! Log-log error-versus-time plots as hand-written SVG: per setting, every
//! run as a point, the min-max spread across seeds at each budget as a bar,
//! a line through the geometric means, and the least-squares power law
//! (dashed, its slope in the legend).

use super::fit::Line;

/// One setting's runs, grouped by budget: (seconds, error) per seed.
pub struct Series {
    pub name: String,
    pub colour: &'static str,
    pub groups: Vec<Vec<(f64, f64)>>,
    /// ln error = intercept + slope * ln seconds, drawn over the runs' seconds.
    pub fit: Option<Line>,
}

impl Series {
    /// The fitted line's two ends, at the series' shortest and longest run.
    fn fit_ends(&self) -> Option<[(f64, f64); 2]> {
        let l = self.fit?;
        let xs = self
            .groups
            .iter()
            .flatten()
            .map(|p| p.0)
            .filter(|x| *x > 0.0);
        let (lo, hi) = xs.fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
        let at = |x: f64| (x, l.at(x.ln()).exp());
        (hi > 0.0).then(|| [at(lo), at(hi)])
    }
}

/// Colour-blind-friendly categorical colours (Okabe-Ito).
pub const COLOURS: [&str; 8] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442",
];

fn log_range(v: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for x in v.filter(|x| *x > 0.0 && x.is_finite()) {
        lo = lo.min(x);
        hi = hi.max(x);
    }
    if !(hi > 0.0) {
        return None;
    }
    // Pad by 15% of the span in log space (at least a factor 1.5 overall).
    let span = (hi / lo).log10().max(0.18);
    let pad = 10f64.powf(span * 0.15);
    Some((lo / pad, hi * pad))
}

/// Ticks at 1, 2, 5 x 10^k inside `[lo, hi]`; only decades if there are enough.
pub fn ticks(lo: f64, hi: f64) -> Vec<f64> {
    let mut t = Vec::new();
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    for k in k0..=k1 {
        for m in [1.0, 2.0, 5.0] {
            let v = m * 10f64.powi(k);
            if v >= lo && v <= hi {
                t.push(v);
            }
        }
    }
    let decades: Vec<f64> = t
        .iter()
        .cloned()
        .filter(|v| (v.log10() - v.log10().round()).abs() < 1e-9)
        .collect();
    if decades.len() >= 3 {
        decades
    } else {
        t
    }
}

pub fn tick_label(v: f64) -> String {
    if (0.01..10000.0).contains(&v) {
        let s = format!("{v:.2}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        let k = v.log10().floor() as i32;
        let m = (v / 10f64.powi(k)).round();
        if m == 1.0 {
            format!("1e{k}")
        } else {
            format!("{m}e{k}")
        }
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The SVG text of a log-log plot of `series` (x: seconds, y: `y_label`).
pub fn svg(title: &str, y_label: &str, series: &[Series]) -> String {
    svg_xy(title, "seconds (wall clock, log)", y_label, series)
}

/// [`svg`] with its own x-axis label (the groups' first values are x).
pub fn svg_xy(title: &str, x_label: &str, y_label: &str, series: &[Series]) -> String {
    let (w, h) = (490.0, 300.0);
    let (ml, mr, mt, mb) = (62.0, 160.0, 26.0, 42.0);
    let ends: Vec<(f64, f64)> = series
        .iter()
        .filter_map(|s| s.fit_ends())
        .flatten()
        .collect();
    let pts = || {
        series
            .iter()
            .flat_map(|s| s.groups.iter().flatten())
            .chain(&ends)
    };
    let mut o = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="11">"#
    );
    o += &format!(
        r#"<rect width="{w}" height="{h}" fill="white"/><text x="{}" y="16" text-anchor="middle" font-size="12">{}</text>"#,
        ml + (w - ml - mr) / 2.0,
        esc(title)
    );
    let (Some((x0, x1)), Some((y0, y1))) =
        (log_range(pts().map(|p| p.0)), log_range(pts().map(|p| p.1)))
    else {
        return o + r#"<text x="100" y="150">no finished runs</text></svg>"#;
    };
    let px = |x: f64| ml + (x.log10() - x0.log10()) / (x1.log10() - x0.log10()) * (w - ml - mr);
    let py = |y: f64| h - mb - (y.log10() - y0.log10()) / (y1.log10() - y0.log10()) * (h - mt - mb);
    o += &format!(
        r##"<rect x="{ml}" y="{mt}" width="{}" height="{}" fill="none" stroke="#444"/>"##,
        w - ml - mr,
        h - mt - mb
    );
    for t in ticks(x0, x1) {
        let x = px(t);
        o += &format!(
            r##"<line x1="{x:.1}" y1="{mt}" x2="{x:.1}" y2="{}" stroke="#ddd"/><text x="{x:.1}" y="{}" text-anchor="middle">{}</text>"##,
            h - mb,
            h - mb + 14.0,
            tick_label(t)
        );
    }
    for t in ticks(y0, y1) {
        let y = py(t);
        o += &format!(
            r##"<line x1="{ml}" y1="{y:.1}" x2="{}" y2="{y:.1}" stroke="#ddd"/><text x="{}" y="{:.1}" text-anchor="end">{}</text>"##,
            w - mr,
            ml - 4.0,
            y + 4.0,
            tick_label(t)
        );
    }
    o += &format!(
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        ml + (w - ml - mr) / 2.0,
        h - 8.0,
        esc(x_label)
    );
    o += &format!(
        r#"<text transform="translate(14 {}) rotate(-90)" text-anchor="middle">{} (log)</text>"#,
        mt + (h - mt - mb) / 2.0,
        esc(y_label)
    );
    for (i, s) in series.iter().enumerate() {
        let c = s.colour;
        let mut line = Vec::new();
        for g in s.groups.iter().filter(|g| !g.is_empty()) {
            let ok: Vec<&(f64, f64)> = g.iter().filter(|p| p.0 > 0.0 && p.1 > 0.0).collect();
            if ok.is_empty() {
                continue;
            }
            let n = ok.len() as f64;
            let mx = ok.iter().map(|p| p.0).sum::<f64>() / n;
            let gy = (ok.iter().map(|p| p.1.ln()).sum::<f64>() / n).exp();
            let (lo, hi) = ok.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
            o += &format!(
                r#"<line x1="{0:.1}" y1="{1:.1}" x2="{0:.1}" y2="{2:.1}" stroke="{c}" stroke-width="3" opacity="0.35"/>"#,
                px(mx),
                py(lo),
                py(hi)
            );
            for p in &ok {
                o += &format!(
                    r#"<circle cx="{:.1}" cy="{:.1}" r="2.5" fill="{c}"/>"#,
                    px(p.0),
                    py(p.1)
                );
            }
            line.push(format!("{:.1},{:.1}", px(mx), py(gy)));
        }
        o += &format!(
            r#"<polyline points="{}" fill="none" stroke="{c}" stroke-width="1.5"/>"#,
            line.join(" ")
        );
        if let Some([a, b]) = s.fit_ends() {
            o += &format!(
                r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{c}" stroke-width="1" stroke-dasharray="5 3"/>"#,
                px(a.0),
                py(a.1),
                px(b.0),
                py(b.1)
            );
        }
        let label = match s.fit {
            Some(l) => format!("{} ({:.2})", s.name, l.slope),
            None => s.name.clone(),
        };
        let ly = mt + 10.0 + i as f64 * 16.0;
        o += &format!(
            r#"<line x1="{0}" y1="{ly}" x2="{1}" y2="{ly}" stroke="{c}" stroke-width="2"/><circle cx="{2}" cy="{ly}" r="2.5" fill="{c}"/><text x="{3}" y="{4}">{5}</text>"#,
            w - mr + 8.0,
            w - mr + 28.0,
            w - mr + 18.0,
            w - mr + 32.0,
            ly + 4.0,
            esc(&label)
        );
    }
    o + "</svg>"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_and_labels() {
        assert_eq!(ticks(0.8, 9.0), vec![1.0, 2.0, 5.0]);
        assert_eq!(ticks(1e-5, 2e-2), vec![1e-5, 1e-4, 1e-3, 1e-2]);
        assert_eq!(tick_label(0.5), "0.5");
        assert_eq!(tick_label(2.0), "2");
        assert_eq!(tick_label(1e-4), "1e-4");
        assert_eq!(tick_label(5e-3), "5e-3");
    }

    #[test]
    fn svg_has_a_point_per_run_and_a_legend() {
        let s = Series {
            name: "mis".into(),
            colour: COLOURS[0],
            groups: vec![vec![(1.0, 0.1), (1.1, 0.2)], vec![(2.0, 0.05), (2.1, 0.06)]],
            fit: None,
        };
        let t = svg("scene", "relMSE", &[s]);
        assert!(t.starts_with("<svg") && t.ends_with("</svg>"));
        assert_eq!(t.matches("<circle").count(), 4 + 1);
        assert!(t.contains(">mis</text>"));
        assert!(!t.contains("stroke-dasharray"));
        assert!(svg("empty", "x", &[]).contains("no finished runs"));
    }

    #[test]
    fn the_fit_is_dashed_and_its_slope_in_the_legend() {
        let fit = Line {
            intercept: 0.0,
            slope: -1.0,
        };
        let s = Series {
            name: "pbrt".into(),
            colour: COLOURS[1],
            groups: vec![vec![(2.0, 0.5)], vec![(8.0, 0.125)]],
            fit: Some(fit),
        };
        let [a, b] = s.fit_ends().unwrap();
        assert!(a.0 == 2.0 && (a.1 - 0.5).abs() < 1e-12, "{a:?}");
        assert!(b.0 == 8.0 && (b.1 - 0.125).abs() < 1e-12, "{b:?}");
        let t = svg("scene", "MSE", &[s]);
        assert_eq!(t.matches("stroke-dasharray").count(), 1);
        assert!(t.contains(">pbrt (-1.00)</text>"), "{t}");
    }
}
