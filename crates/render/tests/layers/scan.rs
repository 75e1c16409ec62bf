//! Reads which top-level modules of its crate a source file refers to:
//! `crate::name`, each first name in `crate::{a, b::c}`, and `super::`
//! chains that climb to the crate root (`super::super::name` from a file
//! two modules deep). Comments, strings and `$crate` (macros) are skipped;
//! inline `mod name { .. }` blocks count as one more level for `super`.
//! Code under `#[cfg(test)]` is read like any other code.

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    /// `::`
    Path,
    Open,
    Close,
    Comma,
    Other(char),
}

/// A reference to `target` (a name right below the crate root) on `line`.
#[derive(Clone, Debug, PartialEq)]
pub struct Ref {
    pub target: String,
    pub line: usize,
}

fn tokens(src: &str) -> Vec<(Tok, usize)> {
    let b: Vec<char> = src.chars().collect();
    let at = |i: usize| b.get(i).copied().unwrap_or('\0');
    let (mut i, mut line, mut out) = (0, 1, Vec::new());
    // Skips to just past the closing `"` (with `hashes` `#`s) of a string.
    let skip_string = |mut i: usize, hashes: usize, raw: bool, line: &mut usize| {
        while i < b.len() {
            match b[i] {
                '\\' if !raw => i += 1,
                '\n' => *line += 1,
                '"' if (1..=hashes).all(|k| at(i + k) == '#') => return i + 1 + hashes,
                _ => {}
            }
            i += 1;
        }
        i
    };
    while i < b.len() {
        let c = b[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '/' && at(i + 1) == '/' {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 1;
                } else if b[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 1;
                } else if b[i] == '\n' {
                    line += 1;
                }
                i += 1;
                if depth == 0 {
                    break;
                }
            }
        } else if c == '"' {
            i = skip_string(i + 1, 0, false, &mut line);
        } else if (c == 'r' || (c == 'b' && at(i + 1) == 'r'))
            && matches!(at(i + 1 + (c == 'b') as usize), '"' | '#')
            && {
                let s = i + 1 + (c == 'b') as usize;
                let h = (s..).take_while(|&k| at(k) == '#').count();
                at(s + h) == '"'
            }
        {
            let s = i + 1 + (c == 'b') as usize;
            let h = (s..).take_while(|&k| at(k) == '#').count();
            i = skip_string(s + h + 1, h, true, &mut line);
        } else if c == 'b' && at(i + 1) == '"' {
            i = skip_string(i + 2, 0, false, &mut line);
        } else if c == '\'' {
            // A char literal ('x', '\n', '\u{..}'), or else a lifetime.
            if at(i + 1) == '\\' {
                i += 2;
                while i < b.len() && b[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if at(i + 2) == '\'' {
                i += 3;
            } else {
                i += 1;
            }
        } else if c.is_alphanumeric() || c == '_' {
            let s = i;
            while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_') {
                i += 1;
            }
            let word: String = b[s..i].iter().collect();
            out.push((Tok::Ident(word), line));
        } else if c == ':' && at(i + 1) == ':' {
            out.push((Tok::Path, line));
            i += 2;
        } else {
            out.push((
                match c {
                    '{' => Tok::Open,
                    '}' => Tok::Close,
                    ',' => Tok::Comma,
                    _ => Tok::Other(c),
                },
                line,
            ));
            i += 1;
        }
    }
    out
}

fn is(t: Option<&(Tok, usize)>, want: &Tok) -> bool {
    t.is_some_and(|(t, _)| t == want)
}

fn ident(t: Option<&(Tok, usize)>) -> Option<&str> {
    match t {
        Some((Tok::Ident(s), _)) => Some(s),
        _ => None,
    }
}

/// The names right after a path that starts at the crate root, from token
/// `j` on: `name` or every first name in `{a, b::{c}, d}`.
fn root_names(toks: &[(Tok, usize)], j: usize, out: &mut Vec<Ref>) {
    let mut push = |t: &(Tok, usize)| {
        if let Tok::Ident(name) = &t.0 {
            if name != "self" {
                out.push(Ref {
                    target: name.clone(),
                    line: t.1,
                });
            }
        }
    };
    if !is(toks.get(j), &Tok::Open) {
        if let Some(t) = toks.get(j) {
            push(t);
        }
        return;
    }
    let (mut depth, mut k, mut item_start) = (0, j, false);
    while let Some(t) = toks.get(k) {
        match t.0 {
            Tok::Open => {
                depth += 1;
                item_start = depth == 1;
            }
            Tok::Close => {
                depth -= 1;
                if depth == 0 {
                    return;
                }
            }
            Tok::Comma => item_start = depth == 1,
            _ => {
                if item_start {
                    push(t);
                }
                item_start = false;
            }
        }
        k += 1;
    }
}

/// Names right below the crate root that the code of module `path` (its
/// file's module path, e.g. `["light", "area"]` for `light/area.rs`) uses.
pub fn references(src: &str, path: &[String]) -> Vec<Ref> {
    let toks = tokens(src);
    let mut out = Vec::new();
    let mut depth = 0usize;
    // Inline modules open at this point: the brace depth inside each.
    let mut inline: Vec<usize> = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        let prev = i.checked_sub(1).and_then(|p| toks.get(p));
        match &toks[i].0 {
            Tok::Open => depth += 1,
            Tok::Close => {
                if inline.last() == Some(&depth) {
                    inline.pop();
                }
                depth = depth.saturating_sub(1);
            }
            Tok::Ident(k)
                if k == "mod"
                    && ident(toks.get(i + 1)).is_some()
                    && is(toks.get(i + 2), &Tok::Open) =>
            {
                inline.push(depth + 1);
            }
            Tok::Ident(k)
                if k == "crate"
                    && is(toks.get(i + 1), &Tok::Path)
                    && !is(prev, &Tok::Other('$')) =>
            {
                root_names(&toks, i + 2, &mut out);
            }
            Tok::Ident(k) if k == "super" && !is(prev, &Tok::Path) => {
                let mut j = i;
                let mut n = 0;
                while ident(toks.get(j)) == Some("super") && is(toks.get(j + 1), &Tok::Path) {
                    n += 1;
                    j += 2;
                }
                if n > 0 && n == path.len() + inline.len() {
                    root_names(&toks, j, &mut out);
                }
                i = j.max(i + 1);
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

#[test]
fn references_are_read_from_paths_groups_and_super() {
    let src = r##"
//! Uses crate::commented, which is no reference.
use crate::geometry::Ray;
use crate::{light::Light, scene::{Hit, Scene}, self as me};
use super::sibling;
use super::super::texture::Texture;
let s = "crate::in_a_string";
let r = r#"crate::raw"#;
let c = '{';
fn f<'a>(x: &'a str) -> crate::film::Film { $crate::macro_path }
mod tests {
    use super::super::super::camera::Camera;
    use super::*;
}
/* block crate::comment */ let v = crate::accel::Bvh::new();
"##;
    let path = vec!["integrator".to_string(), "photon".to_string()];
    let refs = references(src, &path);
    let names: Vec<(&str, usize)> = refs.iter().map(|r| (r.target.as_str(), r.line)).collect();
    assert_eq!(
        names,
        [
            ("geometry", 3),
            ("light", 4),
            ("scene", 4),
            ("texture", 6),
            ("film", 10),
            ("camera", 12),
            ("accel", 15),
        ]
    );
}
