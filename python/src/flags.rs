//! A study run's `lumis render` flags as a job, made as the CLI makes one
//! (`crates/cli/src/job.rs`): the same fields, the same overrides in the
//! same order, labelled with their flags. Only the render flags a study
//! gives (its settings' and scenes' flags, budget, seed, threads) are
//! needed here; output-only flags (`-q`, `-v`, `--stats`) are ignored.

use crate::params;
use lumis_render::session::{Accel, Budget, RenderJob};
use lumis_scene::{Overrides, ParamSpec};
use std::path::PathBuf;

/// The flags of `lumis render` that take no value here.
const IGNORED: &[&str] = &["-q", "--quiet", "-v", "--verbose", "--stats"];

/// The job the arguments `args` of `lumis render` describe.
pub fn job_from_flags(args: &[String]) -> Result<RenderJob, String> {
    let mut scene = None;
    let mut values: Vec<(String, String)> = Vec::new();
    let mut it = args.iter().peekable();
    let table = params::all();
    while let Some(a) = it.next() {
        if !a.starts_with('-') {
            if scene.replace(PathBuf::from(a)).is_some() {
                return Err(format!("bad flags: a second scene `{a}`"));
            }
            continue;
        }
        if IGNORED.contains(&a.as_str()) {
            continue;
        }
        let (flag, inline) = match a.split_once('=') {
            Some((f, v)) => (f.to_string(), Some(v.to_string())),
            None => (a.clone(), None),
        };
        let flag = if flag == "-o" {
            "--output".into()
        } else {
            flag
        };
        let spec = table.iter().find(|s| flag == format!("--{}", s.words));
        let value = match (inline, spec) {
            (Some(v), _) => v,
            // `--aim-caustics` alone means true.
            (None, Some(s)) if s.ty == "bool" => match it.peek() {
                Some(v) if *v == "true" || *v == "false" => it.next().unwrap().clone(),
                _ => "true".into(),
            },
            (None, _) => it
                .next()
                .ok_or_else(|| format!("bad flags: `{flag}` needs a value"))?
                .clone(),
        };
        values.push((flag, value));
    }
    let mut job = RenderJob::new(scene);
    let get = |f: &str| values.iter().rev().find(|(k, _)| k == f).map(|(_, v)| v);
    job.seed = parse(get("--seed"), "--seed")?.unwrap_or(0);
    job.budget = Budget {
        spp: parse(get("--spp"), "--spp")?,
        time: parse(get("--time"), "--time")?,
    };
    job.threads = parse(get("--threads"), "--threads")?.unwrap_or(0);
    job.clamp = parse(get("--clamp"), "--clamp")?;
    job.exposure = parse(get("--exposure"), "--exposure")?.unwrap_or(0.0);
    job.accel = match get("--accel").map(String::as_str) {
        None | Some("bvh") => Accel::Bvh,
        Some("embree") => Accel::Embree,
        Some(o) => return Err(format!("unknown --accel `{o}`: expected `bvh` or `embree`")),
    };
    job.outputs = get("--output").map(PathBuf::from).into_iter().collect();
    job.overrides = overrides(&values, &table, &get)?;
    for (f, _) in &values {
        let known =
            OWN.contains(&f.as_str()) || table.iter().any(|s| *f == format!("--{}", s.words));
        if !known {
            return Err(format!("bad flags: unknown flag `{f}`"));
        }
    }
    Ok(job)
}

/// The flags that are the job's fields or scene overrides.
const OWN: &[&str] = &[
    "--output",
    "--spp",
    "--time",
    "--threads",
    "--seed",
    "--integrator",
    "--maxdepth",
    "--resolution",
    "--crop",
    "--exposure",
    "--sampler",
    "--clamp",
    "--accel",
];

fn parse<T: std::str::FromStr>(v: Option<&String>, flag: &str) -> Result<Option<T>, String> {
    v.map(|v| {
        v.trim()
            .parse()
            .map_err(|_| format!("bad flags: `{flag} {v}` is not a valid value"))
    })
    .transpose()
}

/// The overrides, in the CLI's order: resolution, crop, sampler,
/// integrator, maxdepth, then the integrators' parameters in table order.
fn overrides<'a>(
    values: &[(String, String)],
    table: &[&'static ParamSpec],
    get: &dyn Fn(&str) -> Option<&'a String>,
) -> Result<Overrides, String> {
    let mut o = Overrides::default();
    if let Some(r) = get("--resolution") {
        let bad = || format!("bad flags: --resolution expects WxH, found `{r}`");
        let (w, h) = r.split_once(['x', 'X']).ok_or_else(bad)?;
        let w: u32 = w.trim().parse().map_err(|_| bad())?;
        let h: u32 = h.trim().parse().map_err(|_| bad())?;
        o.resolution_from(w, h, "--resolution");
    }
    if let Some(c) = get("--crop") {
        let v: Vec<f32> = c
            .split(',')
            .map(|t| t.trim().parse::<f32>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("bad flags: --crop expects x0,x1,y0,y1, found `{c}`"))?;
        let [x0, x1, y0, y1] = v[..] else {
            return Err(format!(
                "bad flags: --crop expects x0,x1,y0,y1, found `{c}`"
            ));
        };
        o.crop_from([x0, x1, y0, y1], "--crop");
    }
    if let Some(s) = get("--sampler") {
        o.sampler_from(s, "--sampler");
    }
    if let Some(i) = get("--integrator") {
        o.integrator_from(i, "--integrator");
    }
    if let Some(d) = get("--maxdepth") {
        o.max_depth_from(parse(Some(d), "--maxdepth")?.unwrap_or(0), "--maxdepth");
    }
    for s in table {
        let flag = format!("--{}", s.words);
        let Some(v) = values
            .iter()
            .rev()
            .find(|(k, _)| *k == flag)
            .map(|(_, v)| v)
        else {
            continue;
        };
        let value = match s.ty {
            "string" => format!("\"{v}\""),
            "integer" => v.replace(',', " "),
            _ => v.clone(),
        };
        o.param("Integrator", &format!("{} {}", s.ty, s.name), &value, &flag);
    }
    Ok(o)
}
