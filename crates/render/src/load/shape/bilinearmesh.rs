//! `bilinearmesh`: pbrt-v4's bilinear patches (`P`, `indices` in fours,
//! optional `uv` and `N`), rendered as triangles: planar patches exactly,
//! twisted ones as a fine grid on the bilinear surface.

use super::common::{make_mesh, Built, Ctx};
use crate::load::Warnings;
use lumis_math::{Transform, Vec2, Vec3};
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    let (e, p) = (c.e, c.p);
    let pos = p
        .get_point3s("P")?
        .ok_or_else(|| Diagnostic::error(&e.loc, "bilinearmesh needs \"point3 P\""))?;
    let indices = match p.get_ints("indices")? {
        Some(i) => i,
        None if pos.len() == 4 => vec![0, 1, 2, 3],
        None => {
            return Err(Diagnostic::error(
                &e.loc,
                "bilinearmesh needs \"integer indices\" (only a single patch may omit them)",
            ))
        }
    };
    let uvs = p.get_point2s("uv")?;
    let normals = p.get_normals("N")?;
    p.mark_used("faceIndices");
    w.unused(
        p,
        "shape \"bilinearmesh\"",
        &["P", "indices", "uv", "N", "faceIndices"],
    );
    if !indices.len().is_multiple_of(4) {
        return Err(Diagnostic::error(
            &e.loc,
            format!(
                "bilinearmesh: {} indices is not a multiple of 4",
                indices.len()
            ),
        ));
    }
    // Checked as a mesh (index range, uv and normal counts) before use.
    let tris: Vec<i32> = indices
        .chunks(4)
        .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
        .collect();
    let checked = make_mesh(e, pos, normals, uvs, tris, &Transform::IDENTITY, false)?;
    let idx: Vec<u32> = indices.iter().map(|&i| i as u32).collect();
    let (bp, buv, bn, bi) = bilinear_triangles(
        &checked.positions,
        &idx,
        checked.uvs.as_deref(),
        checked.normals.as_deref(),
    );
    let mesh = make_mesh(e, bp, bn, Some(buv), bi, &c.xf, c.flip)?;
    Ok(Built::Mesh(mesh))
}

/// Grid cells per side for a non-planar bilinear patch.
const BILINEAR_CELLS: usize = 16;

/// pbrt-v4's `bilinearmesh` as triangles: each patch (vertices p00, p10, p01,
/// p11) is evaluated on its bilinear surface at a grid of (u, v). A planar
/// patch is its two triangles exactly (its bilinear surface is the planar
/// quad); a non-planar one becomes a 16 x 16 grid, within about 1/512 of the
/// patch's twist of pbrt-v4's exact surface. Returns positions, uvs,
/// normals (if given) and triangle indices.
#[allow(clippy::type_complexity)]
fn bilinear_triangles(
    p: &[Vec3],
    idx: &[u32],
    uv: Option<&[Vec2]>,
    n: Option<&[Vec3]>,
) -> (Vec<Vec3>, Vec<Vec2>, Option<Vec<Vec3>>, Vec<i32>) {
    let (mut op, mut ouv, mut on, mut oi) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for q in idx.chunks(4) {
        let v = [q[0], q[1], q[2], q[3]].map(|i| i as usize);
        let c = v.map(|i| p[i]);
        // Twist: distance of p11 from the plane of the other three.
        let nrm = (c[1] - c[0]).cross(c[2] - c[0]);
        let planar = (c[3] - c[0]).dot(nrm).abs() <= 1e-6 * nrm.length() * (c[3] - c[0]).length();
        let cells = if planar { 1 } else { BILINEAR_CELLS };
        let lerp4 = |a: [Vec3; 4], s: f32, t: f32| {
            (1.0 - s) * (1.0 - t) * a[0]
                + s * (1.0 - t) * a[1]
                + (1.0 - s) * t * a[2]
                + s * t * a[3]
        };
        let base = op.len() as i32;
        for j in 0..=cells {
            for i in 0..=cells {
                let (s, t) = (i as f32 / cells as f32, j as f32 / cells as f32);
                op.push(lerp4(c, s, t));
                let st = match uv {
                    Some(uv) => {
                        let w = v.map(|k| uv[k].extend(0.0));
                        lerp4(w, s, t).truncate()
                    }
                    None => Vec2::new(s, t),
                };
                ouv.push(st);
                if let Some(n) = n {
                    on.push(lerp4(v.map(|k| n[k]), s, t).normalize_or_zero());
                }
            }
        }
        let row = cells as i32 + 1;
        for j in 0..cells as i32 {
            for i in 0..cells as i32 {
                let a = base + j * row + i;
                // (p00, p10, p11) and (p00, p11, p01): pbrt's orientation, n = dpdu x dpdv.
                oi.extend([a, a + 1, a + row + 1, a, a + row + 1, a + row]);
            }
        }
    }
    (op, ouv, n.map(|_| on), oi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planar_patch_is_two_triangles_and_twisted_patch_follows_the_surface() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0)];
        let (pos, uv, n, idx) = bilinear_triangles(&p, &[0, 1, 2, 3], None, None);
        assert_eq!((pos.len(), idx.len()), (4, 6));
        assert!(n.is_none());
        assert_eq!(uv[3], Vec2::ONE);
        // Winding gives +z = dp/du x dp/dv, as pbrt's patch normal.
        let t = |k: usize| pos[idx[k] as usize];
        assert!((t(1) - t(0)).cross(t(2) - t(0)).z > 0.0);
        // A hyperbolic paraboloid z = u v: every grid vertex lies on it.
        let q = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0)];
        let (pos, uv, _, idx) = bilinear_triangles(&q, &[0, 1, 2, 3], None, None);
        assert_eq!(pos.len(), 17 * 17);
        assert_eq!(idx.len(), 16 * 16 * 6);
        for (x, st) in pos.iter().zip(&uv) {
            assert!((x.z - x.x * x.y).abs() < 1e-6 && (x.x - st.x).abs() < 1e-6);
        }
        // Triangle centres stay within 1/512 of the surface (the twist is 1).
        for f in idx.chunks(3) {
            let c = (pos[f[0] as usize] + pos[f[1] as usize] + pos[f[2] as usize]) / 3.0;
            assert!((c.z - c.x * c.y).abs() <= 1.0 / 512.0 + 1e-6);
        }
    }
}
