//! Typed lookups on a [`ParamSet`]. Each marks the parameter used.

use super::{arity, Param, ParamSet, Value};
use crate::loc::Diagnostic;
use lumis_math::Vec3;

/// A spectrum-valued parameter, as written.
#[derive(Clone, Debug, PartialEq)]
pub enum SpectrumValue {
    Rgb([f32; 3]),
    /// Temperature in kelvin.
    Blackbody(f32),
    /// (wavelength nm, value) pairs.
    Sampled(Vec<(f32, f32)>),
    /// A built-in named spectrum such as "metal-Cu-eta".
    Named(String),
    /// A `.spd` file name, relative to the scene folder.
    File(String),
}

const NAMED_PREFIXES: &[&str] = &[
    "metal-", "glass-", "canon_", "nikon_", "sony_", "stdillum", "illum-",
];

impl ParamSet {
    /// The parameter called `name`, checked to have one of `types`, marked used.
    fn typed(&self, name: &str, types: &[&str]) -> Result<Option<&Param>, Diagnostic> {
        let Some(p) = self.param(name) else {
            return Ok(None);
        };
        if !types.contains(&p.ty.as_str()) {
            let expected = types
                .iter()
                .map(|t| format!("`{t}`"))
                .collect::<Vec<_>>()
                .join(" or ");
            return Err(Diagnostic::error(
                &p.loc,
                format!(
                    "parameter `{name}` should have type {expected}, but is declared as `{}`",
                    p.ty
                ),
            ));
        }
        p.mark_used();
        Ok(Some(p))
    }

    pub(super) fn floats_of(
        &self,
        name: &str,
        types: &[&str],
    ) -> Result<Option<(&Param, Vec<f32>)>, Diagnostic> {
        let Some(p) = self.typed(name, types)? else {
            return Ok(None);
        };
        let v = match &p.value {
            Value::Floats(f) => f.clone(),
            Value::Ints(i) => i.iter().map(|&x| x as f32).collect(),
            _ => {
                return Err(Diagnostic::error(
                    &p.loc,
                    format!("parameter `{name}` is not numeric"),
                ))
            }
        };
        Ok(Some((p, v)))
    }

    pub(super) fn get_triples(
        &self,
        name: &str,
        ty: &str,
    ) -> Result<Option<Vec<Vec3>>, Diagnostic> {
        let Some((p, f)) = self.floats_of(name, &[ty])? else {
            return Ok(None);
        };
        if f.is_empty() || f.len() % 3 != 0 {
            return Err(arity(p, "a non-zero multiple of 3 values"));
        }
        Ok(Some(
            f.chunks(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect(),
        ))
    }

    fn single<'a>(&'a self, name: &str, types: &[&str]) -> Result<Option<&'a Param>, Diagnostic> {
        match self.typed(name, types)? {
            Some(p) if p.value.len() != 1 => Err(arity(p, "exactly 1 value")),
            other => Ok(other),
        }
    }

    /// A single float; an `integer` parameter is accepted too.
    pub fn get_float(&self, name: &str, default: f32) -> Result<f32, Diagnostic> {
        Ok(
            match self.single(name, &["float", "integer"])?.map(|p| &p.value) {
                Some(Value::Floats(f)) => f[0],
                Some(Value::Ints(i)) => i[0] as f32,
                _ => default,
            },
        )
    }

    pub fn get_int(&self, name: &str, default: i32) -> Result<i32, Diagnostic> {
        Ok(match self.single(name, &["integer"])?.map(|p| &p.value) {
            Some(Value::Ints(i)) => i[0],
            _ => default,
        })
    }

    pub fn get_bool(&self, name: &str, default: bool) -> Result<bool, Diagnostic> {
        Ok(match self.single(name, &["bool"])?.map(|p| &p.value) {
            Some(Value::Bools(b)) => b[0],
            _ => default,
        })
    }

    pub fn get_opt_string(&self, name: &str) -> Result<Option<String>, Diagnostic> {
        Ok(match self.single(name, &["string"])?.map(|p| &p.value) {
            Some(Value::Strings(s)) => Some(s[0].clone()),
            _ => None,
        })
    }

    pub fn get_string(&self, name: &str, default: &str) -> Result<String, Diagnostic> {
        Ok(self
            .get_opt_string(name)?
            .unwrap_or_else(|| default.to_string()))
    }

    /// All values of a float (or integer) parameter.
    pub fn get_floats(&self, name: &str) -> Result<Option<Vec<f32>>, Diagnostic> {
        Ok(self.floats_of(name, &["float", "integer"])?.map(|(_, f)| f))
    }

    pub fn get_ints(&self, name: &str) -> Result<Option<Vec<i32>>, Diagnostic> {
        Ok(match self.typed(name, &["integer"])?.map(|p| &p.value) {
            Some(Value::Ints(i)) => Some(i.clone()),
            _ => None,
        })
    }

    pub fn get_point3s(&self, name: &str) -> Result<Option<Vec<Vec3>>, Diagnostic> {
        self.get_triples(name, "point3")
    }

    /// All values of an `rgb` parameter, three at a time (grids of colours).
    pub fn get_rgbs(&self, name: &str) -> Result<Option<Vec<Vec3>>, Diagnostic> {
        self.get_triples(name, "rgb")
    }

    pub fn get_normals(&self, name: &str) -> Result<Option<Vec<Vec3>>, Diagnostic> {
        self.get_triples(name, "normal")
    }

    /// Name of the texture bound to `name`, if the parameter has type `texture`.
    /// Parameters of other types are left alone (not marked used).
    pub fn get_texture(&self, name: &str) -> Option<String> {
        let p = self.param(name).filter(|p| p.ty == "texture")?;
        p.mark_used();
        match &p.value {
            Value::Strings(s) if s.len() == 1 => Some(s[0].clone()),
            _ => None,
        }
    }

    /// A spectrum given as `rgb`, `blackbody` or `spectrum`.
    pub fn get_spectrum(&self, name: &str) -> Result<Option<SpectrumValue>, Diagnostic> {
        let Some(p) = self.typed(name, &["rgb", "blackbody", "spectrum"])? else {
            return Ok(None);
        };
        let sv = match (p.ty.as_str(), &p.value) {
            ("rgb", Value::Floats(f)) if f.len() == 3 => SpectrumValue::Rgb([f[0], f[1], f[2]]),
            ("rgb", _) => return Err(arity(p, "exactly 3 values")),
            ("blackbody", Value::Floats(f)) if f.len() == 1 => SpectrumValue::Blackbody(f[0]),
            ("blackbody", _) => {
                return Err(arity(p, "exactly 1 value (temperature in kelvin)").with_help(
                    "pbrt-v3's `blackbody [T scale]` is written `\"blackbody L\" [T]` plus `\"float scale\"` in pbrt-v4",
                ))
            }
            (_, Value::Strings(s)) if s.len() == 1 => {
                let s = s[0].clone();
                if NAMED_PREFIXES.iter().any(|pre| s.starts_with(pre)) || !s.contains('.') {
                    SpectrumValue::Named(s)
                } else {
                    SpectrumValue::File(s)
                }
            }
            (_, Value::Strings(_)) => return Err(arity(p, "exactly 1 string")),
            (_, Value::Floats(f)) if !f.is_empty() && f.len() % 2 == 0 => {
                SpectrumValue::Sampled(f.chunks(2).map(|c| (c[0], c[1])).collect())
            }
            _ => return Err(arity(p, "an even number of values (wavelength, value pairs)")),
        };
        Ok(Some(sv))
    }
}
