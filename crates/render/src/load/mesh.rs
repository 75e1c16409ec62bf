//! Triangle meshes from scene parameters: checked, transformed to world space.

use crate::geometry::{Prim, TriangleMesh};
use crate::scene::Shapes;
use lumis_math::{Vec2, Vec3};
use lumis_scene::{Diagnostic, Entity};

pub(super) fn make_mesh(
    e: &Entity,
    pos: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    indices: Vec<i32>,
    xf: &lumis_math::Transform,
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

/// Adds a mesh; degenerate (zero-area) triangles are left out.
pub(super) fn push_mesh(shapes: &mut Shapes, mesh: TriangleMesh) -> Vec<Prim> {
    let id = shapes.meshes.len() as u32;
    let prims = (0..mesh.triangle_count() as u32)
        .filter(|&t| mesh.area(t) > 0.0)
        .map(|tri| Prim::Triangle { mesh: id, tri })
        .collect();
    shapes.meshes.push(mesh);
    prims
}
