//! `plymesh`: a triangle mesh read from a PLY file (`filename`).

use super::common::{make_mesh, Built, Ctx};
use crate::load::Warnings;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    let (e, p) = (c.e, c.p);
    let file = p.get_string("filename", "")?;
    if file.is_empty() {
        return Err(Diagnostic::error(
            &e.loc,
            "plymesh needs \"string filename\"",
        ));
    }
    let path = c.desc.read_path(&file);
    let loc = p.loc_of("filename").unwrap_or(e.loc.clone());
    let ply = lumis_scene::ply::read_ply(&path)
        .map_err(|err| Diagnostic::error(&loc, format!("{err}")))?;
    w.unsupported(p, &["displacement", "edgelength"], "plymesh", "ignored");
    w.unused(p, "shape \"plymesh\"", &["filename"]);
    let indices = ply.indices.iter().map(|&i| i as i32).collect();
    let mesh = make_mesh(
        e,
        ply.positions,
        ply.normals,
        ply.uvs,
        indices,
        &c.xf,
        c.flip,
    )?;
    Ok(Built::Mesh(mesh))
}
