//! What the texture builders share: [`TexBuilder`], the texture table under
//! construction with its file caches, and the texture-or-value parameter
//! readers that textures and materials use; the 2D mapping parameters.
//! Imports no sibling module, so every texture file may use it.

use crate::load::spectrum::rgb_param;
use crate::load::Warnings;
use crate::texture::image::{read_texture_image, Encoding};
use crate::texture::{Mapping2D, Mapping3D, MipMap, TexFloat, TexRgb, Texture, Textures};
use lumis_math::{Rgb, Vec3};
use lumis_scene::{Diagnostic, Loc, ParamSet, SceneDesc, TextureDesc};
use std::collections::HashMap;
use std::path::PathBuf;

/// A texture's value and the names of the parameters its type reads.
pub(super) type Built = (Texture, Vec<&'static str>);

/// Parameter names of the 2D mappings.
pub(super) const MAP2D: [&str; 7] = [
    "mapping", "uscale", "vscale", "udelta", "vdelta", "v1", "v2",
];

pub struct TexBuilder<'a> {
    desc: &'a SceneDesc,
    pub textures: Textures,
    floats: HashMap<String, u32>,
    spectra: HashMap<String, u32>,
    images: HashMap<(PathBuf, String), u32>,
    normal_maps: HashMap<PathBuf, u32>,
}

impl<'a> TexBuilder<'a> {
    /// No textures yet.
    pub(super) fn new(desc: &'a SceneDesc) -> TexBuilder<'a> {
        TexBuilder {
            desc,
            textures: Textures::default(),
            floats: HashMap::new(),
            spectra: HashMap::new(),
            images: HashMap::new(),
            normal_maps: HashMap::new(),
        }
    }

    /// Adds texture `t`'s value, under its name among the float or spectrum textures.
    pub(super) fn push(&mut self, t: &TextureDesc, float: bool, tex: Texture) {
        let id = self.textures.push(tex);
        let names = if float {
            &mut self.floats
        } else {
            &mut self.spectra
        };
        names.insert(t.name.clone(), id);
    }

    fn lookup(&self, p: &ParamSet, name: &str, float: bool) -> Result<Option<u32>, Diagnostic> {
        let Some(tex) = p.get_texture(name) else {
            return Ok(None);
        };
        let (first, second) = if float {
            (&self.floats, &self.spectra)
        } else {
            (&self.spectra, &self.floats)
        };
        match first.get(&tex).or_else(|| second.get(&tex)) {
            Some(&id) => Ok(Some(id)),
            None => Err(Diagnostic::error(
                &p.loc_of(name).unwrap_or_else(Loc::none),
                format!(
                    "no {} texture named `{tex}` is defined before this point",
                    if float { "float" } else { "spectrum" }
                ),
            )),
        }
    }

    /// A spectrum parameter that may be a texture.
    pub fn spectrum(&self, p: &ParamSet, name: &str, default: Rgb) -> Result<TexRgb, Diagnostic> {
        if let Some(id) = self.lookup(p, name, false)? {
            return Ok(TexRgb::Tex(id));
        }
        if p.param(name).is_some_and(|q| q.ty == "float") {
            return Ok(TexRgb::Const(Rgb::splat(p.get_float(name, 0.0)?)));
        }
        Ok(TexRgb::Const(
            rgb_param(self.desc, p, name)?.unwrap_or(default),
        ))
    }

    /// A float parameter that may be a texture.
    pub fn float(&self, p: &ParamSet, name: &str, default: f32) -> Result<TexFloat, Diagnostic> {
        if let Some(id) = self.lookup(p, name, true)? {
            return Ok(TexFloat::Tex(id));
        }
        Ok(TexFloat::Const(p.get_float(name, default)?))
    }

    /// A float texture parameter in a texture (`tex1`, `amount`, ...), as RGB.
    pub(super) fn float_rgb(
        &self,
        p: &ParamSet,
        name: &str,
        default: f32,
    ) -> Result<TexRgb, Diagnostic> {
        Ok(match self.float(p, name, default)? {
            TexFloat::Const(v) => TexRgb::Const(Rgb::splat(v)),
            TexFloat::Tex(id) => TexRgb::Tex(id),
        })
    }

    /// A texture's value parameter: a float texture's as RGB, a spectrum texture's as is.
    pub(super) fn value(
        &self,
        p: &ParamSet,
        name: &str,
        default: f32,
        float: bool,
    ) -> Result<TexRgb, Diagnostic> {
        if float {
            self.float_rgb(p, name, default)
        } else {
            self.spectrum(p, name, Rgb::splat(default))
        }
    }

    /// A `normalmap` image (linear), shared by file.
    pub fn normal_map(&mut self, p: &ParamSet) -> Result<Option<u32>, Diagnostic> {
        let Some(file) = p.get_opt_string("normalmap")? else {
            return Ok(None);
        };
        let path = self.desc.read_path(&file);
        if let Some(&id) = self.normal_maps.get(&path) {
            return Ok(Some(id));
        }
        let loc = p.loc_of("normalmap").unwrap_or_else(Loc::none);
        let level = read_texture_image(&path, Encoding::Linear).map_err(|e| {
            Diagnostic::error(
                &loc,
                format!("cannot read normal map {}: {e}", path.display()),
            )
        })?;
        self.textures.normal_maps.push(level);
        let id = (self.textures.normal_maps.len() - 1) as u32;
        self.normal_maps.insert(path, id);
        Ok(Some(id))
    }

    /// The id of the image file at `path` read with encoding `enc`
    /// (`enc_name` as written), read once per (file, encoding).
    pub(super) fn image(
        &mut self,
        path: PathBuf,
        enc_name: String,
        enc: Encoding,
        loc: &Loc,
    ) -> Result<u32, Diagnostic> {
        let key = (path, enc_name);
        if let Some(&id) = self.images.get(&key) {
            return Ok(id);
        }
        let level = read_texture_image(&key.0, enc).map_err(|err| {
            Diagnostic::error(
                loc,
                format!("cannot read texture {}: {err}", key.0.display()),
            )
        })?;
        self.textures.mipmaps.push(MipMap::new(level));
        let id = (self.textures.mipmaps.len() - 1) as u32;
        self.images.insert(key, id);
        Ok(id)
    }

    pub(in crate::load) fn desc(&self) -> &SceneDesc {
        self.desc
    }

    /// Texture `t`'s 2D mapping from the [`MAP2D`] parameters.
    pub(super) fn mapping(
        &self,
        t: &TextureDesc,
        w: &mut Warnings,
    ) -> Result<Mapping2D, Diagnostic> {
        let p = &t.entity.params;
        let ty = p.get_string("mapping", "uv")?;
        let tex_from_world = t.object_to_world.inverse();
        let (du, dv) = (p.get_float("udelta", 0.0)?, p.get_float("vdelta", 0.0)?);
        Ok(match ty.as_str() {
            "uv" => Mapping2D::Uv {
                su: p.get_float("uscale", 1.0)?,
                sv: p.get_float("vscale", 1.0)?,
                du,
                dv,
            },
            "spherical" => Mapping2D::Spherical { tex_from_world },
            "cylindrical" => Mapping2D::Cylindrical { tex_from_world },
            "planar" => Mapping2D::Planar {
                tex_from_world,
                vs: p.get_vector3("v1", Vec3::X)?,
                vt: p.get_vector3("v2", Vec3::Y)?,
                ds: du,
                dt: dv,
            },
            other => {
                w.push(Diagnostic::warning(
                    &p.loc_of("mapping").unwrap_or_else(|| t.entity.loc.clone()),
                    format!("unknown texture mapping `{other}`; using `uv` (expected uv, spherical, cylindrical or planar)"),
                ));
                Mapping2D::Uv {
                    su: 1.0,
                    sv: 1.0,
                    du,
                    dv,
                }
            }
        })
    }
}

/// The 3D mapping of the solid textures: the texture's own space.
pub(super) fn map3d(t: &TextureDesc) -> Mapping3D {
    Mapping3D {
        tex_from_world: t.object_to_world.inverse(),
    }
}
