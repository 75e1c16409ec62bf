//! The self-contained `index.html`: inline CSS, inline SVG plots, images by
//! relative path, no scripts.

use super::config::{Budget, Config};
use super::fit;
use super::plot::{self, Series};
use super::store::{RunResult, Summary};

/// Per-scene facts for the report.
pub struct SceneInfo {
    pub reference_png: String,
    /// The reference's `lumis:spp` and `lumis:command` (EXR header), if present.
    pub reference_spp: Option<String>,
    pub reference_command: Option<String>,
    pub exposure: f32,
}

/// Machine and timing facts, printed at the top.
pub struct Context {
    pub machine: String,
    pub load_before: String,
    pub load_after: String,
    pub started: String,
    pub finished: String,
    pub command: String,
    pub planned: usize,
    pub summary: Summary,
}

pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

const CSS: &str = "body{font-family:sans-serif;margin:1.5em;max-width:1400px;color:#222}\
h2{margin-top:2em;border-bottom:1px solid #ccc}\
table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #ccc;padding:3px 7px;text-align:right}\
th{background:#f3f3f3}td.best{background:#c8efc8;font-weight:bold}\
.grid td{text-align:center;vertical-align:top;font-size:11px}.grid img{image-rendering:pixelated;width:160px;display:block}\
.ref img{image-rendering:pixelated;width:256px}.small{color:#666;font-size:12px}\
.row{display:flex;flex-wrap:wrap;gap:2em;align-items:flex-start}";

fn find<'a>(rs: &'a [RunResult], scene: &str, setting: &str, budget: &str) -> Vec<&'a RunResult> {
    rs.iter()
        .filter(|r| r.scene == scene && r.setting == setting && r.budget == budget)
        .collect()
}

/// A table of `metric` (mean over seeds, min-max under it): rows budgets,
/// columns settings, the lowest mean of each row highlighted.
fn metric_table(c: &Config, rs: &[RunResult], scene: &str, metric: &str, label: &str) -> String {
    let mut o = format!("<table><tr><th>{label}</th>");
    for s in &c.settings {
        o += &format!("<th>{}</th>", esc(&s.name));
    }
    o += "</tr>";
    for b in c.budgets() {
        let bl = b.label();
        // Per setting: mean, min, max, mean spp, mean seconds.
        let cells: Vec<Option<[f64; 5]>> = c
            .settings
            .iter()
            .map(|s| {
                let v: Vec<&RunResult> = find(rs, scene, &s.name, &bl);
                if v.is_empty() {
                    return None;
                }
                let m: Vec<f64> = v.iter().map(|r| r.metric(metric)).collect();
                let mean = m.iter().sum::<f64>() / m.len() as f64;
                let spp = v.iter().map(|r| r.spp as f64).sum::<f64>() / v.len() as f64;
                let secs = v.iter().map(|r| r.seconds).sum::<f64>() / v.len() as f64;
                let (lo, hi) = m
                    .iter()
                    .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
                Some([mean, lo, hi, spp, secs])
            })
            .collect();
        let best = cells
            .iter()
            .flatten()
            .map(|c| c[0])
            .fold(f64::INFINITY, f64::min);
        let name = match b {
            Budget::Time(t) => format!("{t} s"),
            Budget::Spp(n) => format!("{n} spp"),
        };
        o += &format!("<tr><th>{name}</th>");
        for cell in cells {
            o += &match cell {
                None => "<td>–</td>".to_string(),
                Some([m, lo, hi, spp, secs]) => format!(
                    "<td{}>{m:.3e}<br><span class=small>{lo:.2e}–{hi:.2e}, {spp:.0} spp, {secs:.2} s</span></td>",
                    if m == best { " class=best" } else { "" }
                ),
            };
        }
        o += "</tr>";
    }
    o + "</table>"
}

fn shown(c: &Config, r: &RunResult) -> bool {
    let first_seed = r.seed == c.seeds[0];
    let largest = c.budgets().last().map(|b| b.label()) == Some(r.budget.clone());
    match c.show_images.as_str() {
        "first-seed" => first_seed,
        "largest-budget" => first_seed && largest,
        _ => true,
    }
}

/// Image files of the finished runs that the report shows (relative paths).
pub fn shown_files(c: &Config, rs: &[RunResult]) -> Vec<String> {
    rs.iter()
        .filter(|r| shown(c, r))
        .flat_map(|r| [r.png.clone(), r.heatmap.clone()])
        .collect()
}

fn image_grid(c: &Config, rs: &[RunResult], scene: &str) -> String {
    let mut o = String::from("<table class=grid>");
    for s in &c.settings {
        let runs: Vec<&RunResult> = rs
            .iter()
            .filter(|r| r.scene == scene && r.setting == s.name && shown(c, r))
            .collect();
        if runs.is_empty() {
            continue;
        }
        o += &format!("<tr><th>{}</th>", esc(&s.name));
        for r in runs {
            o += &format!(
                "<td><img src=\"{}\" alt=\"{}\"><img src=\"{}\" alt=\"error map\">{} seed {}: {} spp, {:.2} s<br>relMSE {:.2e}</td>",
                esc(&r.png),
                esc(&r.id),
                esc(&r.heatmap),
                esc(&r.budget),
                r.seed,
                r.spp,
                r.seconds,
                r.relmse
            );
        }
        o += "</tr>";
    }
    o + "</table>"
}

fn plot_for(c: &Config, rs: &[RunResult], scene: &str, metric: &str, label: &str) -> String {
    let series: Vec<Series> = c
        .settings
        .iter()
        .enumerate()
        .map(|(i, s)| Series {
            name: s.name.clone(),
            colour: plot::COLOURS[i % plot::COLOURS.len()],
            groups: c
                .budgets()
                .iter()
                .map(|b| {
                    find(rs, scene, &s.name, &b.label())
                        .iter()
                        .map(|r| (r.seconds, r.metric(metric)))
                        .collect()
                })
                .collect(),
            fit: fit::metric_fit(
                rs.iter()
                    .filter(|r| r.scene == scene && r.setting == s.name),
                metric,
            ),
        })
        .collect();
    plot::svg(&format!("{scene}: {label} vs time"), label, &series)
}

pub fn html(c: &Config, rs: &[RunResult], info: &[SceneInfo], ctx: &Context) -> String {
    let heat = match c.heatmap.as_str() {
        "abs" | "absolute" => "absolute error |t−r| per pixel (channel mean)",
        _ => "relative squared error (t−r)²/(r²+0.01) per pixel (channel mean; its image mean is relMSE)",
    };
    let mut o = format!(
        "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>{t}</title><style>{CSS}</style></head><body><h1>{t}</h1>",
        t = esc(&c.title)
    );
    o += &format!(
        "<p>{} of {} runs finished. Machine: {}. Load average (1, 5, 15 min) before: {}; after: {}. Started {}, finished {}.<br>Command: <code>{}</code></p>",
        rs.len(),
        ctx.planned,
        esc(&ctx.machine),
        esc(&ctx.load_before),
        esc(&ctx.load_after),
        esc(&ctx.started),
        esc(&ctx.finished),
        esc(&ctx.command)
    );
    o += &format!(
        "<p class=small>Budgets are wall-clock seconds including photon tracing and map building (scene loading excluded); a render stops after the last whole 1-spp pass that fits and always does at least one pass, so the measured time (plot x axis) can exceed the budget. Timings are noisy when the machine is shared. Metrics: mean over seeds in each cell, min–max and mean spp and seconds under it; the lowest mean of each row is highlighted. Heatmaps: {heat}, log scale {:.0e} … {:.0e} (viridis), the same for every run. Images: tone-mapped PNG, the same exposure across a scene; full runs in <a href=\"metrics.csv\">metrics.csv</a> and <a href=\"metrics.json\">metrics.json</a>.</p>",
        c.heatmap_range[0], c.heatmap_range[1]
    );
    o += &super::summary::html(c, &ctx.summary);
    for (sc, inf) in c.scenes.iter().zip(info) {
        o += &format!("<h2>{}</h2>", esc(&sc.name));
        o += &format!(
            "<div class=row><div class=ref><img src=\"{}\" alt=\"reference\"><br><span class=small>Reference ({} spp), exposure {:+.1} stops{}<br><code>{}</code></span></div>",
            esc(&inf.reference_png),
            esc(inf.reference_spp.as_deref().unwrap_or("?")),
            inf.exposure,
            sc.mask
                .map(|m| format!(", metrics over x {}–{}, y {}–{}", m[0], m[1], m[2], m[3]))
                .unwrap_or_default(),
            esc(inf.reference_command.as_deref().unwrap_or(""))
        );
        o += &plot_for(c, rs, &sc.name, "relmse", "relMSE");
        o += &plot_for(c, rs, &sc.name, "mse", "MSE");
        o += "</div>";
        o += &metric_table(c, rs, &sc.name, "relmse", "relMSE");
        o += &metric_table(c, rs, &sc.name, "mse", "MSE");
        o += &image_grid(c, rs, &sc.name);
    }
    o + "</body></html>\n"
}
