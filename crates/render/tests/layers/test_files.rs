//! Every integration-test file of every workspace crate is compiled. The
//! crates list their test binaries (`autotests = false`, `[[test]]` in
//! Cargo.toml: one binary per crate whose modules are the files beside
//! its `tests/main.rs`), so a file neither listed nor declared as a module
//! would never be built or run, and nothing would say so.

use super::crates;
use std::collections::BTreeSet;
use std::path::Path;

/// The `path = "..."` values of a manifest's `[[test]]` tables.
fn listed_tests(manifest: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_test = false;
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            in_test = line == "[[test]]";
        } else if let Some(v) = line.strip_prefix("path").filter(|_| in_test) {
            let v = v.trim_start().trim_start_matches('=').trim();
            out.push(v.trim_matches('"').to_string());
        }
    }
    out
}

/// `NAME` of every `mod NAME;` line of a test binary's root file.
fn declared_modules(root: &Path) -> BTreeSet<String> {
    let text = std::fs::read_to_string(root).unwrap();
    let names = text.lines().filter_map(|l| {
        let l = l.trim();
        l.strip_prefix("mod ")?
            .strip_suffix(';')
            .map(str::to_string)
    });
    names.collect()
}

#[test]
fn every_test_file_is_a_test_binary_or_one_of_its_modules() {
    for (name, src) in crates() {
        let dir = src.parent().unwrap();
        let tests = dir.join("tests");
        if !tests.is_dir() {
            continue;
        }
        let manifest = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap();
        let listed = listed_tests(&manifest);
        // Modules of the binaries rooted in tests/ itself.
        let mut modules = BTreeSet::new();
        for p in &listed {
            let root = dir.join(p);
            if root.parent() == Some(tests.as_path()) {
                modules.extend(declared_modules(&root));
            }
        }
        for entry in std::fs::read_dir(&tests).unwrap() {
            let path = entry.unwrap().path();
            let file = path.file_name().unwrap().to_string_lossy().into_owned();
            let (stem, rel) = match path.extension() {
                Some(e) if e == "rs" => (
                    file.trim_end_matches(".rs").to_string(),
                    format!("tests/{file}"),
                ),
                // A folder of Rust: a binary's root (`main.rs`) or a module (`mod.rs`).
                None if path.join("main.rs").is_file() || path.join("mod.rs").is_file() => {
                    (file.clone(), format!("tests/{file}/main.rs"))
                }
                _ => continue,
            };
            let built = listed.contains(&rel) || modules.contains(&stem);
            assert!(
                built,
                "{name}: tests/{file} is neither a [[test]] in Cargo.toml nor a module of one (`mod {stem};`)"
            );
        }
    }
}
