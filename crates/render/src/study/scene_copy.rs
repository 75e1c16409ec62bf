//! A copy of a scene file for another renderer: its `Integrator` directive
//! renamed (parameters kept), and its relative paths made absolute so the
//! copy works from any folder. Relative paths resolve against the top-level
//! file's folder, as lumis and pbrt-v4 resolve them, in included files too.
//!
//! Made absolute: `Include`/`Import` file names, `"string filename"` and
//! `"string lensfile"` values, and `spectrum` values naming an existing file.
//! An included file that needs a change is copied too (`inc<N>-<name>`);
//! one that does not (or is gzip-compressed) is named by its absolute path.

use super::error::{bail, Result};
use lumis_scene::lexer::{tokenize, Token, TokenKind};
use lumis_scene::{Diagnostic, SourceFile};
use std::path::{Path, PathBuf};

const MAX_DEPTH: usize = 32;

struct Copier<'a> {
    base: PathBuf,
    dir: &'a Path,
    integrator: &'a str,
    params: Option<&'a str>,
    copies: usize,
    found_integrator: bool,
    world_begin: Option<Token>,
}

/// Writes the copy of `scene` (and of the included files that need one) into
/// `dir`, and returns the copy's path; `params` (pbrt parameter text) are
/// added to the renamed `Integrator`. Errors: unreadable or unparsable
/// files, and a scene without an `Integrator` directive.
pub fn write_copy(
    scene: &Path,
    dir: &Path,
    integrator: &str,
    params: Option<&str>,
) -> Result<PathBuf> {
    let scene = std::path::absolute(scene)?;
    let base = scene.parent().unwrap_or(Path::new("/")).to_path_buf();
    std::fs::create_dir_all(dir)?;
    let mut c = Copier {
        base,
        dir,
        integrator,
        params,
        copies: 0,
        found_integrator: false,
        world_begin: None,
    };
    let copy = c.file(&scene, 0)?;
    if !c.found_integrator {
        let msg = format!(
            "no `Integrator` directive to rename to `{integrator}` (the setting's `integrator`); add one before WorldBegin"
        );
        return Err(match &c.world_begin {
            Some(t) => Diagnostic::error(&t.loc, msg).to_string().into(),
            None => format!("{}: {msg}", scene.display()).into(),
        });
    }
    Ok(copy)
}

/// `s` as a pbrt string token.
fn quote(s: &str) -> String {
    format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\""))
}

/// The byte range of a token in `text` (locations count characters).
fn span(text: &str, t: &Token) -> std::ops::Range<usize> {
    let line_start: usize = text
        .split_inclusive('\n')
        .take(t.loc.line as usize - 1)
        .map(str::len)
        .sum();
    let line = &text[line_start..];
    let at = |col: usize| line.char_indices().nth(col).map_or(line.len(), |(i, _)| i);
    let c0 = t.loc.col as usize - 1;
    line_start + at(c0)..line_start + at(c0 + t.loc.len as usize)
}

/// Whether a parameter declaration (`"type name"`) holds a file path.
fn is_path_param(decl: &str) -> bool {
    let w: Vec<&str> = decl.split_whitespace().collect();
    matches!(
        w.as_slice(),
        ["string", "filename" | "lensfile"] | ["spectrum", _]
    )
}

impl Copier<'_> {
    fn absolute(&self, p: &str) -> Option<String> {
        let path = Path::new(p);
        (!path.is_absolute()).then(|| self.base.join(path).display().to_string())
    }

    /// The path a parent file should name for `path`: a rewritten copy, or
    /// `path` itself when nothing in it changes.
    fn file(&mut self, path: &Path, depth: usize) -> Result<PathBuf> {
        let top = depth == 0;
        if depth > MAX_DEPTH {
            bail!(
                "{}: Include nesting is too deep (an include cycle?)",
                path.display()
            );
        }
        if !top && path.extension().is_some_and(|e| e == "gz") {
            return Ok(path.to_path_buf());
        }
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read scene file `{}`: {e}", path.display()))?;
        let src = SourceFile::new(path.display().to_string(), text);
        let toks = tokenize(&src).map_err(|d| d.to_string())?;
        let mut edits: Vec<(&Token, String)> = Vec::new();
        let str_at = |i: usize| match toks.get(i).map(|t| &t.kind) {
            Some(TokenKind::Str(s)) => Some((&toks[i], s.as_str())),
            _ => None,
        };
        for (i, t) in toks.iter().enumerate() {
            match &t.kind {
                TokenKind::Ident(d) if d == "Integrator" => {
                    if let Some((name, _)) = str_at(i + 1) {
                        let new = match self.params {
                            Some(p) => format!("{} {p}", quote(self.integrator)),
                            None => quote(self.integrator),
                        };
                        edits.push((name, new));
                        self.found_integrator = true;
                    }
                }
                TokenKind::Ident(d) if d == "WorldBegin" && self.world_begin.is_none() => {
                    self.world_begin = Some(t.clone());
                }
                TokenKind::Ident(d) if d == "Include" || d == "Import" => {
                    if let Some((tok, f)) = str_at(i + 1) {
                        let child = self.base.join(f);
                        if !child.is_file() {
                            let msg = format!("cannot read included file `{}`", child.display());
                            return Err(Diagnostic::error(&tok.loc, msg).to_string().into());
                        }
                        let named = self.file(&child, depth + 1)?;
                        if named.as_os_str() != f {
                            edits.push((tok, quote(&named.display().to_string())));
                        }
                    }
                }
                TokenKind::Str(decl) if is_path_param(decl) => {
                    let v = str_at(i + 1).or_else(|| {
                        (toks.get(i + 1)?.kind == TokenKind::LBracket).then_some(())?;
                        str_at(i + 2)
                    });
                    let spectrum = decl.starts_with("spectrum");
                    if let Some((tok, p)) = v {
                        if let Some(abs) = self.absolute(p) {
                            if !spectrum || Path::new(&abs).is_file() {
                                edits.push((tok, quote(&abs)));
                            }
                        }
                    }
                }
                _ => {}
            }
        }
        if edits.is_empty() && !top {
            return Ok(path.to_path_buf());
        }
        let mut out = src.text.clone();
        edits.sort_by_key(|e| std::cmp::Reverse(span(&src.text, e.0).start));
        for (tok, new) in edits {
            out.replace_range(span(&src.text, tok), &new);
        }
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let copy = if top {
            self.dir.join(&*name)
        } else {
            self.copies += 1;
            self.dir.join(format!("inc{}-{name}", self.copies))
        };
        super::store::write_atomic(&copy, out.as_bytes())?;
        Ok(copy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("lumis-copy-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("sub")).unwrap();
        d
    }

    #[test]
    fn renames_the_integrator_and_makes_paths_absolute() {
        let d = dir("paths");
        let top = "# é comment\nIntegrator \"photon\" \"integer maxdepth\" [ 10 ]\nFilm \"rgb\" \"string filename\" \"x.exr\"\nWorldBegin\nInclude \"sub/mesh.pbrt\"\nImport \"plain.pbrt\"\nMaterial \"conductor\" \"spectrum eta\" \"metal-Cu-eta\" \"spectrum k\" [ \"k.spd\" ]\nTexture \"t\" \"spectrum\" \"imagemap\" \"string filename\" [ \"/abs/t.png\" ]\nTexture \"té\" \"spectrum\" \"imagemap\" \"string filename\" \"t.png\"\n";
        std::fs::write(d.join("s.pbrt"), top).unwrap();
        std::fs::write(d.join("k.spd"), "300 1 800 1").unwrap();
        std::fs::write(d.join("plain.pbrt"), "Shape \"sphere\"\n").unwrap();
        std::fs::write(
            d.join("sub/mesh.pbrt"),
            "Shape \"plymesh\" \"string filename\" \"sub/m.ply\"\n",
        )
        .unwrap();
        let out = d.join("copy");
        let copy = write_copy(
            &d.join("s.pbrt"),
            &out,
            "sppm",
            Some("\"float radius\" [ 0.1 ]"),
        )
        .unwrap();
        assert_eq!(copy, out.join("s.pbrt"));
        let t = std::fs::read_to_string(&copy).unwrap();
        let abs = |p: &str| d.join(p).display().to_string();
        let want = top
            .replace("\"photon\"", "\"sppm\" \"float radius\" [ 0.1 ]")
            .replace("\"x.exr\"", &quote(&abs("x.exr")))
            .replace(
                "\"sub/mesh.pbrt\"",
                &quote(&out.join("inc1-mesh.pbrt").display().to_string()),
            )
            .replace("\"plain.pbrt\"", &quote(&abs("plain.pbrt")))
            .replace("\"k.spd\"", &quote(&abs("k.spd")))
            .replace("\"t.png\"", &quote(&abs("t.png")));
        assert_eq!(t, want);
        // The included file's path resolves against the top file's folder.
        let inc = std::fs::read_to_string(out.join("inc1-mesh.pbrt")).unwrap();
        assert_eq!(
            inc,
            format!(
                "Shape \"plymesh\" \"string filename\" {}\n",
                quote(&abs("sub/m.ply"))
            )
        );
        assert!(
            !out.join("plain.pbrt").exists(),
            "unchanged includes are not copied"
        );
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_scene_without_integrator_or_with_bad_text_is_a_located_error() {
        let d = dir("errors");
        std::fs::write(d.join("s.pbrt"), "Film \"rgb\"\n\nWorldBegin\n").unwrap();
        let e = write_copy(&d.join("s.pbrt"), &d.join("c"), "sppm", None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("s.pbrt:3:1") && e.contains("no `Integrator`"),
            "{e}"
        );
        std::fs::write(
            d.join("s.pbrt"),
            "Integrator \"path\"\nInclude \"none.pbrt\"\n",
        )
        .unwrap();
        let e = write_copy(&d.join("s.pbrt"), &d.join("c"), "sppm", None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("s.pbrt:2:9") && e.contains("none.pbrt"), "{e}");
        std::fs::write(d.join("s.pbrt"), "Integrator \"path\n").unwrap();
        let e = write_copy(&d.join("s.pbrt"), &d.join("c"), "sppm", None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("s.pbrt:1:12") && e.contains("unterminated"),
            "{e}"
        );
        std::fs::remove_dir_all(&d).unwrap();
    }
}
