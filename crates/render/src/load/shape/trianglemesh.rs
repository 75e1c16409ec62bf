//! `trianglemesh`: vertices `P`, `indices` (optional for one triangle),
//! optional per-vertex normals `N` and `uv`.

use super::common::{make_mesh, Built, Ctx};
use crate::load::Warnings;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    let (e, p) = (c.e, c.p);
    let pos = p
        .get_point3s("P")?
        .ok_or_else(|| Diagnostic::error(&e.loc, "trianglemesh needs \"point3 P\""))?;
    let indices = match p.get_ints("indices")? {
        Some(i) => i,
        None if pos.len() == 3 => vec![0, 1, 2],
        None => {
            return Err(Diagnostic::error(
                &e.loc,
                "trianglemesh needs \"integer indices\" (only a single triangle may omit them)",
            ))
        }
    };
    let normals = p.get_normals("N")?;
    let uvs = p.get_point2s("uv")?;
    p.mark_used("S");
    p.mark_used("faceIndices");
    w.unused(
        p,
        "shape \"trianglemesh\"",
        &["P", "indices", "N", "uv", "S", "faceIndices"],
    );
    let mesh = make_mesh(e, pos, normals, uvs, indices, &c.xf, c.flip)?;
    Ok(Built::Mesh(mesh))
}
