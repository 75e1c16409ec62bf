//! Materials from `Material` / `MakeNamedMaterial` descriptions, one file
//! per pbrt-v4 material type, named as the runtime's [`crate::material`]
//! modules. This module dispatches on the type name and handles what every
//! material has (`displacement`, `normalmap`, the unused-parameter
//! warnings); [`common`] holds the builders' context and the parameter
//! readers several types share (roughness, eta, conductor optics).
//!
//! To add a material type: a file here whose `build(&Ctx, &mut Warnings)`
//! returns its [`MaterialKind`](crate::material::MaterialKind) and the
//! names of the parameters it reads, and one line in [`build_material`]'s
//! match.

mod coat;
mod coated_conductor;
mod coated_diffuse;
mod common;
mod conductor;
mod dielectric;
mod diffuse;
mod diffuse_transmission;
mod interface;
mod mix;
mod phong;
mod thin_dielectric;

use super::texture::TexBuilder;
use super::Warnings;
use crate::material::{Material, Shading};
use crate::texture::TexFloat;
use common::{Built, Ctx};
use lumis_scene::{Diagnostic, Entity, MaterialDesc, MaterialRef, SceneDesc};

pub struct BuiltMaterials {
    /// One per description material, in the description's order, then the default.
    pub materials: Vec<Material>,
    /// Index of the default material (pbrt's diffuse 0.5), appended last.
    pub default: u32,
    /// Copies of materials on surfaces between media, appended after the
    /// default: (material, interface) to the copy's id.
    with_media: std::collections::HashMap<(u32, crate::media::MediumInterface), u32>,
}

impl BuiltMaterials {
    /// The id of material `id` on a surface between media `mi`: a copy of
    /// it carrying the interface, made once per pair.
    pub fn with_media(&mut self, id: u32, mi: crate::media::MediumInterface) -> u32 {
        if let Some(&i) = self.with_media.get(&(id, mi)) {
            return i;
        }
        let mut m = self.materials[id as usize].clone();
        m.media = Some(mi);
        self.materials.push(m);
        let i = (self.materials.len() - 1) as u32;
        self.with_media.insert((id, mi), i);
        i
    }

    /// A copy of material `id` for a shape with an `alpha` cutout.
    pub fn with_alpha(&mut self, id: u32, alpha: crate::texture::TexFloat) -> u32 {
        let mut m = self.materials[id as usize].clone();
        m.alpha = Some(alpha);
        self.materials.push(m);
        (self.materials.len() - 1) as u32
    }

    /// The runtime id of the material a shape refers to: the material's
    /// index in `desc.materials` (materials are built in that order), or
    /// [`Self::default`]. An undefined name is an error at the reference.
    pub fn id(&self, desc: &SceneDesc, r: &MaterialRef) -> Result<u32, Diagnostic> {
        let i = match r {
            MaterialRef::Default => return Ok(self.default),
            MaterialRef::Index(i) => *i,
            MaterialRef::Named(name, _) => match desc.named_materials.get(name) {
                Some(&i) => i,
                // `SceneDesc::material` makes the located error (with suggestions).
                None => return desc.material(r).map(|_| self.default),
            },
        };
        Ok(if (i as usize) < desc.materials.len() {
            i
        } else {
            self.default
        })
    }
}

pub fn build_materials(
    desc: &SceneDesc,
    tex: &mut TexBuilder,
    w: &mut Warnings,
) -> Result<BuiltMaterials, Diagnostic> {
    let mut materials = Vec::with_capacity(desc.materials.len() + 1);
    for (i, m) in desc.materials.iter().enumerate() {
        materials.push(build_material(desc, i, m, tex, w)?);
    }
    let default = materials.len() as u32;
    materials.push(diffuse::default_kind().into());
    Ok(BuiltMaterials {
        materials,
        default,
        with_media: Default::default(),
    })
}

fn build_material(
    desc: &SceneDesc,
    index: usize,
    m: &MaterialDesc,
    tex: &mut TexBuilder,
    w: &mut Warnings,
) -> Result<Material, Diagnostic> {
    let e = &m.entity;
    let p = &e.params;
    p.mark_used("type");
    let c = Ctx {
        desc,
        index,
        m,
        p,
        tex,
    };
    let (kind, known) = match e.ty.as_str() {
        "diffuse" => diffuse::build(&c, w)?,
        "conductor" => conductor::build(&c, w)?,
        "dielectric" => dielectric::build(&c, w)?,
        "thindielectric" => thin_dielectric::build(&c, w)?,
        "diffusetransmission" => diffuse_transmission::build(&c, w)?,
        "coateddiffuse" => coated_diffuse::build(&c, w)?,
        "coatedconductor" => coated_conductor::build(&c, w)?,
        "phong" => phong::build(&c, w)?,
        "mix" => mix::build(&c, w)?,
        "interface" | "" | "none" => interface::build(&c, w)?,
        _ => unsupported(e, w),
    };
    let shading = if let Some(id) = tex.normal_map(p)? {
        Shading::NormalMap(id)
    } else if p.has("displacement") {
        match tex.float(p, "displacement", 0.0)? {
            TexFloat::Const(_) => Shading::Smooth,
            d => Shading::Bump(d),
        }
    } else {
        Shading::Smooth
    };
    let known = [&known[..], &["displacement", "normalmap"]].concat();
    w.unused(p, &format!("material \"{}\"", e.ty), &known);
    Ok(Material {
        kind,
        shading,
        media: None,
        alpha: None,
    })
}

/// A type lumis does not have: a warning, and the default material.
fn unsupported(e: &Entity, w: &mut Warnings) -> Built {
    w.push(Diagnostic::warning(
        &e.loc,
        format!(
            "material `{}` is not supported yet; using diffuse 0.5",
            e.ty
        ),
    ));
    for q in e.params.unused() {
        q.mark_used();
    }
    (diffuse::default_kind(), vec![])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn shapes_get_the_description_index_of_their_material() {
        let desc = lumis_scene::load_str(
            r#"WorldBegin
            Shape "sphere"
            MakeNamedMaterial "a" "string type" "diffuse"
            Material "conductor"
            Shape "sphere"
            MakeNamedMaterial "b" "string type" "dielectric"
            NamedMaterial "a" Shape "sphere"
            NamedMaterial "b" Shape "sphere"
            NamedMaterial "missing" Shape "sphere""#,
            "ids.pbrt",
            Path::new("."),
        )
        .unwrap();
        let mats = BuiltMaterials {
            materials: Vec::new(),
            default: desc.materials.len() as u32,
            with_media: Default::default(),
        };
        let ids: Vec<_> = desc.shapes[..4]
            .iter()
            .map(|s| mats.id(&desc, &s.material).unwrap())
            .collect();
        assert_eq!(ids, [3, 1, 0, 2]);
        let err = mats.id(&desc, &desc.shapes[4].material).unwrap_err();
        assert!(err.message.contains("`missing` is not defined"), "{err:?}");
    }
}
