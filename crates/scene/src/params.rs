//! Parameter lists (`"type name" [ values ]`) and typed lookups.

use crate::lexer::{Token, TokenKind};
use crate::loc::{suggest, Diagnostic, Loc};
use lumis_math::{Vec2, Vec3};
use std::cell::Cell;

mod get;
pub use get::SpectrumValue;

/// The raw payload of a parameter.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Ints(Vec<i32>),
    Floats(Vec<f32>),
    Bools(Vec<bool>),
    Strings(Vec<String>),
}

impl Value {
    pub fn len(&self) -> usize {
        match self {
            Value::Ints(v) => v.len(),
            Value::Floats(v) => v.len(),
            Value::Bools(v) => v.len(),
            Value::Strings(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[derive(Clone, Debug)]
pub struct Param {
    /// Normalised type: "point3", "normal", "vector3", "rgb", or as written.
    pub ty: String,
    pub name: String,
    pub value: Value,
    /// Location of the `"type name"` string.
    pub loc: Loc,
    /// Location of each value token.
    pub value_locs: Vec<Loc>,
    used: Cell<bool>,
}

impl Param {
    pub fn new(ty: &str, name: &str, value: Value, loc: Loc, value_locs: Vec<Loc>) -> Param {
        Param {
            ty: ty.to_string(),
            name: name.to_string(),
            value,
            loc,
            value_locs,
            used: Cell::new(false),
        }
    }

    pub fn is_used(&self) -> bool {
        self.used.get()
    }

    pub fn mark_used(&self) {
        self.used.set(true);
    }
}

#[derive(Clone, Debug, Default)]
pub struct ParamSet {
    pub params: Vec<Param>,
}

/// Parameter types as written, with what they normalise to.
const TYPES: &[(&str, &str)] = &[
    ("integer", "integer"),
    ("float", "float"),
    ("point2", "point2"),
    ("vector2", "vector2"),
    ("point3", "point3"),
    ("point", "point3"),
    ("vector3", "vector3"),
    ("vector", "vector3"),
    ("normal3", "normal"),
    ("normal", "normal"),
    ("rgb", "rgb"),
    ("color", "rgb"),
    ("bool", "bool"),
    ("string", "string"),
    ("texture", "texture"),
    ("spectrum", "spectrum"),
    ("blackbody", "blackbody"),
];

impl ParamSet {
    pub fn new() -> ParamSet {
        ParamSet::default()
    }

    /// Parses a whole parameter list (the tokens after a directive's strings).
    pub fn parse(tokens: &[Token]) -> Result<ParamSet, Diagnostic> {
        let mut set = ParamSet::new();
        let mut i = 0;
        while i < tokens.len() {
            let decl = &tokens[i];
            let TokenKind::Str(text) = &decl.kind else {
                return Err(Diagnostic::error(
                    &decl.loc,
                    format!(
                        "expected a parameter declaration like \"float radius\", found {}",
                        decl.describe()
                    ),
                ));
            };
            let (ty, name) = split_decl(text, &decl.loc)?;
            i += 1;
            let values: &[Token] = match tokens.get(i).map(|t| &t.kind) {
                Some(TokenKind::LBracket) => {
                    let start = i + 1;
                    let Some(len) = tokens[start..]
                        .iter()
                        .position(|t| t.kind == TokenKind::RBracket)
                    else {
                        return Err(Diagnostic::error(&tokens[i].loc, "unclosed `[`"));
                    };
                    i = start + len + 1;
                    &tokens[start..start + len]
                }
                Some(TokenKind::Str(_) | TokenKind::Num { .. } | TokenKind::Ident(_)) => {
                    i += 1;
                    &tokens[i - 1..i]
                }
                _ => {
                    return Err(Diagnostic::error(
                        &decl.loc,
                        format!("parameter \"{text}\" has no value"),
                    ))
                }
            };
            let value = parse_values(ty, values)?;
            if let Some(prev) = set.params.iter().find(|p| p.name == name) {
                return Err(
                    Diagnostic::error(&decl.loc, format!("parameter `{name}` redefined"))
                        .with_help(format!("first defined at {}", prev.loc)),
                );
            }
            let value_locs = values.iter().map(|t| t.loc.clone()).collect();
            set.params
                .push(Param::new(ty, name, value, decl.loc.clone(), value_locs));
        }
        Ok(set)
    }

    pub fn push(&mut self, p: Param) {
        self.params.push(p);
    }

    pub fn param(&self, name: &str) -> Option<&Param> {
        self.params.iter().find(|p| p.name == name)
    }

    pub fn has(&self, name: &str) -> bool {
        self.param(name).is_some()
    }

    pub fn loc_of(&self, name: &str) -> Option<Loc> {
        self.param(name).map(|p| p.loc.clone())
    }

    pub fn mark_used(&self, name: &str) {
        if let Some(p) = self.param(name) {
            p.mark_used();
        }
    }

    pub fn unused(&self) -> Vec<&Param> {
        self.params.iter().filter(|p| !p.is_used()).collect()
    }

    /// One warning per unused parameter, suggesting a near name from `known`.
    /// Unused parameters whose name is in `known` are not reported.
    pub fn report_unused(&self, context: &str, known: &[&str]) -> Vec<Diagnostic> {
        self.unused()
            .into_iter()
            .filter(|p| !known.contains(&p.name.as_str()))
            .map(|p| {
                let d = Diagnostic::warning(
                    &p.loc,
                    format!("unknown parameter `{}` for {context}", p.name),
                );
                match suggest(&p.name, known, 2) {
                    Some(s) => d.with_help(format!("did you mean `{s}`?")),
                    None => d,
                }
            })
            .collect()
    }

    pub fn get_vector3(&self, name: &str, default: Vec3) -> Result<Vec3, Diagnostic> {
        self.get_vec3_typed(name, "vector3", default)
    }

    pub fn get_point3(&self, name: &str, default: Vec3) -> Result<Vec3, Diagnostic> {
        self.get_vec3_typed(name, "point3", default)
    }

    fn get_vec3_typed(&self, name: &str, ty: &str, default: Vec3) -> Result<Vec3, Diagnostic> {
        match self.get_triples(name, ty)? {
            None => Ok(default),
            Some(v) if v.len() == 1 => Ok(v[0]),
            Some(_) => {
                let p = self.param(name).expect("present");
                Err(arity(p, "exactly 3 values"))
            }
        }
    }

    pub fn get_point2s(&self, name: &str) -> Result<Option<Vec<Vec2>>, Diagnostic> {
        let Some((p, f)) = self.floats_of(name, &["point2"])? else {
            return Ok(None);
        };
        if f.len() % 2 != 0 {
            return Err(arity(p, "a multiple of 2 values"));
        }
        Ok(Some(f.chunks(2).map(|c| Vec2::new(c[0], c[1])).collect()))
    }
}

fn split_decl<'a>(text: &'a str, loc: &Loc) -> Result<(&'static str, &'a str), Diagnostic> {
    let mut parts = text.split_whitespace();
    let (Some(ty), Some(name), None) = (parts.next(), parts.next(), parts.next()) else {
        return Err(Diagnostic::error(
            loc,
            format!("\"{text}\" is not a parameter declaration: expected \"type name\""),
        ));
    };
    match TYPES.iter().find(|(t, _)| *t == ty) {
        Some((_, norm)) => Ok((norm, name)),
        None => {
            let names: Vec<&str> = TYPES.iter().map(|(t, _)| *t).collect();
            let d = Diagnostic::error(loc, format!("unknown parameter type `{ty}`"));
            Err(match suggest(ty, &names, 2) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None => d,
            })
        }
    }
}

fn bad_value(t: &Token, expected: &str, ty: &str) -> Diagnostic {
    Diagnostic::error(
        &t.loc,
        format!(
            "expected {expected} for a `{ty}` parameter, found {}",
            t.describe()
        ),
    )
}

fn parse_values(ty: &str, toks: &[Token]) -> Result<Value, Diagnostic> {
    match ty {
        "integer" => toks
            .iter()
            .map(|t| match t.kind {
                TokenKind::Num {
                    value,
                    is_int: true,
                } if value >= i32::MIN as f64 && value <= i32::MAX as f64 => Ok(value as i32),
                _ => Err(bad_value(t, "an integer", ty)),
            })
            .collect::<Result<_, _>>()
            .map(Value::Ints),
        "bool" => toks
            .iter()
            .map(|t| match &t.kind {
                TokenKind::Str(s) | TokenKind::Ident(s) if s == "true" => Ok(true),
                TokenKind::Str(s) | TokenKind::Ident(s) if s == "false" => Ok(false),
                _ => Err(bad_value(t, "true or false", ty)),
            })
            .collect::<Result<_, _>>()
            .map(Value::Bools),
        "string" | "texture" => strings(ty, toks).map(Value::Strings),
        "spectrum" if matches!(toks.first().map(|t| &t.kind), Some(TokenKind::Str(_))) => {
            strings(ty, toks).map(Value::Strings)
        }
        _ => toks
            .iter()
            .map(|t| match t.kind {
                TokenKind::Num { value, .. } => Ok(value as f32),
                _ => Err(bad_value(t, "a number", ty)),
            })
            .collect::<Result<_, _>>()
            .map(Value::Floats),
    }
}

fn strings(ty: &str, toks: &[Token]) -> Result<Vec<String>, Diagnostic> {
    toks.iter()
        .map(|t| match &t.kind {
            TokenKind::Str(s) => Ok(s.clone()),
            _ => Err(bad_value(t, "a quoted string", ty)),
        })
        .collect()
}

fn arity(p: &Param, expected: &str) -> Diagnostic {
    Diagnostic::error(
        &p.loc,
        format!(
            "parameter `{}` of type `{}` needs {expected}, but has {}",
            p.name,
            p.ty,
            p.value.len()
        ),
    )
}

#[cfg(test)]
mod tests;

/// A parameter as a reader declares it: its scene-file type and name, a
/// one-line description, and the words of its command-line spelling (e.g.
/// `caustic-photons` for `causticphotons`), so front ends can offer every
/// parameter without declaring it again.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParamSpec {
    pub ty: &'static str,
    pub name: &'static str,
    pub words: &'static str,
    /// What the value may be (for help texts): `N`, `R`, `mis|photons|gather`.
    pub value: &'static str,
    pub help: &'static str,
}

impl ParamSpec {
    /// The names of `specs`, for unused-parameter reports.
    pub fn names(specs: &[ParamSpec]) -> Vec<&'static str> {
        specs.iter().map(|s| s.name).collect()
    }
}
