//! `lumis render`'s arguments as strings → [`RenderFlags`], for the front
//! ends that do not have the CLI's parser (a study run's flags in Python).
//! Only the flags that make a study run's job are known here (its
//! settings' and scenes' flags, budget, seed, threads, output); the
//! output-only flags (`-q`, `-v`, `--stats`) are ignored. A flag given
//! twice takes its last value.

use super::{integrator_params, IntegratorParam, RenderFlags};
use std::path::PathBuf;

/// The flags of `lumis render` that take no value here.
const IGNORED: &[&str] = &["-q", "--quiet", "-v", "--verbose", "--stats"];

/// The flags of [`OWN`] that take `true` or `false`, or nothing for true.
const OWN_BOOLS: &[&str] = &["--filter-splat"];

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
    "--filter-splat",
    "--accel",
];

impl RenderFlags {
    /// The flags `args` (the arguments of `lumis render`) give; errors
    /// start with `bad flags:`.
    pub fn parse(args: &[String]) -> Result<RenderFlags, String> {
        let table = integrator_params();
        let (scene, values) = collect(args, &table)?;
        let get = |f: &str| {
            values
                .iter()
                .rev()
                .find(|(k, _)| k == f)
                .map(|(_, v)| v.as_str())
        };
        let f = RenderFlags {
            scene,
            seed: parse(get("--seed"), "--seed")?.unwrap_or(0),
            spp: parse(get("--spp"), "--spp")?,
            time: parse(get("--time"), "--time")?,
            threads: parse(get("--threads"), "--threads")?,
            clamp: parse(get("--clamp"), "--clamp")?,
            filter_splat: parse(get("--filter-splat"), "--filter-splat")?,
            exposure: parse(get("--exposure"), "--exposure")?.unwrap_or(0.0),
            accel: get("--accel").map(String::from),
            output: get("--output").map(PathBuf::from),
            resolution: get("--resolution").map(resolution).transpose()?,
            crop: get("--crop").map(crop).transpose()?,
            sampler: get("--sampler").map(String::from),
            integrator: get("--integrator").map(String::from),
            maxdepth: parse(get("--maxdepth"), "--maxdepth")?,
            params: table
                .iter()
                .filter_map(|p| get(&p.flag()).map(|v| (p.spec, v.to_string())))
                .collect(),
            ..RenderFlags::default()
        };
        for (k, _) in &values {
            if !OWN.contains(&k.as_str()) && !table.iter().any(|p| *k == p.flag()) {
                return Err(format!("bad flags: unknown flag `{k}`"));
            }
        }
        Ok(f)
    }
}

/// Each flag given with its value as typed (`-o` as `--output`), in order.
type Values = Vec<(String, String)>;

/// The scene, and the flags' values.
fn collect(
    args: &[String],
    table: &[IntegratorParam],
) -> Result<(Option<PathBuf>, Values), String> {
    let mut scene = None;
    let mut values = Vec::new();
    let mut it = args.iter().peekable();
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
        let param = table.iter().find(|p| flag == p.flag());
        let value = match (inline, param) {
            (Some(v), _) => v,
            // `--aim-caustics` alone means true.
            (None, p)
                if p.is_some_and(|p| p.spec.ty == "bool") || OWN_BOOLS.contains(&flag.as_str()) =>
            {
                match it.peek() {
                    Some(v) if *v == "true" || *v == "false" => it.next().unwrap().clone(),
                    _ => "true".into(),
                }
            }
            (None, _) => it
                .next()
                .ok_or_else(|| format!("bad flags: `{flag}` needs a value"))?
                .clone(),
        };
        values.push((flag, value));
    }
    Ok((scene, values))
}

fn parse<T: std::str::FromStr>(v: Option<&str>, flag: &str) -> Result<Option<T>, String> {
    v.map(|v| {
        v.trim()
            .parse()
            .map_err(|_| format!("bad flags: `{flag} {v}` is not a valid value"))
    })
    .transpose()
}

fn resolution(r: &str) -> Result<(u32, u32), String> {
    let bad = || format!("bad flags: --resolution expects WxH, found `{r}`");
    let (w, h) = r.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    Ok((w, h))
}

fn crop(c: &str) -> Result<[f32; 4], String> {
    let bad = || format!("bad flags: --crop expects x0,x1,y0,y1, found `{c}`");
    let v: Vec<f32> = c
        .split(',')
        .map(|t| t.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad())?;
    let [x0, x1, y0, y1] = v[..] else {
        return Err(bad());
    };
    Ok([x0, x1, y0, y1])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(a: &[&str]) -> Vec<String> {
        a.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn flags_of_every_kind() {
        let f = RenderFlags::parse(&args(&[
            "s.pbrt",
            "-q",
            "--spp",
            "2",
            "--threads=1",
            "--resolution",
            "24x16",
            "--crop",
            "0.25,0.75,0,1",
            "--filter-splat",
            "--integrator",
            "photon",
            "--progressive",
            "false",
            "--radiance-photons",
            "--caustics",
            "mis",
            "--seed",
            "3",
            "-o",
            "a.pfm",
            "--stats",
            "--photons",
            "5",
            "--photons",
            "7",
        ]))
        .unwrap();
        let given: Vec<(&str, &str)> = f
            .params
            .iter()
            .map(|(s, v)| (s.words, v.as_str()))
            .collect();
        let want = RenderFlags {
            scene: Some("s.pbrt".into()),
            output: Some("a.pfm".into()),
            spp: Some(2),
            threads: Some(1),
            seed: 3,
            resolution: Some((24, 16)),
            crop: Some([0.25, 0.75, 0.0, 1.0]),
            filter_splat: Some(true),
            integrator: Some("photon".into()),
            params: f.params.clone(),
            ..RenderFlags::default()
        };
        assert_eq!(f, want);
        // Table order; the last of a repeated flag.
        assert_eq!(
            given,
            [
                ("photons", "7"),
                ("caustics", "mis"),
                ("radiance-photons", "true"),
                ("progressive", "false"),
            ]
        );
    }

    #[test]
    fn unknown_incomplete_and_bad_flags_are_refused() {
        let err = |a: &[&str]| RenderFlags::parse(&args(a)).unwrap_err();
        assert_eq!(
            err(&["--no-such", "1"]),
            "bad flags: unknown flag `--no-such`"
        );
        assert_eq!(err(&["--spp"]), "bad flags: `--spp` needs a value");
        assert!(err(&["--resolution", "12"]).contains("--resolution expects WxH"));
        assert!(err(&["--crop", "0,1,0"]).contains("--crop expects x0,x1,y0,y1"));
        assert!(err(&["--spp", "x"]).contains("`--spp x` is not a valid value"));
        assert!(err(&["a.pbrt", "b.pbrt"]).contains("a second scene `b.pbrt`"));
        // `--filter-splat` takes a value only if it is one.
        let f = |a: &[&str]| RenderFlags::parse(&args(a)).unwrap();
        assert_eq!(f(&["--filter-splat", "false"]).filter_splat, Some(false));
        let g = f(&["--filter-splat", "s.pbrt"]);
        assert_eq!(
            (g.filter_splat, g.scene),
            (Some(true), Some("s.pbrt".into()))
        );
        // Flags of the CLI that a study run does not give.
        assert!(err(&["--checkpoint", "c"]).contains("unknown flag"));
    }
}
