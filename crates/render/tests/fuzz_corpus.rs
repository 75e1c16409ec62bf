//! Replays the fuzz corpus (`fuzz/corpus/<target>/*`, inputs the fuzzers
//! found interesting, crashes among them once fixed) through the fuzz
//! targets' own entry points: errors are fine, panics are not.

#[path = "../../../fuzz/entry.rs"]
mod entry;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

#[test]
fn corpus_replays_without_panics() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/corpus");
    let mut count = 0;
    let mut panics = Vec::new();
    for dir in std::fs::read_dir(&root).expect("fuzz/corpus") {
        let dir = dir.unwrap().path();
        let target = dir.file_name().unwrap().to_string_lossy().to_string();
        let run = entry::by_name(&target)
            .unwrap_or_else(|| panic!("corpus folder `{target}` has no entry point"));
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|f| f.unwrap().path())
            .collect();
        files.sort();
        for f in files {
            let data = std::fs::read(&f).unwrap();
            if catch_unwind(AssertUnwindSafe(|| run(&data))).is_err() {
                panics.push(f.display().to_string());
            }
            count += 1;
        }
    }
    assert!(count >= 20, "only {count} corpus files");
    assert!(panics.is_empty(), "panicked on: {panics:#?}");
    eprintln!("replayed {count} corpus inputs");
}
