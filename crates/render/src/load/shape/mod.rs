//! Shapes from `Shape` descriptions, one file per pbrt-v4 shape type:
//! trianglemesh, plymesh, bilinearmesh, loopsubdiv (all triangle meshes in
//! the end), sphere, cylinder and disk. This module builds the scene's and
//! the objects' shapes with their material ids and area lights, dispatches
//! on the type name and stores each built shape; [`common`] holds the
//! builders' context and the mesh check they share.
//!
//! To add a shape type: a file here whose `build(&Ctx, &mut Warnings)`
//! returns its geometry as a [`Built`] (reading its parameters and
//! reporting unused ones), and one line in [`build_shape`]'s match.

mod bilinearmesh;
mod common;
mod cylinder;
mod disk;
mod loopsubdiv;
mod plymesh;
mod sphere;
mod trianglemesh;

use super::material::BuiltMaterials;
use super::medium::BuiltMedia;
use super::texture::TexBuilder;
use super::Warnings;
use crate::geometry::{Prim, TriangleMesh};
use crate::light::Light;
use crate::media::LightMedium;
use crate::scene::{Instance, InstanceSet, PrimInfo, Shapes, NO_LIGHT};
use crate::texture::TexFloat;
use common::{Built, Ctx};
use lumis_scene::{Diagnostic, SceneDesc, ShapeDesc};

/// What a shape's surface is made of: materials (extended with copies for
/// media interfaces and cutouts), media and textures.
pub struct Surfaces<'a, 't> {
    pub mats: &'a mut BuiltMaterials,
    pub media: &'a BuiltMedia,
    pub tex: &'a TexBuilder<'t>,
    /// The medium each area light made so far emits into (its shape's
    /// interface, or the outside medium in effect), in the order of the lights.
    pub light_media: Vec<LightMedium>,
}

impl Surfaces<'_, '_> {
    /// The material id of shape `s`: its material, on its medium interface
    /// (if it changes the medium), with its `alpha` cutout (if any).
    fn material(
        &mut self,
        desc: &SceneDesc,
        s: &ShapeDesc,
        w: &mut Warnings,
    ) -> Result<u32, Diagnostic> {
        let mut material = self.mats.id(desc, &s.material)?;
        if let Some(mi) = self.media.interface(&s.media)? {
            material = self.mats.with_media(material, mi);
        }
        let loc = || {
            let p = &s.entity.params;
            p.loc_of("alpha").unwrap_or_else(|| s.entity.loc.clone())
        };
        match self.tex.float(&s.entity.params, "alpha", 1.0)? {
            TexFloat::Const(a) if a >= 1.0 => {}
            TexFloat::Const(a) if !(a >= 0.0) => {
                return Err(Diagnostic::error(
                    &loc(),
                    format!("`alpha` must be in [0, 1] (above 1 counts as 1), found {a}"),
                ));
            }
            // Light sampling picks points on an emitter whatever its alpha:
            // cutting rays through it would make the two disagree.
            _ if s.area_light.is_some() => w.push(Diagnostic::warning(
                &loc(),
                "`alpha` on an emitting shape is ignored (the whole shape emits and is solid)",
            )),
            alpha => material = self.mats.with_alpha(material, alpha),
        }
        Ok(material)
    }
}

pub fn build_shapes(
    desc: &SceneDesc,
    surf: &mut Surfaces,
    shapes: &mut Shapes,
    lights: &mut Vec<Light>,
    w: &mut Warnings,
) -> Result<(Vec<PrimInfo>, InstanceSet), Diagnostic> {
    let prims = add_shapes(desc, &desc.shapes, surf, shapes, lights, w)?;
    // Objects: built once, in the space of their shapes' own transforms
    // (area lights were already refused by the parser, as pbrt-v4 does).
    let mut set = InstanceSet::default();
    for o in &desc.objects {
        let before = lights.len();
        let prims = add_shapes(desc, &o.shapes, surf, shapes, lights, w)?;
        debug_assert_eq!(lights.len(), before, "objects carry no area lights");
        set.objects.push(prims);
    }
    for inst in &desc.instances {
        if set.objects[inst.object as usize].is_empty() {
            w.push(Diagnostic::warning(
                &inst.loc,
                format!(
                    "object `{}` has no shapes; this instance adds nothing",
                    desc.objects[inst.object as usize].name
                ),
            ));
            continue;
        }
        set.instances.push(Instance {
            object: inst.object,
            world_from_object: inst.world_from_object,
        });
    }
    Ok((prims, set))
}

fn add_shapes(
    desc: &SceneDesc,
    list: &[ShapeDesc],
    surf: &mut Surfaces,
    shapes: &mut Shapes,
    lights: &mut Vec<Light>,
    w: &mut Warnings,
) -> Result<Vec<PrimInfo>, Diagnostic> {
    let mut prims = Vec::new();
    for s in list {
        let material = surf.material(desc, s, w)?;
        let new_prims = match build_shape(desc, s, w)? {
            Some(built) => store(shapes, built),
            None => continue,
        };
        if new_prims.is_empty() {
            continue;
        }
        let first_light = lights.len() as u32;
        if let Some(al) = &s.area_light {
            let built = super::area_lights::area_lights(desc, al, shapes, &new_prims, w)?;
            let medium = match surf.media.interface(&s.media)? {
                Some(mi) => LightMedium::Between(mi),
                None => LightMedium::In(surf.media.id(&s.media.outside)?),
            };
            surf.light_media
                .extend(std::iter::repeat_n(medium, built.len()));
            lights.extend(built.into_iter().map(Light::Area));
        }
        let has_light = lights.len() as u32 > first_light;
        for (i, &p) in new_prims.iter().enumerate() {
            let light = if has_light {
                first_light + i as u32
            } else {
                NO_LIGHT
            };
            prims.push(PrimInfo {
                prim: p,
                material,
                light,
            });
        }
    }
    Ok(prims)
}

/// One shape's geometry, or `None` for a type lumis does not have (a warning).
fn build_shape(
    desc: &SceneDesc,
    s: &ShapeDesc,
    w: &mut Warnings,
) -> Result<Option<Built>, Diagnostic> {
    let e = &s.entity;
    let p = &e.params;
    w.unsupported(p, &["emissionfilename"], "shape", "ignored");
    let xf = s.object_to_world;
    let c = Ctx {
        desc,
        s,
        e,
        p,
        xf,
        flip: s.reverse_orientation ^ xf.swaps_handedness(),
    };
    Ok(Some(match e.ty.as_str() {
        "trianglemesh" => trianglemesh::build(&c, w)?,
        "plymesh" => plymesh::build(&c, w)?,
        "bilinearmesh" => bilinearmesh::build(&c, w)?,
        "loopsubdiv" => loopsubdiv::build(&c, w)?,
        "sphere" => sphere::build(&c, w)?,
        "cylinder" => cylinder::build(&c, w)?,
        "disk" => disk::build(&c, w)?,
        other => {
            for q in p.unused() {
                q.mark_used();
            }
            w.push(Diagnostic::warning(
                &e.loc,
                format!("shape `{other}` is not supported yet; skipped"),
            ));
            return Ok(None);
        }
    }))
}

/// Adds a built shape to `shapes`; its primitives (several for a mesh).
fn store(shapes: &mut Shapes, built: Built) -> Vec<Prim> {
    match built {
        Built::Mesh(mesh) => push_mesh(shapes, mesh),
        Built::Sphere(sphere) => {
            shapes.spheres.push(sphere);
            vec![Prim::Sphere(shapes.spheres.len() as u32 - 1)]
        }
        Built::Cylinder(c) => {
            shapes.cylinders.push(c);
            vec![Prim::Cylinder(shapes.cylinders.len() as u32 - 1)]
        }
        Built::Disk(d) => {
            shapes.disks.push(d);
            vec![Prim::Disk(shapes.disks.len() as u32 - 1)]
        }
    }
}

/// Adds a mesh; degenerate (zero-area) triangles are left out.
fn push_mesh(shapes: &mut Shapes, mesh: TriangleMesh) -> Vec<Prim> {
    let id = shapes.meshes.len() as u32;
    let prims = (0..mesh.triangle_count() as u32)
        .filter(|&t| mesh.area(t) > 0.0)
        .map(|tri| Prim::Triangle { mesh: id, tri })
        .collect();
    shapes.meshes.push(mesh);
    prims
}
