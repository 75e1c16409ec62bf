use super::*;

/// A regular tetrahedron centred at the origin, faces wound outward.
fn tetrahedron() -> (Vec<Vec3>, Vec<u32>) {
    let p = vec![
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(1.0, -1.0, -1.0),
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(-1.0, -1.0, 1.0),
    ];
    (p, vec![0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2])
}

fn edges(idx: &[u32]) -> usize {
    let mut e: Vec<(u32, u32)> = idx
        .chunks(3)
        .flat_map(|f| (0..3).map(move |k| key(f[k], f[(k + 1) % 3])))
        .collect();
    e.sort_unstable();
    e.dedup();
    e.len()
}

#[test]
fn tetrahedron_counts_limit_positions_and_normals() {
    let (p, idx) = tetrahedron();
    for f in idx.chunks(3) {
        let [a, b, c] = [0, 1, 2].map(|k| p[f[k] as usize]);
        assert!((b - a).cross(c - a).dot(a + b + c) > 0.0, "outward winding");
    }
    // Level 0: each vertex has valence 3, gamma = 1/5, so the limit of a
    // vertex of a centred tetrahedron is 0.4 p + 0.2 (-p) = 0.2 p.
    let s0 = loop_subdivide(&p, &idx, 0).unwrap();
    for (q, v) in s0.positions.iter().zip(&p) {
        assert!((*q - 0.2 * *v).length() < 1e-6);
    }
    let (mut v, mut f) = (4, 4);
    for levels in 1..=3u32 {
        let s = loop_subdivide(&p, &idx, levels).unwrap();
        let e = edges(&s.indices);
        // Each round adds one vertex per edge and splits each face in four.
        v += edges(&loop_subdivide(&p, &idx, levels - 1).unwrap().indices);
        f *= 4;
        assert_eq!((s.positions.len(), s.indices.len() / 3), (v, f));
        assert_eq!(s.positions.len() + s.indices.len() / 3, e + 2, "Euler");
        // The limit position of an old vertex does not depend on the level.
        for k in 0..4 {
            assert!(
                (s.positions[k] - s0.positions[k]).length() < 1e-5,
                "level {levels} vertex {k}"
            );
        }
        // Normals are unit and point outward; the surface is symmetric.
        for (q, n) in s.positions.iter().zip(&s.normals) {
            assert!((n.length() - 1.0).abs() < 1e-4);
            assert!(n.dot(*q) > 0.0);
        }
        let r0 = s.positions[0].length();
        for k in 1..4 {
            assert!((s.positions[k].length() - r0).abs() < 1e-5);
        }
    }
    // At an old vertex the limit normal points along the symmetry axis.
    let s = loop_subdivide(&p, &idx, 2).unwrap();
    assert!(s.normals[0].dot(p[0].normalize()) > 1.0 - 1e-5);
}

/// An open patch: an n x n grid on [0, n]^2 with bumpy interior heights and
/// its boundary on the square's sides at z = 0.
fn patch(n: usize) -> (Vec<Vec3>, Vec<u32>) {
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let inner = i > 0 && j > 0 && i < n && j < n;
            let z = if inner {
                ((i * 7 + j * 3) % 5) as f32 * 0.3
            } else {
                0.0
            };
            p.push(Vec3::new(i as f32, j as f32, z));
        }
    }
    let mut idx = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let v = (j * (n + 1) + i) as u32;
            let w = v + n as u32 + 1;
            idx.extend([v, v + 1, w + 1, v, w + 1, w]);
        }
    }
    (p, idx)
}

#[test]
fn open_patch_keeps_its_boundary_on_the_boundary_curve() {
    let n = 6;
    let (p, idx) = patch(n);
    let (v0, f0, e0) = (p.len(), idx.len() / 3, edges(&idx));
    assert_eq!(e0, 3 * n * n + 2 * n);
    let s = loop_subdivide(&p, &idx, 2).unwrap();
    let e1 = 2 * e0 + 3 * f0;
    assert_eq!(s.positions.len(), v0 + e0 + e1);
    assert_eq!(s.indices.len() / 3, 16 * f0);
    let faces: Vec<[u32; 3]> = s.indices.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    let t = topology(s.positions.len(), &faces).unwrap();
    assert_eq!(
        t.boundary.iter().filter(|&&b| b).count(),
        4 * n * 4,
        "boundary edges double per level"
    );
    // Boundary rules use boundary vertices only: changing the interior moves
    // no boundary vertex, and a boundary at z = 0 stays at z = 0.
    let mut p2 = p.clone();
    for q in p2.iter_mut().filter(|q| q.z != 0.0) {
        q.z = -2.0 * q.z + 0.7;
    }
    let s2 = loop_subdivide(&p2, &idx, 2).unwrap();
    let nf = n as f32;
    for k in 0..s.positions.len() {
        let q = s.positions[k];
        if t.boundary[k] {
            assert_eq!(q, s2.positions[k], "boundary vertex {k}");
            assert_eq!(q.z, 0.0);
            // The boundary curve is the (rounded-corner) spline of the square:
            // away from the corners' support it runs along the sides.
            let along = if q.x == 0.0 || q.x == nf { q.y } else { q.x };
            if along > 2.0 && along < nf - 2.0 {
                assert!(q.x == 0.0 || q.y == 0.0 || q.x == nf || q.y == nf, "{q}");
            }
            assert!(q.x >= 0.0 && q.y >= 0.0 && q.x <= nf && q.y <= nf);
        } else {
            assert_ne!(
                q, s2.positions[k],
                "interior vertex {k} ignores the interior?"
            );
        }
    }
    // Normals point up (+z), as the faces are wound.
    assert!(s.normals.iter().all(|n| n.z > 0.0));
}

#[test]
fn non_manifold_input_is_refused() {
    let p = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z, -Vec3::Y];
    let e = loop_subdivide(&p, &[0, 1, 2, 1, 0, 3, 0, 1, 4], 1)
        .err()
        .unwrap();
    assert!(e.contains("more than two faces"), "{e}");
}
