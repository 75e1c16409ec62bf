//! Scoping, materials, textures, shapes, lights, includes and unsupported directives.

use super::PendingInstance;
use super::{upgrade, with_defaults, Builder, Scope, MAX_INCLUDE_DEPTH};
use crate::desc::{
    Entity, LightDesc, MaterialDesc, MaterialRef, MediumDesc, MediumInterfaceDesc, MediumName,
    ObjectDesc, ShapeDesc, TextureDesc,
};
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
                let params = ParamSet::parse(rest)?;
                let a = &mut self.gs.attrs;
                let set = match s[0].0.as_str() {
                    "shape" => &mut a.shape,
                    "light" => &mut a.light,
                    "material" => &mut a.material,
                    "medium" => &mut a.medium,
                    "texture" => &mut a.texture,
                    other => {
                        return Err(Diagnostic::error(
                            &s[0].1,
                            format!("unknown Attribute target \"{other}\""),
                        )
                        .with_help("targets are \"shape\", \"light\", \"material\", \"medium\" and \"texture\""))
                    }
                };
                for p in params.params {
                    set.params.retain(|q| q.name != p.name);
                    set.params.push(p);
                }
            }
            "Material" => {
                self.require_world(dir, name)?;
                let mut entity =
                    with_defaults(Self::entity(dir, name, args)?, &self.gs.attrs.material);
                upgrade::material(&mut entity, &mut self.desc.warnings)?;
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
                let mut entity = with_defaults(Entity { ty, params, loc }, &self.gs.attrs.material);
                upgrade::material(&mut entity, &mut self.desc.warnings)?;
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
                let mut entity = with_defaults(
                    Entity {
                        ty: s[2].0.clone(),
                        params: ParamSet::parse(rest)?,
                        loc: s[2].1.clone(),
                    },
                    &self.gs.attrs.texture,
                );
                upgrade::texture(&mut entity, kind)?;
                self.desc.textures.push(TextureDesc {
                    name: tex_name,
                    kind: kind.to_string(),
                    entity,
                    object_to_world: self.gs.ctm,
                });
            }
            "Shape" => {
                self.require_world(dir, name)?;
                let mut entity =
                    with_defaults(Self::entity(dir, name, args)?, &self.gs.attrs.shape);
                upgrade::shape(&mut entity);
                let mut shape = ShapeDesc {
                    entity,
                    object_to_world: self.gs.ctm,
                    reverse_orientation: self.gs.reverse_orientation,
                    material: self.gs.material.clone(),
                    area_light: self.gs.area_light.clone(),
                    media: self.gs.media.clone(),
                };
                match self.object {
                    None => self.desc.shapes.push(shape),
                    Some(obj) => {
                        if let Some(al) = shape.area_light.take() {
                            let d = Diagnostic::warning(
                                &shape.entity.loc,
                                "area lights are not supported in object instances (as in pbrt-v4); this shape does not emit",
                            )
                            .with_help(format!("AreaLightSource at {}", al.loc));
                            self.desc.warnings.push(d);
                        }
                        self.desc.objects[obj as usize].shapes.push(shape);
                    }
                }
            }
            "AreaLightSource" => {
                self.require_world(dir, name)?;
                let mut e = with_defaults(Self::entity(dir, name, args)?, &self.gs.attrs.light);
                upgrade::light(&mut e, true)?;
                self.gs.area_light = Some(e);
            }
            "LightSource" => {
                self.require_world(dir, name)?;
                let mut entity =
                    with_defaults(Self::entity(dir, name, args)?, &self.gs.attrs.light);
                upgrade::light(&mut entity, false)?;
                self.desc.lights.push(LightDesc {
                    entity,
                    light_to_world: self.gs.ctm,
                    medium: self.gs.media.outside.clone(),
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
                let (s, rest) = Self::strings(dir, name, args, 1, "ObjectBegin \"name\"")?;
                Self::no_args(dir, name, rest)?;
                let (obj_name, loc) = s.into_iter().next().expect("one string");
                if self.object.is_some() {
                    return Err(Diagnostic::error(
                        &dir.loc,
                        "ObjectBegin inside another object definition",
                    )
                    .with_help("close the open object with ObjectEnd first"));
                }
                if let Some(&prev) = self.object_names.get(&obj_name) {
                    let first = &self.desc.objects[prev as usize].loc;
                    return Err(Diagnostic::error(
                        &loc,
                        format!("object `{obj_name}` is defined twice"),
                    )
                    .with_help(format!("first defined at {first}")));
                }
                self.stack
                    .push((Scope::Object, self.gs.clone(), dir.loc.clone()));
                let idx = self.desc.objects.len() as u32;
                self.object_names.insert(obj_name.clone(), idx);
                self.desc.objects.push(ObjectDesc {
                    name: obj_name,
                    loc,
                    shapes: Vec::new(),
                });
                self.object = Some(idx);
            }
            "ObjectEnd" => {
                Self::no_args(dir, name, args)?;
                self.pop_scope(dir, name, Scope::Object)?;
                self.object = None;
            }
            "ObjectInstance" => {
                self.require_world(dir, name)?;
                let (s, rest) = Self::strings(dir, name, args, 1, "ObjectInstance \"name\"")?;
                Self::no_args(dir, name, rest)?;
                if self.object.is_some() {
                    return Err(Diagnostic::error(
                        &dir.loc,
                        "ObjectInstance inside an object definition (pbrt-v4 does not nest instances)",
                    ));
                }
                let (obj_name, loc) = s.into_iter().next().expect("one string");
                self.pending_instances.push(PendingInstance {
                    name: obj_name,
                    loc,
                    world_from_object: self.gs.ctm,
                });
            }
            "WorldEnd" => Self::no_args(dir, name, args)?, // pbrt-v3's end of scene
            "MakeNamedMedium" => self.make_named_medium(dir, name, args)?,
            "MediumInterface" => {
                let n = args.len().min(2);
                let (s, rest) = Self::strings(
                    dir,
                    name,
                    args,
                    n.max(1),
                    "MediumInterface \"inside\" [\"outside\"]",
                )?;
                Self::no_args(dir, name, rest)?;
                let named = |(name, loc): &(String, crate::loc::Loc)| {
                    (!name.is_empty()).then(|| MediumName {
                        name: name.clone(),
                        loc: loc.clone(),
                    })
                };
                // One name is both sides (pbrt-v4); two are inside, outside.
                self.gs.media = MediumInterfaceDesc {
                    inside: named(&s[0]),
                    outside: named(s.last().expect("one or two names")),
                };
            }
            "Accelerator" => {
                Self::entity(dir, name, args)?;
                self.warn(
                    &dir.loc,
                    "`Accelerator` is ignored: lumis always uses its own BVH",
                );
            }
            _ => return Err(Self::unknown_directive(dir, name)),
        }
        Ok(())
    }

    fn pop_scope(&mut self, dir: &Token, name: &str, want: Scope) -> Result<(), Diagnostic> {
        let Some((scope, saved, begin)) = self.stack.pop() else {
            return Err(Diagnostic::error(
                &dir.loc,
                format!("`{name}` without a matching begin: no `{want:?}Begin` is open here"),
            )
            .with_help(format!("remove it, or add `{want:?}Begin` before it")));
        };
        if scope != want {
            return Err(Diagnostic::error(
                &dir.loc,
                format!("`{name}` does not match the {scope:?}Begin at {begin}: expected `{scope:?}End`"),
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

        if self.depth >= MAX_INCLUDE_DEPTH {
            return Err(Diagnostic::error(
                loc,
                "Include nesting is too deep (an include cycle?)",
            ));
        }
        let path = self.desc.read_path(file);
        let text = super::read_scene_text(&path).map_err(|e| {
            Diagnostic::error(
                loc,
                format!("cannot read included file `{}`: {e}", path.display()),
            )
            .with_help("included paths are relative to the top-level scene file's folder")
        })?;
        // Import (pbrt-v4): like Include, but changes to the graphics state
        // made in the imported file do not carry over.
        let saved = (name == "Import").then(|| self.gs.clone());
        self.depth += 1;
        let result = self.run(SourceFile::new(path.display().to_string(), text));
        self.depth -= 1;
        if let Some(gs) = saved {
            self.gs = gs;
        }
        result
    }
}

impl Builder {
    /// `MakeNamedMedium "name" "string type" "homogeneous" ...`: the type
    /// is a parameter; names are unique (pbrt-v4 refuses a redefinition).
    fn make_named_medium(
        &mut self,
        dir: &Token,
        name: &str,
        args: &[Token],
    ) -> Result<(), Diagnostic> {
        let usage = "MakeNamedMedium \"name\" \"string type\" \"homogeneous\" parameters...";
        let (s, rest) = Self::strings(dir, name, args, 1, usage)?;
        let (medium_name, loc) = s.into_iter().next().expect("one string");
        let params = ParamSet::parse(rest)?;
        let entity = with_defaults(
            Entity {
                ty: String::new(),
                params,
                loc: loc.clone(),
            },
            &self.gs.attrs.medium,
        );
        let Some(ty) = entity.params.get_opt_string("type")? else {
            return Err(Diagnostic::error(
                &loc,
                format!("medium `{medium_name}` has no type: expected a \"string type\" parameter"),
            )
            .with_help(usage));
        };
        if let Some(prev) = self.desc.media.iter().find(|m| m.name == medium_name) {
            return Err(Diagnostic::error(
                &loc,
                format!("medium `{medium_name}` is defined twice"),
            )
            .with_help(format!("first defined at {}", prev.entity.loc)));
        }
        let mut entity = entity;
        entity.ty = ty;
        self.desc.media.push(MediumDesc {
            name: medium_name,
            entity,
            medium_to_world: self.gs.ctm,
        });
        Ok(())
    }
}
