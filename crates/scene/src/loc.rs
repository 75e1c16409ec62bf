//! Source locations and diagnostics (errors and warnings) with a caret display.

use std::fmt;
use std::sync::Arc;

/// One scene file's text, shared by every location inside it.
#[derive(Debug, Default)]
pub struct SourceFile {
    pub path: String,
    pub text: String,
}

impl SourceFile {
    pub fn new(path: impl Into<String>, text: impl Into<String>) -> Arc<SourceFile> {
        Arc::new(SourceFile {
            path: path.into(),
            text: text.into(),
        })
    }

    /// The text of 1-based line `line`, without its line ending.
    pub fn line_text(&self, line: u32) -> Option<&str> {
        if line == 0 {
            return None;
        }
        self.text
            .split('\n')
            .nth(line as usize - 1)
            .map(|l| l.strip_suffix('\r').unwrap_or(l))
    }
}

/// A place in a source file: 1-based line and column (in characters) and the
/// length of the token there, in characters.
#[derive(Clone)]
pub struct Loc {
    pub file: Arc<SourceFile>,
    pub line: u32,
    pub col: u32,
    pub len: u32,
}

impl Loc {
    /// Location of built-in defaults: an empty file, line 0.
    pub fn none() -> Loc {
        Loc {
            file: Arc::new(SourceFile::default()),
            line: 0,
            col: 0,
            len: 0,
        }
    }

    pub fn is_none(&self) -> bool {
        self.line == 0
    }
}

impl fmt::Debug for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file.path, self.line, self.col)
    }
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file.path, self.line, self.col)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
        })
    }
}

/// An error or warning, optionally tied to a location, with an optional hint.
#[derive(Clone, Debug)]
pub struct Diagnostic {
    pub severity: Severity,
    pub loc: Option<Loc>,
    pub message: String,
    pub help: Option<String>,
}

impl Diagnostic {
    pub fn error(loc: &Loc, msg: impl Into<String>) -> Self {
        Self::located(Severity::Error, loc, msg.into())
    }

    pub fn warning(loc: &Loc, msg: impl Into<String>) -> Self {
        Self::located(Severity::Warning, loc, msg.into())
    }

    /// An error with no location (e.g. the top-level file is missing).
    pub fn plain_error(msg: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Error,
            loc: None,
            message: msg.into(),
            help: None,
        }
    }

    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    fn located(severity: Severity, loc: &Loc, message: String) -> Self {
        Diagnostic {
            severity,
            loc: if loc.is_none() {
                None
            } else {
                Some(loc.clone())
            },
            message,
            help: None,
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Some(loc) = &self.loc else {
            write!(f, "{}: {}", self.severity, self.message)?;
            if let Some(h) = &self.help {
                write!(f, "\n   = help: {h}")?;
            }
            return Ok(());
        };
        write!(f, "{loc}: {}: {}", self.severity, self.message)?;
        let width = loc.line.to_string().len().max(4) + 1;
        if let Some(src) = loc.file.line_text(loc.line) {
            write!(f, "\n{:>width$} | {}", loc.line, src)?;
            // Pad with the source's own tabs so the caret lines up.
            let pad: String = src
                .chars()
                .take(loc.col.saturating_sub(1) as usize)
                .map(|c| if c == '\t' { '\t' } else { ' ' })
                .collect();
            let carets = "^".repeat(loc.len.max(1) as usize);
            write!(f, "\n{:>width$} | {pad}{carets}", "")?;
        }
        if let Some(h) = &self.help {
            write!(f, "\n{:>w$}= help: {h}", "", w = width - 2)?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostic {}

/// Levenshtein distance between two strings, in characters.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        cur[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

/// The candidate nearest to `word` within edit distance `max`, if any.
pub fn suggest<'a>(word: &str, candidates: &[&'a str], max: usize) -> Option<&'a str> {
    candidates
        .iter()
        .map(|c| (edit_distance(word, c), *c))
        .filter(|(d, _)| *d <= max)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn loc(text: &str, line: u32, col: u32, len: u32) -> Loc {
        Loc {
            file: SourceFile::new("scene.pbrt", text),
            line,
            col,
            len,
        }
    }

    #[test]
    fn display_has_location_source_and_caret() {
        let l = loc("Shape \"sphere\"\n  \"flaot radius\" 1\n", 2, 3, 14);
        let d = Diagnostic::error(&l, "unknown type").with_help("did you mean `float`?");
        let s = d.to_string();
        assert!(
            s.starts_with("scene.pbrt:2:3: error: unknown type\n"),
            "{s}"
        );
        assert!(s.contains("    2 |   \"flaot radius\" 1\n"), "{s}");
        assert!(s.contains("      |   ^^^^^^^^^^^^^^\n"), "{s}");
        assert!(s.ends_with("   = help: did you mean `float`?"), "{s}");
    }

    #[test]
    fn caret_follows_tabs() {
        let l = loc("\tShape x", 1, 2, 5);
        let s = Diagnostic::warning(&l, "w").to_string();
        assert!(s.contains("| \t^^^^^"), "{s}");
        assert!(s.contains("warning: w"));
    }

    #[test]
    fn plain_and_none_locations() {
        let s = Diagnostic::plain_error("no file").to_string();
        assert_eq!(s, "error: no file");
        let d = Diagnostic::error(&Loc::none(), "built-in");
        assert!(d.loc.is_none());
    }

    #[test]
    fn edit_distance_and_suggest() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("same", "same"), 0);
        assert_eq!(
            suggest("reflectence", &["reflectance", "roughness"], 2),
            Some("reflectance")
        );
        assert_eq!(suggest("zzz", &["reflectance"], 2), None);
    }
}
