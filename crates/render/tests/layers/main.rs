//! The module structure of every workspace crate (`crates/*/src`): no
//! import cycles between a crate's top-level modules, and for lumis-render
//! imports only towards the layers below ([`RENDER_LAYERS`]). References
//! are read from the source text (`scan.rs`), tests included; the crate
//! root file (`lib.rs`, `main.rs`) only declares modules and is not a node.

mod graph;
mod scan;

mod test_files;

use graph::{cycles, Graph};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// lumis-render's top-level modules, bottom layer first. A module may use
/// modules of its own layer or the layers below, never above; inside one
/// layer the cycle check keeps the imports one-way.
const RENDER_LAYERS: &[&[&str]] = &[
    &["geometry", "bsdf", "film", "media"],
    &["camera", "image_io", "metrics"],
    &["texture"],
    &["material"],
    &["light"],
    &["accel"],
    &["scene"],
    &["integrator"],
    &["checkpoint"],
    &["load"],
    &["session"],
    &["study"],
];

/// Known edges both checks skip, as (crate folder, from, to, file that
/// makes the edge): each is to be removed, then its entry deleted (a test
/// fails once an entry is no longer needed).
const ALLOWED: &[(&str, &str, &str, &str)] = &[];

/// One reference from a top-level module to another.
struct Site {
    from: String,
    to: String,
    /// Relative to the crate's `src`.
    file: String,
    line: usize,
}

impl Site {
    fn allowed(&self, krate: &str) -> bool {
        ALLOWED.contains(&(krate, &self.from, &self.to, &self.file))
    }
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Every workspace crate's folder name and `src` path.
fn crates() -> Vec<(String, PathBuf)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut out: Vec<(String, PathBuf)> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("Cargo.toml").is_file() && p.join("src").is_dir())
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                p.join("src"),
            )
        })
        .collect();
    out.sort();
    assert!(
        out.len() >= 4,
        "expected the workspace crates in {}",
        root.display()
    );
    out
}

/// A crate's top-level modules and the references between them.
fn crate_sites(src: &Path) -> (BTreeSet<String>, Vec<Site>) {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let rel = |p: &Path| {
        p.strip_prefix(src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/")
    };
    // Module path of each file: `light/area.rs` -> [light, area], `light/mod.rs` -> [light].
    let mut paths = Vec::new();
    for f in &files {
        let r = rel(f);
        if r.starts_with("bin/") || r == "lib.rs" || r == "main.rs" {
            continue;
        }
        let mut path: Vec<String> = r
            .trim_end_matches(".rs")
            .split('/')
            .map(String::from)
            .collect();
        if path.last().is_some_and(|l| l == "mod") {
            path.pop();
        }
        paths.push((f, r, path));
    }
    let modules: BTreeSet<String> = paths.iter().map(|(_, _, p)| p[0].clone()).collect();
    let mut sites = Vec::new();
    for (f, r, path) in &paths {
        let text = std::fs::read_to_string(f).unwrap();
        for re in scan::references(&text, path) {
            if re.target != path[0] && modules.contains(&re.target) {
                sites.push(Site {
                    from: path[0].clone(),
                    to: re.target,
                    file: r.clone(),
                    line: re.line,
                });
            }
        }
    }
    (modules, sites)
}

/// `file:line` of the first references that make the edge `from -> to`.
fn where_(sites: &[Site], from: &str, to: &str) -> String {
    let at: Vec<String> = sites
        .iter()
        .filter(|s| s.from == from && s.to == to)
        .map(|s| format!("{}:{}", s.file, s.line))
        .collect();
    let more = at.len().saturating_sub(4);
    let mut s = at.into_iter().take(4).collect::<Vec<_>>().join(", ");
    if more > 0 {
        s += &format!(" and {more} more");
    }
    s
}

#[test]
fn no_cycles_between_top_level_modules_in_any_crate() {
    let mut problems = Vec::new();
    for (krate, src) in crates() {
        let (modules, sites) = crate_sites(&src);
        let sites: Vec<Site> = sites.into_iter().filter(|s| !s.allowed(&krate)).collect();
        let mut g: Graph = modules
            .iter()
            .map(|m| (m.clone(), BTreeSet::new()))
            .collect();
        for s in &sites {
            g.get_mut(&s.from).unwrap().insert(s.to.clone());
        }
        for cycle in cycles(&g) {
            let mut msg = format!("crates/{krate}: import cycle {}", cycle.join(" -> "));
            for w in cycle.windows(2) {
                msg += &format!(
                    "\n    {} -> {}: {}",
                    w[0],
                    w[1],
                    where_(&sites, &w[0], &w[1])
                );
            }
            problems.push(msg);
        }
    }
    assert!(problems.is_empty(), "\n{}\n", problems.join("\n"));
}

#[test]
fn lumis_render_modules_follow_the_layer_order() {
    let layer: BTreeMap<&str, usize> = RENDER_LAYERS
        .iter()
        .enumerate()
        .flat_map(|(i, l)| l.iter().map(move |m| (*m, i)))
        .collect();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let (modules, sites) = crate_sites(&src);
    let listed: BTreeSet<String> = layer.keys().map(|m| m.to_string()).collect();
    assert_eq!(
        modules, listed,
        "every top-level module of lumis-render has a place in RENDER_LAYERS"
    );
    let mut problems = Vec::new();
    let mut seen = BTreeSet::new();
    for s in sites.iter().filter(|s| !s.allowed("render")) {
        let (a, b) = (layer[s.from.as_str()], layer[s.to.as_str()]);
        if a < b && seen.insert((&s.from, &s.to)) {
            problems.push(format!(
                "upward import: {} (layer {a}) uses {} (layer {b}) at {}",
                s.from,
                s.to,
                where_(&sites, &s.from, &s.to)
            ));
        }
    }
    assert!(problems.is_empty(), "\n{}\n", problems.join("\n"));
}

#[test]
fn every_allowed_edge_is_still_made() {
    let all: BTreeMap<String, Vec<Site>> = crates()
        .into_iter()
        .map(|(k, src)| (k, crate_sites(&src).1))
        .collect();
    for &(krate, from, to, file) in ALLOWED {
        let made = all[krate]
            .iter()
            .any(|s| s.from == from && s.to == to && s.file == file);
        assert!(
            made,
            "crates/{krate}: {file} no longer makes the edge {from} -> {to}: delete it from ALLOWED"
        );
    }
}
