//! Scoping, materials, textures, shapes, lights, includes and unsupported directives.

use super::{Builder, Scope, MAX_INCLUDE_DEPTH};
use crate::desc::{Entity, LightDesc, MaterialDesc, MaterialRef, ShapeDesc, TextureDesc};
use crate::lexer::Token;
use crate::loc::{Diagnostic, SourceFile};
use crate::params::ParamSet;

impl Builder {
    pub(super) fn world_directive(
        &mut self,
        dir: &Token,
        name: &str,
        args: &[Token],
    ) -> Result<(), Diagnostic> {
        match name {
            "AttributeBegin" | "TransformBegin" => {
                Self::no_args(dir, name, args)?;
                let scope = if name == "AttributeBegin" {
                    Scope::Attribute
                } else {
                    self.warn(&dir.loc, "TransformBegin is deprecated; use AttributeBegin");
                    Scope::Transform
                };
                self.stack.push((scope, self.gs.clone(), dir.loc.clone()));
            }
            "AttributeEnd" | "TransformEnd" => {
                Self::no_args(dir, name, args)?;
                let want = if name == "AttributeEnd" {
                    Scope::Attribute
                } else {
                    Scope::Transform
                };
                self.pop_scope(dir, name, want)?;
            }
            "Attribute" => {
                let (s, rest) =
                    Self::strings(dir, name, args, 1, "Attribute \"shape\" parameters...")?;
                ParamSet::parse(rest)?;
                self.warn(
                    &dir.loc,
                    format!("`Attribute \"{}\"` is not supported yet; ignored", s[0].0),
                );
            }
            "Material" => {
                self.require_world(dir, name)?;
                let entity = Self::entity(dir, name, args)?;
                self.desc
                    .materials
                    .push(MaterialDesc { name: None, entity });
                self.gs.material = MaterialRef::Index(self.desc.materials.len() as u32 - 1);
            }
            "MakeNamedMaterial" => {
                self.require_world(dir, name)?;
                let usage = "MakeNamedMaterial \"name\" \"string type\" \"diffuse\" parameters...";
                let (s, rest) = Self::strings(dir, name, args, 1, usage)?;
                let (mat_name, loc) = s.into_iter().next().expect("one string");
                let params = ParamSet::parse(rest)?;
                let Some(ty) = params.get_opt_string("type")? else {
                    return Err(Diagnostic::error(
                        &loc,
                        format!("named material `{mat_name}` has no \"string type\" parameter"),
                    )
                    .with_help("add e.g. \"string type\" \"diffuse\""));
                };
                if self.desc.named_materials.contains_key(&mat_name) {
                    self.warn(
                        &loc,
                        format!("named material `{mat_name}` redefined; the last one is used"),
                    );
                }
                let entity = Entity { ty, params, loc };
                self.desc.materials.push(MaterialDesc {
                    name: Some(mat_name.clone()),
                    entity,
                });
                let idx = self.desc.materials.len() as u32 - 1;
                self.desc.named_materials.insert(mat_name, idx);
            }
            "NamedMaterial" => {
                self.require_world(dir, name)?;
                let (s, rest) = Self::strings(dir, name, args, 1, "NamedMaterial \"name\"")?;
                Self::no_args(dir, name, rest)?;
                let (n, loc) = s.into_iter().next().expect("one string");
                self.gs.material = MaterialRef::Named(n, loc);
            }
            "Texture" => {
                self.require_world(dir, name)?;
                let usage = "Texture \"name\" \"spectrum\"|\"float\" \"class\" parameters...";
                let (s, rest) = Self::strings(dir, name, args, 3, usage)?;
                let kind = match s[1].0.as_str() {
                    "float" => "float",
                    "spectrum" | "color" | "rgb" => "spectrum",
                    other => {
                        return Err(Diagnostic::error(
                            &s[1].1,
                            format!(
                                "texture kind must be \"float\" or \"spectrum\", found \"{other}\""
                            ),
                        ))
                    }
                };
                let tex_name = s[0].0.clone();
                if self
                    .desc
                    .textures
                    .iter()
                    .any(|t| t.name == tex_name && t.kind == kind)
                {
                    self.warn(
                        &s[0].1,
                        format!("{kind} texture `{tex_name}` redefined; the last one is used"),
                    );
                }
                let entity = Entity {
                    ty: s[2].0.clone(),
                    params: ParamSet::parse(rest)?,
                    loc: s[2].1.clone(),
                };
                self.desc.textures.push(TextureDesc {
                    name: tex_name,
                    kind: kind.to_string(),
                    entity,
                    object_to_world: self.gs.ctm,
                });
            }
            "Shape" => {
                self.require_world(dir, name)?;
                let entity = Self::entity(dir, name, args)?;
                if self.object.is_none() {
                    self.desc.shapes.push(ShapeDesc {
                        entity,
                        object_to_world: self.gs.ctm,
                        reverse_orientation: self.gs.reverse_orientation,
                        material: self.gs.material.clone(),
                        area_light: self.gs.area_light.clone(),
                        inside_object: None,
                    });
                }
            }
            "AreaLightSource" => {
                self.require_world(dir, name)?;
                self.gs.area_light = Some(Self::entity(dir, name, args)?);
            }
            "LightSource" => {
                self.require_world(dir, name)?;
                let entity = Self::entity(dir, name, args)?;
                self.desc.lights.push(LightDesc {
                    entity,
                    light_to_world: self.gs.ctm,
                });
            }
            "ReverseOrientation" => {
                self.require_world(dir, name)?;
                Self::no_args(dir, name, args)?;
                self.gs.reverse_orientation = !self.gs.reverse_orientation;
            }
            "Include" | "Import" => self.include(dir, name, args)?,
            "ObjectBegin" => {
                self.require_world(dir, name)?;
                let (s, _) = Self::strings(dir, name, args, 1, "ObjectBegin \"name\"")?;
                self.warn(
                    &dir.loc,
                    format!("object instancing is not supported yet; the shapes of object `{}` are ignored", s[0].0),
                );
                self.stack
                    .push((Scope::Object, self.gs.clone(), dir.loc.clone()));
                self.object = Some(s[0].0.clone());
            }
            "ObjectEnd" => {
                Self::no_args(dir, name, args)?;
                self.pop_scope(dir, name, Scope::Object)?;
                self.object = None;
            }
            "ObjectInstance" => {
                self.require_world(dir, name)?;
                self.warn(
                    &dir.loc,
                    "object instancing is not supported yet; ObjectInstance ignored",
                );
            }
            "WorldEnd" => self.warn(&dir.loc, "WorldEnd is pbrt-v3 syntax; ignored"),
            "MakeNamedMedium" | "MediumInterface" | "ActiveTransform" | "TransformTimes"
            | "Accelerator" => {
                self.warn(&dir.loc, format!("`{name}` is not supported yet; ignored"))
            }
            _ => return Err(Self::unknown_directive(dir, name)),
        }
        Ok(())
    }

    fn pop_scope(&mut self, dir: &Token, name: &str, want: Scope) -> Result<(), Diagnostic> {
        let Some((scope, saved, begin)) = self.stack.pop() else {
            return Err(Diagnostic::error(
                &dir.loc,
                format!("`{name}` without a matching begin"),
            ));
        };
        if scope != want {
            return Err(Diagnostic::error(
                &dir.loc,
                format!("`{name}` does not match the {scope:?}Begin at {begin}"),
            ));
        }
        if scope == Scope::Transform {
            self.gs.ctm = saved.ctm;
        } else {
            self.gs = saved;
        }
        Ok(())
    }

    fn include(&mut self, dir: &Token, name: &str, args: &[Token]) -> Result<(), Diagnostic> {
        let (s, rest) = Self::strings(dir, name, args, 1, &format!("{name} \"file.pbrt\""))?;
        Self::no_args(dir, name, rest)?;
        let (file, loc) = &s[0];
        if name == "Import" {
            self.warn(&dir.loc, "Import is treated as Include");
        }
        if file.ends_with(".gz") {
            return Err(Diagnostic::error(
                loc,
                "gzip-compressed scene files are not supported yet",
            ));
        }
        if self.depth >= MAX_INCLUDE_DEPTH {
            return Err(Diagnostic::error(
                loc,
                "Include nesting is too deep (an include cycle?)",
            ));
        }
        let path = self.desc.resolve_path(file);
        let text = std::fs::read_to_string(&path).map_err(|e| {
            Diagnostic::error(
                loc,
                format!("cannot read included file `{}`: {e}", path.display()),
            )
            .with_help("included paths are relative to the top-level scene file's folder")
        })?;
        self.depth += 1;
        let result = self.run(SourceFile::new(path.display().to_string(), text));
        self.depth -= 1;
        result
    }
}
