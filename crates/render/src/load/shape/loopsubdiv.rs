//! `loopsubdiv`: a triangle control mesh (`P`, `indices`) refined `levels`
//! times by Loop subdivision, with the limit surface's normals.

use super::common::{make_mesh, Built, Ctx};
use crate::geometry::subdiv::loop_subdivide;
use crate::load::Warnings;
use lumis_math::Transform;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    let (e, p) = (c.e, c.p);
    let pos = p
        .get_point3s("P")?
        .ok_or_else(|| Diagnostic::error(&e.loc, "loopsubdiv needs \"point3 P\""))?;
    let indices = p
        .get_ints("indices")?
        .ok_or_else(|| Diagnostic::error(&e.loc, "loopsubdiv needs \"integer indices\""))?;
    let levels = p.get_int("levels", 3)?;
    w.unused(p, "shape \"loopsubdiv\"", &["P", "indices", "levels"]);
    if !(0..=12).contains(&levels) {
        return Err(Diagnostic::error(
            &p.loc_of("levels").unwrap_or(e.loc.clone()),
            format!("loopsubdiv levels must be 0 to 12, found {levels}"),
        ));
    }
    // Checked as a mesh first (index range, multiple of 3).
    let mesh = make_mesh(e, pos, None, None, indices, &Transform::IDENTITY, false)?;
    let sub = loop_subdivide(&mesh.positions, &mesh.indices, levels as u32)
        .map_err(|m| Diagnostic::error(&e.loc, format!("loopsubdiv: {m}")))?;
    let indices = sub.indices.iter().map(|&i| i as i32).collect();
    let mesh = make_mesh(
        e,
        sub.positions,
        Some(sub.normals),
        None,
        indices,
        &c.xf,
        c.flip,
    )?;
    Ok(Built::Mesh(mesh))
}
