//! pbrt-v4 scene text → a plain scene description with file locations, and a
//! PLY mesh reader. Nothing here renders or prints: errors are returned as
//! [`Diagnostic`]s and warnings are collected in [`SceneDesc::warnings`].

pub mod desc;
pub mod lexer;
pub mod loc;
pub mod overrides;
pub mod params;
pub mod parser;
pub mod ply;

pub use desc::*;
pub use loc::{Diagnostic, Loc, Severity, SourceFile};
pub use overrides::{Override, Overrides};
pub use params::{Param, ParamSet, ParamSpec, Value};

use std::path::Path;

/// Parses a scene file and everything it includes.
pub fn load_file(path: &Path) -> Result<SceneDesc, Diagnostic> {
    parser::parse_file(path)
}

/// Parses scene text; `name` labels diagnostics and `base_dir` anchors relative paths.
pub fn load_str(text: &str, name: &str, base_dir: &Path) -> Result<SceneDesc, Diagnostic> {
    parser::parse_str(text, name, base_dir)
}
