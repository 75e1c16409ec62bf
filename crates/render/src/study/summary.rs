//! The report's study-wide sections: skipped settings, external settings
//! and their calibrations, and the error-versus-time slopes.

use super::command::show;
use super::config::{Budget, Config};
use super::report::esc;
use super::store::Summary;

/// Skipped settings, external commands, calibrations and slopes.
pub fn html(c: &Config, s: &Summary) -> String {
    let mut o = String::new();
    for m in &s.skipped {
        o += &format!("<p><b>Skipped:</b> {}.</p>", esc(m));
    }
    o += &external(c, s);
    o + &slopes(c, s)
}

fn external(c: &Config, s: &Summary) -> String {
    let ext: Vec<_> = c.settings.iter().filter(|s| s.external.is_some()).collect();
    if ext.is_empty() {
        return String::new();
    }
    let mut o = String::from("<h2>External renderers</h2><ul>");
    for st in &ext {
        o += &format!(
            "<li><b>{}</b>: <code>{}</code>{}</li>",
            esc(&st.name),
            esc(&show(st.external.as_deref().unwrap_or_default())),
            st.integrator
                .as_ref()
                .map(|i| format!(
                    " on a copy of the scene whose <code>Integrator</code> is <code>{}</code> (its parameters kept{}; paths absolute)",
                    esc(i),
                    st.integrator_params
                        .as_ref()
                        .map(|p| format!(", <code>{}</code> added", esc(p)))
                        .unwrap_or_default()
                ))
                .unwrap_or_default()
        );
    }
    o += "</ul><p class=small>An external run's seconds are the program's wall time from start to exit (start-up, scene loading and image writing included), and its points are placed at that measured time, not at the nominal budget. A time budget becomes a sample count (for pbrt-v4's <code>sppm</code>, iterations) from a calibration per scene and setting, stored in <code>calibration/</code> and reused by a rerun: the program runs at 1 and 4 spp, then 4x more until the slowest run is a quarter of the largest budget slower than the first (at least 2 s). A budget B gets <code>spp = max(1, floor((B − t0) / k))</code> with the line <code>wall = t0 + k·spp</code> through the two calibration runs around B (the last two beyond the longest run). The table also gives the least-squares line over all calibration runs; where its spp differ from the chosen ones, the cost per sample is not constant (pbrt-v4's <code>sppm</code> iterations get cheaper as its radius shrinks).</p>";
    if s.calibrations.is_empty() {
        return o;
    }
    let times: Vec<f64> = c
        .budgets()
        .iter()
        .filter_map(|b| match b {
            Budget::Time(t) => Some(*t),
            Budget::Spp(_) => None,
        })
        .collect();
    o += "<table><tr><th>scene</th><th>setting</th><th>threads</th><th>calibration runs (spp: s)</th><th>all runs: t0 (s)</th><th>k (s/spp)</th>";
    for t in &times {
        o += &format!("<th>spp at {t} s<br><span class=small>(all runs' line)</span></th>");
    }
    o += "</tr>";
    for cal in &s.calibrations {
        let pts: Vec<String> = cal
            .points
            .iter()
            .map(|(n, t)| format!("{n}: {t:.2}"))
            .collect();
        o += &format!(
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.3}</td><td>{:.4}</td>",
            esc(&cal.scene),
            esc(&cal.setting),
            cal.threads,
            pts.join(", "),
            cal.t0,
            cal.k
        );
        for t in &times {
            let all = super::calibrate::spp_for(*t, cal.t0, cal.k);
            o += &format!(
                "<td>{}<br><span class=small>({all})</span></td>",
                cal.spp_for(*t)
            );
        }
        o += "</tr>";
    }
    o + "</table>"
}

fn slopes(c: &Config, s: &Summary) -> String {
    if s.slopes.is_empty() {
        return String::new();
    }
    let mut o = String::from("<h2>Error against time: slopes</h2><p class=small>Least-squares slope of ln relMSE (the report's leading metric) against ln seconds over every finished run of a scene and setting (all budgets and seeds, each run at its measured seconds); MSE's slope and the number of runs under it. An unbiased estimator with constant cost per sample has slope −1; a flatter slope means bias that does not vanish fast enough, or a slower rate. The plots show the fitted lines dashed, their slopes in the legend.</p><table><tr><th>scene</th>");
    for st in &c.settings {
        o += &format!("<th>{}</th>", esc(&st.name));
    }
    o += "</tr>";
    let f = |v: Option<f64>| v.map_or("–".to_string(), |x| format!("{x:.2}"));
    for sc in &c.scenes {
        o += &format!("<tr><th>{}</th>", esc(&sc.name));
        for st in &c.settings {
            let cell = s
                .slopes
                .iter()
                .find(|x| x.scene == sc.name && x.setting == st.name);
            o += &match cell {
                None => "<td>–</td>".to_string(),
                Some(x) => format!(
                    "<td>{}<br><span class=small>MSE {}, {} runs</span></td>",
                    f(x.relmse),
                    f(x.mse),
                    x.runs
                ),
            };
        }
        o += "</tr>";
    }
    o + "</table>"
}
