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

/// Grid cells per side for a non-planar bilinear patch.
const BILINEAR_CELLS: usize = 16;

/// pbrt-v4's `bilinearmesh` as triangles: each patch (vertices p00, p10, p01,
/// p11) is evaluated on its bilinear surface at a grid of (u, v). A planar
/// patch is its two triangles exactly (its bilinear surface is the planar
/// quad); a non-planar one becomes a 16 x 16 grid, within about 1/512 of the
/// patch's twist of pbrt-v4's exact surface. Returns positions, uvs,
/// normals (if given) and triangle indices.
#[allow(clippy::type_complexity)]
pub(super) fn bilinear_triangles(
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
