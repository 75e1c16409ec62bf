//! Helpers shared by the end-to-end tests of the `lumis` binary.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Duration;

/// Runs `lumis` with `args` in `dir` and waits for it.
pub fn lumis(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lumis"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run lumis")
}

/// Starts `lumis` with `args` in `dir`, sends SIGINT after `after`, and
/// returns what it printed and its status.
pub fn lumis_interrupted(dir: &Path, args: &[&str], after: Duration) -> Output {
    let child = Command::new(env!("CARGO_BIN_EXE_lumis"))
        .args(args)
        .current_dir(dir)
        .stderr(Stdio::piped())
        .spawn()
        .expect("run lumis");
    std::thread::sleep(after);
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    child.wait_with_output().unwrap()
}

/// A fresh empty folder `lumis-<suite>-<name>-<pid>` in the temp dir,
/// removed when the test passes (kept for a look when it fails).
pub fn temp_dir(suite: &str, name: &str) -> TempDir {
    let d = std::env::temp_dir().join(format!("lumis-{suite}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    TempDir(d)
}

pub struct TempDir(PathBuf);

impl std::ops::Deref for TempDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for TempDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

/// Runs `lumis` with `args` in `dir`, its stdout a pipe that nobody reads
/// any more (as `lumis ... | head -3` once `head` is done).
pub fn lumis_to_closed_pipe(dir: &Path, args: &[&str]) -> Output {
    let mut reader = Command::new("true")
        .stdin(Stdio::piped())
        .spawn()
        .expect("run true");
    let pipe = reader.stdin.take().unwrap();
    reader.wait().unwrap();
    Command::new(env!("CARGO_BIN_EXE_lumis"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::from(pipe))
        .output()
        .expect("run lumis")
}
