//! pbrt-v4 directives → [`SceneDesc`]: a small state machine over the tokens.

mod upgrade;
mod world;
mod xform;

use crate::desc::{Entity, MaterialRef, SceneDesc};
use crate::lexer::{tokenize, Token, TokenKind};
use crate::loc::{suggest, Diagnostic, Loc, SourceFile};
use crate::params::{Param, ParamSet};
use lumis_math::Transform;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

const DIRECTIVES: &[&str] = &[
    "Identity",
    "Translate",
    "Scale",
    "Rotate",
    "LookAt",
    "Transform",
    "ConcatTransform",
    "CoordinateSystem",
    "CoordSysTransform",
    "Camera",
    "Film",
    "Sampler",
    "Integrator",
    "PixelFilter",
    "ColorSpace",
    "Option",
    "WorldBegin",
    "WorldEnd",
    "AttributeBegin",
    "AttributeEnd",
    "TransformBegin",
    "TransformEnd",
    "Attribute",
    "Material",
    "MakeNamedMaterial",
    "NamedMaterial",
    "Texture",
    "Shape",
    "AreaLightSource",
    "LightSource",
    "ReverseOrientation",
    "Include",
    "Import",
    "ObjectBegin",
    "ObjectEnd",
    "ObjectInstance",
    "MakeNamedMedium",
    "MediumInterface",
    "ActiveTransform",
    "TransformTimes",
    "Accelerator",
];

/// Leading string arguments (with locations) and the remaining tokens.
type StringArgs<'t> = (Vec<(String, Loc)>, &'t [Token]);

/// Deepest allowed nesting of `Include`s (guards against include cycles).
const MAX_INCLUDE_DEPTH: usize = 32;

/// The scoped part of the graphics state.
#[derive(Clone)]
pub(crate) struct GraphicsState {
    pub ctm: Transform,
    pub material: MaterialRef,
    pub area_light: Option<Entity>,
    pub reverse_orientation: bool,
    /// `ActiveTransform`: whether transform directives change the start-time
    /// and the end-time transform. Only the start-time one is rendered.
    pub active_start: bool,
    pub active_end: bool,
    /// `Attribute "shape"|"light"|"material"|"medium"|"texture"` defaults.
    pub attrs: Attributes,
    /// The `MediumInterface` in effect.
    pub media: crate::desc::MediumInterfaceDesc,
}

/// Parameter defaults set by `Attribute`, by target.
#[derive(Clone, Default)]
pub(crate) struct Attributes {
    pub shape: ParamSet,
    pub light: ParamSet,
    pub material: ParamSet,
    pub medium: ParamSet,
    pub texture: ParamSet,
}

/// `e` with every parameter of `defaults` that it does not set itself.
pub(crate) fn with_defaults(mut e: Entity, defaults: &ParamSet) -> Entity {
    for p in &defaults.params {
        if !e.params.has(&p.name) {
            e.params.push(Param::new(
                &p.ty,
                &p.name,
                p.value.clone(),
                p.loc.clone(),
                p.value_locs.clone(),
            ));
        }
    }
    e
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Scope {
    Attribute,
    Transform,
    Object,
}

pub(crate) struct Builder {
    desc: SceneDesc,
    gs: GraphicsState,
    stack: Vec<(Scope, GraphicsState, Loc)>,
    coord_systems: HashMap<String, Transform>,
    /// Index (in `desc.objects`) of the open `ObjectBegin`, if any.
    object: Option<u32>,
    object_names: HashMap<String, u32>,
    /// `ObjectInstance`s, resolved at the end (objects may be defined later).
    pending_instances: Vec<PendingInstance>,
    depth: usize,
    /// Directives already warned about once (media, motion blur).
    warned_once: Vec<&'static str>,
}

pub(crate) struct PendingInstance {
    name: String,
    loc: Loc,
    world_from_object: Transform,
}

/// Parses scene text (and its `Include`s) into a description.
pub fn parse_str(text: &str, name: &str, base_dir: &Path) -> Result<SceneDesc, Diagnostic> {
    parse(text, name, base_dir, None)
}

/// Parses the text of `file` (or text given as such, when `None`).
fn parse(
    text: &str,
    name: &str,
    base_dir: &Path,
    file: Option<&Path>,
) -> Result<SceneDesc, Diagnostic> {
    let mut b = Builder {
        desc: SceneDesc::new(base_dir),
        gs: GraphicsState {
            ctm: Transform::IDENTITY,
            material: MaterialRef::Default,
            area_light: None,
            reverse_orientation: false,
            active_start: true,
            active_end: true,
            attrs: Attributes::default(),
            media: Default::default(),
        },
        stack: Vec::new(),
        coord_systems: HashMap::new(),
        object: None,
        object_names: HashMap::new(),
        pending_instances: Vec::new(),
        depth: 0,
        warned_once: Vec::new(),
    };
    match file {
        Some(path) => b.desc.note_read(path),
        None => b.desc.note_text(text),
    }
    b.run(SourceFile::new(name, text))?;
    for inst in std::mem::take(&mut b.pending_instances) {
        let Some(&object) = b.object_names.get(&inst.name) else {
            let names: Vec<&str> = b.object_names.keys().map(|s| s.as_str()).collect();
            let d = Diagnostic::error(&inst.loc, format!("object `{}` is not defined", inst.name));
            return Err(match suggest(&inst.name, &names, 2) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None => d.with_help("define it with ObjectBegin \"name\" ... ObjectEnd"),
            });
        };
        b.desc.instances.push(crate::desc::InstanceDesc {
            object,
            world_from_object: inst.world_from_object,
            loc: inst.loc,
        });
    }
    for (scope, _, loc) in std::mem::take(&mut b.stack) {
        let what = match scope {
            Scope::Attribute => "AttributeBegin has no matching AttributeEnd",
            Scope::Transform => "TransformBegin has no matching TransformEnd",
            Scope::Object => "ObjectBegin has no matching ObjectEnd",
        };
        b.desc.warnings.push(Diagnostic::warning(
            &loc,
            format!("{what}: expected it before the end of the input"),
        ));
    }
    Ok(b.desc)
}

/// A scene file's text; gzip-compressed files (`.pbrt.gz`, as pbrt-v4
/// reads) are decompressed.
pub(crate) fn read_scene_text(path: &Path) -> Result<String, String> {
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    let bytes = if bytes.starts_with(&[0x1f, 0x8b]) {
        use std::io::Read;
        let mut out = Vec::new();
        flate2::read::MultiGzDecoder::new(&bytes[..])
            .take(4 << 30)
            .read_to_end(&mut out)
            .map_err(|e| format!("corrupt gzip data: {e}"))?;
        out
    } else {
        bytes
    };
    String::from_utf8(bytes).map_err(|_| "the file is not UTF-8 text".to_string())
}

/// Parses a scene file; relative paths resolve against its folder.
pub fn parse_file(path: &Path) -> Result<SceneDesc, Diagnostic> {
    let text = read_scene_text(path).map_err(|e| {
        Diagnostic::plain_error(format!("cannot read scene file `{}`: {e}", path.display()))
    })?;
    let base = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    parse(&text, &path.display().to_string(), base, Some(path))
}

/// Strips one pair of enclosing brackets, if present.
fn unbracket(args: &[Token]) -> &[Token] {
    match args {
        [first, inner @ .., last]
            if first.kind == TokenKind::LBracket && last.kind == TokenKind::RBracket =>
        {
            inner
        }
        _ => args,
    }
}

fn is_bool_word(t: &Token) -> bool {
    matches!(&t.kind, TokenKind::Ident(s) if s == "true" || s == "false")
}

impl Builder {
    fn run(&mut self, file: Arc<SourceFile>) -> Result<(), Diagnostic> {
        let tokens = tokenize(&file)?;
        let mut i = 0;
        while i < tokens.len() {
            let dir = &tokens[i];
            let TokenKind::Ident(name) = &dir.kind else {
                return Err(Diagnostic::error(
                    &dir.loc,
                    format!("expected a directive, found {}", dir.describe()),
                ));
            };
            i += 1;
            let start = i;
            if name == "ActiveTransform"
                && matches!(tokens.get(i).map(|t| &t.kind), Some(TokenKind::Ident(_)))
            {
                i += 1;
            }
            while i < tokens.len()
                && (!matches!(tokens[i].kind, TokenKind::Ident(_)) || is_bool_word(&tokens[i]))
            {
                i += 1;
            }
            self.directive(dir, name, &tokens[start..i])?;
        }
        Ok(())
    }

    fn warn(&mut self, loc: &Loc, msg: impl Into<String>) {
        self.desc.warnings.push(Diagnostic::warning(loc, msg));
    }

    /// A warning given only at the first occurrence of `key` in the scene.
    fn warn_once(&mut self, key: &'static str, loc: &Loc, msg: impl Into<String>) {
        if !self.warned_once.contains(&key) {
            self.warned_once.push(key);
            self.warn(loc, msg);
        }
    }

    fn in_world(&self) -> bool {
        self.desc.saw_world_begin
    }

    fn require_world(&self, dir: &Token, name: &str) -> Result<(), Diagnostic> {
        if self.in_world() {
            return Ok(());
        }
        Err(Diagnostic::error(
            &dir.loc,
            format!("`{name}` is only allowed after WorldBegin"),
        )
        .with_help("scene contents (shapes, lights, materials, textures) go after WorldBegin"))
    }

    fn require_options(&self, dir: &Token, name: &str) -> Result<(), Diagnostic> {
        if !self.in_world() {
            return Ok(());
        }
        Err(Diagnostic::error(
            &dir.loc,
            format!("`{name}` is not allowed after WorldBegin"),
        )
        .with_help("camera, film, sampler, integrator and filter go before WorldBegin"))
    }

    fn no_args(dir: &Token, name: &str, args: &[Token]) -> Result<(), Diagnostic> {
        match args.first() {
            None => Ok(()),
            Some(t) => Err(Diagnostic::error(
                &t.loc,
                format!("`{name}` takes no arguments, found {}", t.describe()),
            ))
            .map_err(|d| d.with_help(format!("directive at {}", dir.loc))),
        }
    }

    /// Exactly `n` numbers, with or without enclosing brackets.
    fn numbers(dir: &Token, name: &str, args: &[Token], n: usize) -> Result<Vec<f32>, Diagnostic> {
        let inner = unbracket(args);
        let mut out = Vec::with_capacity(n);
        for t in inner {
            match t.kind {
                TokenKind::Num { value, .. } => out.push(value as f32),
                _ => {
                    return Err(Diagnostic::error(
                        &t.loc,
                        format!("`{name}` expects {n} numbers, found {}", t.describe()),
                    ))
                }
            }
        }
        if out.len() != n {
            return Err(Diagnostic::error(
                &dir.loc,
                format!("`{name}` expects {n} numbers, found {}", out.len()),
            ));
        }
        Ok(out)
    }

    /// The first `n` arguments as strings (with locations), and the rest.
    fn strings<'t>(
        dir: &Token,
        name: &str,
        args: &'t [Token],
        n: usize,
        usage: &str,
    ) -> Result<StringArgs<'t>, Diagnostic> {
        let mut out = Vec::with_capacity(n);
        for k in 0..n {
            match args.get(k).map(|t| (&t.kind, t)) {
                Some((TokenKind::Str(s), t)) => out.push((s.clone(), t.loc.clone())),
                Some((_, t)) => {
                    return Err(Diagnostic::error(
                        &t.loc,
                        format!(
                            "`{name}` expects a quoted string here, found {}",
                            t.describe()
                        ),
                    )
                    .with_help(format!("usage: {usage}")))
                }
                None => {
                    return Err(Diagnostic::error(
                        &dir.loc,
                        format!("`{name}` is missing arguments"),
                    )
                    .with_help(format!("usage: {usage}")))
                }
            }
        }
        Ok((out, &args[n..]))
    }

    /// `Name "type" params...` as an entity.
    fn entity(dir: &Token, name: &str, args: &[Token]) -> Result<Entity, Diagnostic> {
        let (s, rest) = Self::strings(
            dir,
            name,
            args,
            1,
            &format!("{name} \"type\" parameters..."),
        )?;
        let (ty, loc) = s.into_iter().next().expect("one string");
        Ok(Entity {
            ty,
            params: ParamSet::parse(rest)?,
            loc,
        })
    }

    fn directive(&mut self, dir: &Token, name: &str, args: &[Token]) -> Result<(), Diagnostic> {
        if self.transform_directive(dir, name, args)? {
            return Ok(());
        }
        match name {
            "Camera" => {
                self.require_options(dir, name)?;
                let mut entity = Self::entity(dir, name, args)?;
                upgrade::camera(&mut entity);
                if self.desc.camera.is_some() {
                    self.warn(&dir.loc, "Camera redefined; the last one is used");
                }
                self.coord_systems
                    .insert("camera".into(), self.gs.ctm.inverse());
                self.desc.camera = Some(crate::desc::CameraDesc {
                    entity,
                    camera_from_world: self.gs.ctm,
                    medium: self.gs.media.outside.clone(),
                });
            }
            "Film" | "Sampler" | "Integrator" | "PixelFilter" => {
                self.require_options(dir, name)?;
                let mut e = Self::entity(dir, name, args)?;
                match name {
                    "Film" => upgrade::film(&mut e),
                    "Sampler" => upgrade::sampler(&mut e),
                    "Integrator" => upgrade::integrator(&mut e, &mut self.desc.warnings),
                    _ => upgrade::filter(&mut e),
                }
                let slot = match name {
                    "Film" => &mut self.desc.film,
                    "Sampler" => &mut self.desc.sampler,
                    "Integrator" => &mut self.desc.integrator,
                    _ => &mut self.desc.filter,
                };
                let redefined = slot.replace(e).is_some();
                if redefined {
                    self.warn(&dir.loc, format!("{name} redefined; the last one is used"));
                }
            }
            "ColorSpace" => {
                let (s, rest) = Self::strings(dir, name, args, 1, "ColorSpace \"name\"")?;
                Self::no_args(dir, name, rest)?;
                if s[0].0 != "srgb" {
                    self.warn(
                        &s[0].1,
                        format!("color space `{}` is not supported; using sRGB", s[0].0),
                    );
                }
            }
            "Option" => {
                ParamSet::parse(args)?;
                self.warn(&dir.loc, "`Option` is not supported; ignored");
            }
            "WorldBegin" => {
                Self::no_args(dir, name, args)?;
                if self.in_world() {
                    return Err(Diagnostic::error(&dir.loc, "WorldBegin appears twice"));
                }
                self.desc.saw_world_begin = true;
                self.gs.ctm = Transform::IDENTITY;
                self.coord_systems
                    .insert("world".into(), Transform::IDENTITY);
            }
            _ => return self.world_directive(dir, name, args),
        }
        Ok(())
    }

    fn unknown_directive(dir: &Token, name: &str) -> Diagnostic {
        let d = Diagnostic::error(&dir.loc, format!("unknown directive `{name}`"));
        match suggest(name, DIRECTIVES, 3) {
            Some(s) => d.with_help(format!("did you mean `{s}`?")),
            None => d,
        }
    }
}
