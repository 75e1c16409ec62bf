//! Textures from `Texture` descriptions, and texture-or-value material
//! parameters. Image files are read once per (file, encoding).

use super::spectrum::rgb_param;
use super::Warnings;
use crate::texture::image::{read_texture_image, Encoding};
use crate::texture::*;
use lumis_math::{Rgb, Vec3};
use lumis_scene::{Diagnostic, Loc, ParamSet, SceneDesc, TextureDesc};
use std::collections::HashMap;
use std::path::PathBuf;

pub struct TexBuilder<'a> {
    desc: &'a SceneDesc,
    pub textures: Textures,
    floats: HashMap<String, u32>,
    spectra: HashMap<String, u32>,
    images: HashMap<(PathBuf, String), u32>,
    normal_maps: HashMap<PathBuf, u32>,
}

impl<'a> TexBuilder<'a> {
    /// Builds every texture of the description, in order (a texture may use earlier ones).
    pub fn new(desc: &'a SceneDesc, w: &mut Warnings) -> Result<TexBuilder<'a>, Diagnostic> {
        let mut b = TexBuilder {
            desc,
            textures: Textures::default(),
            floats: HashMap::new(),
            spectra: HashMap::new(),
            images: HashMap::new(),
            normal_maps: HashMap::new(),
        };
        for t in &desc.textures {
            let float = t.kind == "float";
            let tex = b.build(t, float, w)?;
            let id = b.textures.push(tex);
            let names = if float { &mut b.floats } else { &mut b.spectra };
            names.insert(t.name.clone(), id);
        }
        Ok(b)
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
    fn float_rgb(&self, p: &ParamSet, name: &str, default: f32) -> Result<TexRgb, Diagnostic> {
        Ok(match self.float(p, name, default)? {
            TexFloat::Const(v) => TexRgb::Const(Rgb::splat(v)),
            TexFloat::Tex(id) => TexRgb::Tex(id),
        })
    }

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
        let path = self.desc.resolve_path(&file);
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

    pub(super) fn desc(&self) -> &SceneDesc {
        self.desc
    }

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

    fn build(
        &mut self,
        t: &TextureDesc,
        float: bool,
        w: &mut Warnings,
    ) -> Result<Texture, Diagnostic> {
        let e = &t.entity;
        let p = &e.params;
        let map_params = super::textures_procedural::MAP2D;
        let (tex, known): (Texture, Vec<&str>) = match e.ty.as_str() {
            "constant" => (
                Texture::Constant(match self.value(p, "value", 1.0, float)? {
                    TexRgb::Const(c) => c,
                    TexRgb::Tex(id) => return Ok(self.textures.textures[id as usize]),
                }),
                vec!["value"],
            ),
            "scale" => (
                Texture::Scale(ScaleTexture {
                    tex: self.value(p, "tex", 1.0, float)?,
                    scale: self.float_rgb(p, "scale", 1.0)?,
                }),
                vec!["tex", "scale"],
            ),
            "mix" => (
                Texture::Mix(MixTexture {
                    tex1: self.value(p, "tex1", 0.0, float)?,
                    tex2: self.value(p, "tex2", 1.0, float)?,
                    amount: self.float_rgb(p, "amount", 0.5)?,
                }),
                vec!["tex1", "tex2", "amount"],
            ),
            "directionmix" => {
                let d = t.object_to_world.vector(p.get_vector3("dir", Vec3::Y)?);
                (
                    Texture::DirectionMix(DirectionMixTexture {
                        tex1: self.value(p, "tex1", 0.0, float)?,
                        tex2: self.value(p, "tex2", 1.0, float)?,
                        dir: d.normalize_or_zero(),
                    }),
                    vec!["tex1", "tex2", "dir"],
                )
            }
            "imagemap" => (
                Texture::Image(self.image(t, float, w)?),
                [
                    &[
                        "filename",
                        "filter",
                        "maxanisotropy",
                        "wrap",
                        "scale",
                        "invert",
                        "encoding",
                    ][..],
                    &map_params,
                ]
                .concat(),
            ),
            other => {
                if let Some(built) = super::textures_procedural::build(self, t, float, w)? {
                    w.unused(p, &format!("texture \"{other}\""), &built.1);
                    return Ok(built.0);
                }
                w.push(Diagnostic::warning(
                    &e.loc,
                    format!("texture type `{other}` is not supported yet; using a constant 0.5"),
                ));
                for q in p.unused() {
                    q.mark_used();
                }
                (Texture::Constant(Rgb::splat(0.5)), vec![])
            }
        };
        w.unused(p, &format!("texture \"{}\"", e.ty), &known);
        Ok(tex)
    }

    fn image(
        &mut self,
        t: &TextureDesc,
        float: bool,
        w: &mut Warnings,
    ) -> Result<ImageTexture, Diagnostic> {
        let e = &t.entity;
        let p = &e.params;
        let loc = |n: &str| p.loc_of(n).unwrap_or_else(|| e.loc.clone());
        let Some(file) = p.get_opt_string("filename")? else {
            return Err(Diagnostic::error(
                &e.loc,
                "imagemap texture needs a `filename`",
            ));
        };
        let enc_name = p.get_string("encoding", "sRGB")?;
        let enc = Encoding::parse(&enc_name).ok_or_else(|| {
            Diagnostic::error(&loc("encoding"), format!("unknown encoding `{enc_name}`"))
                .with_help("expected sRGB, linear or \"gamma <value>\"")
        })?;
        let filter = match p.get_string("filter", "bilinear")?.as_str() {
            "point" => FilterKind::Point,
            "bilinear" => FilterKind::Bilinear,
            "trilinear" => FilterKind::Trilinear,
            "ewa" | "EWA" => {
                w.push(Diagnostic::warning(
                    &loc("filter"),
                    "EWA filtering is not supported yet; using trilinear",
                ));
                FilterKind::Trilinear
            }
            other => {
                return Err(
                    Diagnostic::error(&loc("filter"), format!("unknown filter `{other}`"))
                        .with_help("expected point, bilinear, trilinear or ewa"),
                )
            }
        };
        let wrap_name = p.get_string("wrap", "repeat")?;
        let wrap = WrapMode::parse(&wrap_name).ok_or_else(|| {
            Diagnostic::error(&loc("wrap"), format!("unknown wrap mode `{wrap_name}`"))
                .with_help("expected repeat, black or clamp")
        })?;
        p.mark_used("maxanisotropy");
        let path = self.desc.resolve_path(&file);
        let key = (path.clone(), enc_name);
        let mipmap = match self.images.get(&key) {
            Some(&id) => id,
            None => {
                let level = read_texture_image(&path, enc).map_err(|err| {
                    Diagnostic::error(
                        &loc("filename"),
                        format!("cannot read texture {}: {err}", path.display()),
                    )
                })?;
                self.textures.mipmaps.push(MipMap::new(level));
                let id = (self.textures.mipmaps.len() - 1) as u32;
                self.images.insert(key, id);
                id
            }
        };
        Ok(ImageTexture {
            mipmap,
            mapping: self.mapping(t, w)?,
            filter,
            wrap,
            scale: p.get_float("scale", 1.0)?,
            invert: p.get_bool("invert", false)?,
            float,
        })
    }
}
