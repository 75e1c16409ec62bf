//! Loop subdivision (pbrt's `loopsubdiv`): `levels` rounds of Loop's scheme
//! with pbrt's boundary rules (boundary vertices and edges follow the cubic
//! B-spline of the boundary curve alone), then every vertex is moved to its
//! limit position and given the limit surface's normal (cross product of the
//! two limit tangents), as pbrt does.

use lumis_math::Vec3;
use std::collections::HashMap;

/// A subdivided triangle mesh: limit positions, limit normals, indices.
pub struct Subdivided {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub indices: Vec<u32>,
}

/// Loop's weight for the old vertex's one-ring (pbrt's `beta`).
fn beta(valence: usize) -> f32 {
    if valence == 3 {
        3.0 / 16.0
    } else {
        3.0 / (8.0 * valence as f32)
    }
}

/// Weight of the one-ring in the limit position (pbrt's `loopGamma`).
fn gamma(valence: usize) -> f32 {
    1.0 / (valence as f32 + 3.0 / (8.0 * beta(valence)))
}

/// Connectivity of one level.
struct Topology {
    /// Edge (lo, hi) → the vertices opposite it in its one or two faces.
    edges: HashMap<(u32, u32), Vec<u32>>,
    /// Per vertex: its neighbours in order around it (a cycle inside, a
    /// chain from one boundary neighbour to the other on the boundary).
    rings: Vec<Vec<u32>>,
    boundary: Vec<bool>,
}

fn key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

fn topology(n_verts: usize, faces: &[[u32; 3]]) -> Result<Topology, String> {
    let mut edges: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
    // Per vertex: directed links x -> y for each face (v, x, y) in winding order.
    let mut links: Vec<Vec<(u32, u32)>> = vec![Vec::new(); n_verts];
    for f in faces {
        for k in 0..3 {
            let (a, b, c) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
            let e = edges.entry(key(a, b)).or_default();
            e.push(c);
            if e.len() > 2 {
                return Err(format!(
                    "edge {a}-{b} is shared by more than two faces (non-manifold)"
                ));
            }
            links[a as usize].push((b, c));
        }
    }
    let mut rings = Vec::with_capacity(n_verts);
    let mut boundary = Vec::with_capacity(n_verts);
    for (v, l) in links.iter().enumerate() {
        if l.is_empty() {
            rings.push(Vec::new());
            boundary.push(false);
            continue;
        }
        let next: HashMap<u32, u32> = l.iter().copied().collect();
        if next.len() != l.len() {
            return Err(format!(
                "faces around vertex {v} are inconsistently oriented"
            ));
        }
        // A chain starts at a neighbour that nothing links to.
        let targets: Vec<u32> = l.iter().map(|x| x.1).collect();
        let start = l.iter().map(|x| x.0).find(|x| !targets.contains(x));
        let is_boundary = start.is_some();
        let mut ring = vec![start.unwrap_or(l[0].0)];
        while let Some(&n) = next.get(ring.last().expect("non-empty")) {
            if n == ring[0] || ring.len() > l.len() {
                break;
            }
            ring.push(n);
        }
        if ring.len() != l.len() + usize::from(is_boundary) {
            return Err(format!(
                "vertex {v} is not a manifold vertex (its faces do not form one fan)"
            ));
        }
        rings.push(ring);
        boundary.push(is_boundary);
    }
    Ok(Topology {
        edges,
        rings,
        boundary,
    })
}

fn sum(p: &[Vec3], ids: &[u32]) -> Vec3 {
    ids.iter()
        .map(|&i| p[i as usize])
        .fold(Vec3::ZERO, |a, b| a + b)
}

/// One round of Loop subdivision.
fn refine(p: &[Vec3], faces: &[[u32; 3]], t: &Topology) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut out: Vec<Vec3> = (0..p.len())
        .map(|v| {
            let ring = &t.rings[v];
            if ring.is_empty() {
                p[v]
            } else if t.boundary[v] {
                let ends = [ring[0], ring[ring.len() - 1]];
                0.75 * p[v] + 0.125 * sum(p, &ends)
            } else {
                let b = beta(ring.len());
                (1.0 - ring.len() as f32 * b) * p[v] + b * sum(p, ring)
            }
        })
        .collect();
    let mut edge_vertex: HashMap<(u32, u32), u32> = HashMap::with_capacity(t.edges.len());
    let mut keys: Vec<&(u32, u32)> = t.edges.keys().collect();
    keys.sort_unstable();
    for k in keys {
        let opp = &t.edges[k];
        let (a, b) = (p[k.0 as usize], p[k.1 as usize]);
        let q = if opp.len() == 1 {
            0.5 * (a + b)
        } else {
            0.375 * (a + b) + 0.125 * sum(p, opp)
        };
        edge_vertex.insert(*k, out.len() as u32);
        out.push(q);
    }
    let mut new_faces = Vec::with_capacity(4 * faces.len());
    for f in faces {
        let e = |i: usize, j: usize| edge_vertex[&key(f[i], f[j])];
        let (ab, bc, ca) = (e(0, 1), e(1, 2), e(2, 0));
        new_faces.push([f[0], ab, ca]);
        new_faces.push([ab, f[1], bc]);
        new_faces.push([ca, bc, f[2]]);
        new_faces.push([ab, bc, ca]);
    }
    (out, new_faces)
}

/// Subdivides `levels` times; `Err` describes a mesh Loop's scheme cannot handle.
pub fn loop_subdivide(
    positions: &[Vec3],
    indices: &[u32],
    levels: u32,
) -> Result<Subdivided, String> {
    let mut p = positions.to_vec();
    let mut faces: Vec<[u32; 3]> = indices.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    let mut t = topology(p.len(), &faces)?;
    for _ in 0..levels {
        let (np, nf) = refine(&p, &faces, &t);
        p = np;
        faces = nf;
        t = topology(p.len(), &faces)?;
    }
    // Face-winding normals, to orient the limit normals consistently with the faces.
    let mut wind = vec![Vec3::ZERO; p.len()];
    for f in &faces {
        let n = (p[f[1] as usize] - p[f[0] as usize]).cross(p[f[2] as usize] - p[f[0] as usize]);
        for &v in f {
            wind[v as usize] += n;
        }
    }
    let mut limit = Vec::with_capacity(p.len());
    let mut normals = Vec::with_capacity(p.len());
    for v in 0..p.len() {
        let ring = &t.rings[v];
        let n = ring.len();
        if n == 0 {
            limit.push(p[v]);
            normals.push(Vec3::ZERO);
            continue;
        }
        let (lp, s, tt) = if t.boundary[v] {
            let ends = [ring[0], ring[n - 1]];
            let lp = 0.6 * p[v] + 0.2 * sum(&p, &ends);
            let s = p[ring[n - 1] as usize] - p[ring[0] as usize];
            let r = |i: usize| p[ring[i] as usize];
            let tt = match n {
                2 => r(0) + r(1) - 2.0 * p[v],
                3 => r(1) - p[v],
                4 => -r(0) + 2.0 * r(1) + 2.0 * r(2) - r(3) - 2.0 * p[v],
                _ => {
                    let th = lumis_math::PI / (n - 1) as f32;
                    let mut tt = th.sin() * (r(0) + r(n - 1));
                    for i in 1..n - 1 {
                        tt += (2.0 * th.cos() - 2.0) * (th * i as f32).sin() * r(i);
                    }
                    -tt
                }
            };
            (lp, s, tt)
        } else {
            let g = gamma(n);
            let lp = (1.0 - n as f32 * g) * p[v] + g * sum(&p, ring);
            let (mut s, mut tt) = (Vec3::ZERO, Vec3::ZERO);
            for (j, &q) in ring.iter().enumerate() {
                let a = 2.0 * lumis_math::PI * j as f32 / n as f32;
                s += a.cos() * p[q as usize];
                tt += a.sin() * p[q as usize];
            }
            (lp, s, tt)
        };
        let mut nn = s.cross(tt).normalize_or_zero();
        if nn.dot(wind[v]) < 0.0 {
            nn = -nn;
        }
        limit.push(lp);
        normals.push(nn);
    }
    Ok(Subdivided {
        positions: limit,
        normals,
        indices: faces.iter().flatten().copied().collect(),
    })
}

#[cfg(test)]
mod tests;
