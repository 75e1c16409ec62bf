//! What the shape builders share: their context ([`Ctx`]), what each
//! returns ([`Built`]), and [`make_mesh`], which checks a triangle mesh's
//! parameters and transforms it to world space. Imports no sibling module,
//! so every shape file may use it.

use crate::geometry::{Cylinder, Disk, Sphere, TriangleMesh};
use lumis_math::{Transform, Vec2, Vec3};
use lumis_scene::{Diagnostic, Entity, ParamSet, SceneDesc, ShapeDesc};

/// One shape description being built.
pub(super) struct Ctx<'a> {
    pub desc: &'a SceneDesc,
    pub s: &'a ShapeDesc,
    pub e: &'a Entity,
    /// `e`'s parameters.
    pub p: &'a ParamSet,
    /// World from object.
    pub xf: Transform,
    /// Whether triangle normals flip: `ReverseOrientation` xor a
    /// handedness-swapping transform.
    pub flip: bool,
}

/// A shape's geometry, in world space.
pub(super) enum Built {
    Mesh(TriangleMesh),
    Sphere(Sphere),
    Cylinder(Cylinder),
    Disk(Disk),
}

pub(super) fn make_mesh(
    e: &Entity,
    pos: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    indices: Vec<i32>,
    xf: &Transform,
    flip: bool,
) -> Result<TriangleMesh, Diagnostic> {
    if !indices.len().is_multiple_of(3) {
        return Err(Diagnostic::error(
            &e.loc,
            format!("{} indices is not a multiple of 3", indices.len()),
        ));
    }
    if let Some(&bad) = indices.iter().find(|&&i| i < 0 || i as usize >= pos.len()) {
        return Err(Diagnostic::error(
            &e.loc,
            format!(
                "vertex index {bad} is out of range (the mesh has {} vertices)",
                pos.len()
            ),
        ));
    }
    if let Some(n) = &normals {
        if n.len() != pos.len() {
            return Err(Diagnostic::error(
                &e.loc,
                format!("{} normals for {} vertices", n.len(), pos.len()),
            ));
        }
    }
    if let Some(uv) = &uvs {
        if uv.len() != pos.len() {
            return Err(Diagnostic::error(
                &e.loc,
                format!("{} uvs for {} vertices", uv.len(), pos.len()),
            ));
        }
    }
    Ok(TriangleMesh {
        positions: pos.iter().map(|&v| xf.point(v)).collect(),
        normals: normals.map(|n| {
            n.iter()
                .map(|&v| xf.normal(v).normalize_or_zero())
                .collect()
        }),
        uvs,
        indices: indices.iter().map(|&i| i as u32).collect(),
        flip_normals: flip,
    })
}
