//! External settings' command lines: placeholders, finding the program, and
//! running it timed (wall clock, start to exit) and cancellable.

use super::error::{bail, Result};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// The placeholders an external command may use.
pub const PLACEHOLDERS: [&str; 6] = ["config_dir", "scene", "out", "spp", "seed", "threads"];

/// `arg` with each `{name}` (letters, digits, `_`) replaced by `f(name)`, or
/// kept where `f` gives None; other braces are plain text.
fn expand(arg: &str, mut f: impl FnMut(&str) -> Option<String>) -> String {
    let mut out = String::new();
    let mut rest = arg;
    while let Some(open) = rest.find('{') {
        out += &rest[..open];
        let after = &rest[open + 1..];
        let name = after.find('}').map(|close| &after[..close]);
        match name
            .filter(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
        {
            Some(n) => {
                out += &f(n).unwrap_or_else(|| format!("{{{n}}}"));
                rest = &after[n.len() + 1..];
            }
            None => {
                out.push('{');
                rest = after;
            }
        }
    }
    out + rest
}

/// The placeholder names in `arg`, known or not.
pub fn placeholders(arg: &str) -> Vec<String> {
    let mut v = Vec::new();
    expand(arg, |n| {
        v.push(n.to_string());
        None
    });
    v
}

/// Placeholder values; None leaves the placeholder in place.
#[derive(Clone, Debug, Default)]
pub struct Vars {
    pub config_dir: String,
    pub scene: String,
    pub threads: String,
    pub spp: Option<String>,
    pub seed: Option<String>,
    pub out: Option<String>,
}

impl Vars {
    fn get(&self, name: &str) -> Option<String> {
        match name {
            "config_dir" => Some(self.config_dir.clone()),
            "scene" => Some(self.scene.clone()),
            "threads" => Some(self.threads.clone()),
            "spp" => self.spp.clone(),
            "seed" => self.seed.clone(),
            "out" => self.out.clone(),
            _ => None,
        }
    }
}

/// The command with its placeholders substituted.
pub fn substitute(cmd: &[String], v: &Vars) -> Vec<String> {
    cmd.iter().map(|a| expand(a, |n| v.get(n))).collect()
}

/// The program a command starts: a path if it has a `/`, else looked up in
/// `PATH`; None if there is no such file.
pub fn find_program(p: &str) -> Option<PathBuf> {
    if p.contains('/') {
        return Path::new(p).is_file().then(|| PathBuf::from(p));
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join(p))
        .find(|f| f.is_file())
}

/// The command as one shell-like line, for messages.
pub fn show(cmd: &[String]) -> String {
    cmd.iter()
        .map(|a| {
            if a.is_empty() || a.contains([' ', '"', '\'']) {
                format!("'{a}'")
            } else {
                a.clone()
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Runs `cmd` in `dir` with its output in `log`; its wall seconds, or None
/// if `cancel` was set (the process is then killed). A failing command is
/// an error that quotes the end of its output.
pub fn run_timed(
    cmd: &[String],
    dir: &Path,
    log: &Path,
    cancel: &AtomicBool,
) -> Result<Option<f64>> {
    let file =
        std::fs::File::create(log).map_err(|e| format!("creating {}: {e}", log.display()))?;
    let start = Instant::now();
    let mut child = Command::new(&cmd[0])
        .args(&cmd[1..])
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(file.try_clone()?)
        .stderr(file)
        .spawn()
        .map_err(|e| format!("cannot start `{}`: {e}", cmd[0]))?;
    let status = loop {
        if let Some(s) = child.try_wait()? {
            break s;
        }
        if cancel.load(Ordering::SeqCst) {
            let _ = child.kill();
            let _ = child.wait();
            return Ok(None);
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let seconds = start.elapsed().as_secs_f64();
    if !status.success() {
        if cancel.load(Ordering::SeqCst) {
            return Ok(None);
        }
        let text = std::fs::read_to_string(log).unwrap_or_default();
        let lines: Vec<&str> = text.lines().collect();
        let tail = lines[lines.len().saturating_sub(12)..].join("\n");
        bail!(
            "`{}` failed ({status}); the end of its output ({}):\n{tail}",
            show(cmd),
            log.display()
        );
    }
    Ok(Some(seconds))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholders_are_substituted_or_kept() {
        let cmd: Vec<String> = [
            "{config_dir}/r",
            "--spp={spp}",
            "{seed}",
            "{out}",
            "{x}",
            "{ a}",
            "{",
            "}{spp",
        ]
        .map(String::from)
        .to_vec();
        let v = Vars {
            config_dir: "/c".into(),
            spp: Some("7".into()),
            seed: None,
            out: Some("o.exr".into()),
            ..Vars::default()
        };
        assert_eq!(
            substitute(&cmd, &v),
            ["/c/r", "--spp=7", "{seed}", "o.exr", "{x}", "{ a}", "{", "}{spp"]
        );
        assert_eq!(placeholders("{a}-{b_2}{}{c"), ["a", "b_2"]);
    }

    #[test]
    fn programs_are_found_by_path_or_in_path() {
        assert!(find_program("sh").is_some());
        assert!(find_program("/bin/sh").is_some() || find_program("/usr/bin/sh").is_some());
        assert_eq!(find_program("/no/such/program"), None);
        assert_eq!(find_program("lumis-no-such-program"), None);
    }

    #[test]
    fn a_failing_command_quotes_its_output() {
        let d = std::env::temp_dir();
        let log = d.join(format!("lumis-cmd-{}.log", std::process::id()));
        let no = AtomicBool::new(false);
        let sh = |s: &str| ["sh", "-c", s].map(String::from).to_vec();
        let t = run_timed(&sh("sleep 0.2"), &d, &log, &no).unwrap().unwrap();
        assert!((0.2..5.0).contains(&t), "{t}");
        let e = run_timed(&sh("echo oops; exit 3"), &d, &log, &no)
            .unwrap_err()
            .to_string();
        assert!(e.contains("exit status: 3") && e.contains("oops"), "{e}");
        let yes = AtomicBool::new(true);
        assert_eq!(run_timed(&sh("sleep 5"), &d, &log, &yes).unwrap(), None);
        std::fs::remove_file(&log).unwrap();
    }
}
