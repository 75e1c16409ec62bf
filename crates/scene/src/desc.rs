//! The plain scene description produced by the parser.

use crate::loc::{Diagnostic, Loc};
use crate::params::ParamSet;
use lumis_math::Transform;
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub use crate::params::SpectrumValue;

/// A directive with a type and parameters, e.g. `Camera "perspective" ...`.
#[derive(Clone, Debug)]
pub struct Entity {
    pub ty: String,
    pub params: ParamSet,
    /// Location of the type string (or of the directive when it has none).
    pub loc: Loc,
}

#[derive(Clone, Debug)]
pub struct CameraDesc {
    pub entity: Entity,
    /// The CTM at the `Camera` directive.
    pub camera_from_world: Transform,
    /// The medium the camera sits in: the outside medium of the
    /// `MediumInterface` in effect at `Camera` (as pbrt-v4), if any.
    pub medium: Option<MediumName>,
}

/// A medium named by `MediumInterface`, with where it was named (resolved
/// against `MakeNamedMedium` when the scene is built, so media may be
/// defined after their use, as in pbrt-v4).
#[derive(Clone, Debug)]
pub struct MediumName {
    pub name: String,
    pub loc: Loc,
}

/// `MediumInterface "inside" "outside"`: the media on either side of a
/// shape (`None`: no medium, the empty string in pbrt-v4).
#[derive(Clone, Debug, Default)]
pub struct MediumInterfaceDesc {
    pub inside: Option<MediumName>,
    pub outside: Option<MediumName>,
}

impl MediumInterfaceDesc {
    /// Whether crossing the shape changes the medium (otherwise rays keep
    /// the medium they travel in, as in pbrt-v4).
    pub fn is_transition(&self) -> bool {
        self.inside.as_ref().map(|m| &m.name) != self.outside.as_ref().map(|m| &m.name)
    }
}

/// `MakeNamedMedium "name" "string type" ...`: `entity.ty` is the type
/// parameter's value.
#[derive(Clone, Debug)]
pub struct MediumDesc {
    pub name: String,
    pub entity: Entity,
    /// The CTM at the directive: the medium's space to world.
    pub medium_to_world: Transform,
}

#[derive(Clone, Debug)]
pub enum MaterialRef {
    Default,
    Index(u32),
    /// Resolved later (forward references are allowed).
    Named(String, Loc),
}

#[derive(Clone, Debug)]
pub struct MaterialDesc {
    pub name: Option<String>,
    pub entity: Entity,
}

#[derive(Clone, Debug)]
pub struct TextureDesc {
    pub name: String,
    /// "float" or "spectrum".
    pub kind: String,
    pub entity: Entity,
    pub object_to_world: Transform,
}

#[derive(Clone, Debug)]
pub struct ShapeDesc {
    pub entity: Entity,
    pub object_to_world: Transform,
    pub reverse_orientation: bool,
    pub material: MaterialRef,
    pub area_light: Option<Entity>,
    /// The `MediumInterface` in effect at the shape.
    pub media: MediumInterfaceDesc,
}

/// An object (`ObjectBegin "name"` ... `ObjectEnd`): shapes placed by
/// `ObjectInstance`. Each shape's `object_to_world` is the CTM at its
/// `Shape` directive; an instance puts it at its own CTM on top of that.
#[derive(Clone, Debug)]
pub struct ObjectDesc {
    pub name: String,
    pub loc: Loc,
    pub shapes: Vec<ShapeDesc>,
}

/// `ObjectInstance "name"`: world-from-object is the CTM at the directive.
#[derive(Clone, Debug)]
pub struct InstanceDesc {
    /// Index into `SceneDesc::objects`.
    pub object: u32,
    pub world_from_object: Transform,
    pub loc: Loc,
}

#[derive(Clone, Debug)]
pub struct LightDesc {
    pub entity: Entity,
    pub light_to_world: Transform,
    /// The medium the light sits in (the outside medium in effect).
    pub medium: Option<MediumName>,
}

#[derive(Clone, Debug, Default)]
pub struct SceneDesc {
    /// Folder of the top-level file; every relative path resolves against it.
    pub base_dir: PathBuf,
    pub camera: Option<CameraDesc>,
    pub film: Option<Entity>,
    pub sampler: Option<Entity>,
    pub integrator: Option<Entity>,
    pub filter: Option<Entity>,
    pub materials: Vec<MaterialDesc>,
    /// Index into `materials`.
    pub named_materials: HashMap<String, u32>,
    pub textures: Vec<TextureDesc>,
    pub shapes: Vec<ShapeDesc>,
    pub objects: Vec<ObjectDesc>,
    pub instances: Vec<InstanceDesc>,
    pub lights: Vec<LightDesc>,
    /// `MakeNamedMedium`s, in order; names are unique.
    pub media: Vec<MediumDesc>,
    pub warnings: Vec<Diagnostic>,
    pub saw_world_begin: bool,
    /// What the scene was made of; see [`SceneDesc::inputs`].
    inputs: RefCell<Inputs>,
}

/// Everything a scene was made of: what makes two loads of it the same scene.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Inputs {
    /// The top-level text when it was given as text, not read from a file
    /// (the built-in default scene, [`crate::load_str`]).
    pub text: Option<Arc<str>>,
    /// Every file read (absolute), each once, in first-read order: the main file, its
    /// `Include`/`Import` files, then the assets the loader opened (meshes,
    /// images, spectra).
    pub files: Vec<PathBuf>,
}

impl SceneDesc {
    pub fn new(base_dir: &Path) -> SceneDesc {
        SceneDesc {
            base_dir: base_dir.to_path_buf(),
            ..SceneDesc::default()
        }
    }

    /// The text and files this scene was made of so far.
    pub fn inputs(&self) -> Inputs {
        self.inputs.borrow().clone()
    }

    /// Notes that `path` is read for this scene (once; later notes of it
    /// are ignored). It is kept absolute, so a later change of the current
    /// folder does not lose it.
    pub fn note_read(&self, path: &Path) {
        let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        let mut inputs = self.inputs.borrow_mut();
        if !inputs.files.contains(&path) {
            inputs.files.push(path);
        }
    }

    /// Notes the top-level text given as text (not as a file).
    pub(crate) fn note_text(&self, text: &str) {
        self.inputs.borrow_mut().text = Some(text.into());
    }

    /// [`SceneDesc::resolve_path`] for a file about to be read: notes it as an input.
    pub fn read_path(&self, p: &str) -> PathBuf {
        let path = self.resolve_path(p);
        self.note_read(&path);
        path
    }

    /// `p` as written in the scene, resolved against the top-level file's folder.
    pub fn resolve_path(&self, p: &str) -> PathBuf {
        let path = Path::new(p);
        if path.is_absolute() {
            path.to_path_buf()
        } else {
            self.base_dir.join(path)
        }
    }

    /// The material a shape uses, following names; `None` for the default
    /// material, `Err` (at the reference) for an undefined name.
    pub fn material(&self, r: &MaterialRef) -> Result<Option<&MaterialDesc>, Diagnostic> {
        match r {
            MaterialRef::Default => Ok(None),
            MaterialRef::Index(i) => Ok(self.materials.get(*i as usize)),
            MaterialRef::Named(name, loc) => match self.named_materials.get(name) {
                Some(&i) => Ok(self.materials.get(i as usize)),
                None => {
                    let names: Vec<&str> =
                        self.named_materials.keys().map(|s| s.as_str()).collect();
                    let d =
                        Diagnostic::error(loc, format!("named material `{name}` is not defined"));
                    Err(match crate::loc::suggest(name, &names, 2) {
                        Some(s) => d.with_help(format!("did you mean `{s}`?")),
                        None if names.is_empty() => d.with_help(
                            "define it first with `MakeNamedMaterial \"name\" \"string type\" ...`",
                        ),
                        None => {
                            let mut names = names;
                            names.sort_unstable();
                            names.truncate(12);
                            d.with_help(format!("named materials defined: {}", names.join(", ")))
                        }
                    })
                }
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolve_relative_and_absolute() {
        let d = SceneDesc::new(Path::new("/scenes/box"));
        assert_eq!(
            d.resolve_path("geo/a.ply"),
            PathBuf::from("/scenes/box/geo/a.ply")
        );
        assert_eq!(d.resolve_path("/abs/a.ply"), PathBuf::from("/abs/a.ply"));
    }

    #[test]
    fn material_lookup_reports_unknown_names() {
        let mut d = SceneDesc::new(Path::new("."));
        d.materials.push(MaterialDesc {
            name: Some("Floor".into()),
            entity: Entity {
                ty: "diffuse".into(),
                params: ParamSet::new(),
                loc: Loc::none(),
            },
        });
        d.named_materials.insert("Floor".into(), 0);
        let m = d
            .material(&MaterialRef::Named("Floor".into(), Loc::none()))
            .unwrap();
        assert_eq!(m.unwrap().entity.ty, "diffuse");
        assert!(d.material(&MaterialRef::Default).unwrap().is_none());
        let e = d
            .material(&MaterialRef::Named("Flor".into(), Loc::none()))
            .unwrap_err();
        assert_eq!(e.help.as_deref(), Some("did you mean `Floor`?"));
    }
}
