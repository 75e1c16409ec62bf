//! A static kd-tree over points, for the photon maps' k-nearest and
//! fixed-radius queries and the nearest-sample searches built on it.
//!
//! The tree is complete and implicit: `2^d` leaves of equal size (at most
//! `leaf_size` points), each inner node a median split on the widest axis of
//! its points, stored heap-ordered (children of `i` are `2i`, `2i + 1`).
//! Leaves hold copies of the positions (with the point index) contiguously,
//! four points to a [`Quad`] by axis, so a query computes four squared
//! distances at once and reads 16 bytes per candidate. Traversal is
//! near-first with an explicit stack and prunes cells by their exact
//! distance lower bound (per-axis offsets, Arya & Mount 1993).

use lumis_math::{Vec3, Vec4};
use rayon::prelude::*;

#[derive(Clone, Copy, Debug, Default)]
struct Node {
    split: f32,
    dim: u32,
}

/// Four points of one leaf, their coordinates by axis, with their indices.
/// A leaf's last quad is filled with points at infinity (index `u32::MAX`),
/// whose squared distance, infinite, passes no bound.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
struct Quad {
    x: Vec4,
    y: Vec4,
    z: Vec4,
    id: [u32; 4],
}

impl Quad {
    const EMPTY: Quad = Quad {
        x: Vec4::INFINITY,
        y: Vec4::INFINITY,
        z: Vec4::INFINITY,
        id: [u32::MAX; 4],
    };

    /// Squared distances of the four points to `q` (`q` splatted per axis),
    /// each rounded as [`dist2`] rounds it.
    #[inline(always)]
    fn dist2(&self, q: &[Vec4; 3]) -> Vec4 {
        let (dx, dy, dz) = (self.x - q[0], self.y - q[1], self.z - q[2]);
        dx * dx + dy * dy + dz * dz
    }

    /// The lanes whose squared distance `d2` is below `bound`, as bits.
    #[inline(always)]
    fn below(d2: Vec4, bound: f32) -> u32 {
        d2.cmplt(Vec4::splat(bound)).bitmask()
    }
}

/// `q` splatted per axis, for [`Quad::dist2`].
#[inline(always)]
fn splat(q: [f32; 3]) -> [Vec4; 3] {
    q.map(Vec4::splat)
}

/// A static kd-tree over points; query results are the points' indices in
/// the slice it was built from (or, after [`KdTree::reindex_to_leaf_order`],
/// their positions in leaf order).
#[derive(Debug, Default)]
pub(crate) struct KdTree {
    /// The leaves' points, each leaf a run of quads.
    quads: Vec<Quad>,
    /// Heap-indexed inner nodes; `nodes.len()` is the leaf count (0 unused).
    nodes: Vec<Node>,
    /// Leaf `j` is `quads[leaf_start[j]..leaf_start[j + 1]]`.
    leaf_start: Vec<u32>,
    /// Points (not counting the fill).
    len: usize,
}

impl KdTree {
    pub(crate) fn build(positions: impl IntoIterator<Item = Vec3>, leaf_size: usize) -> KdTree {
        let mut points: Vec<[f32; 4]> = positions
            .into_iter()
            .enumerate()
            .map(|(i, p)| [p.x, p.y, p.z, f32::from_bits(i as u32)])
            .collect();
        let n = points.len();
        assert!(n < u32::MAX as usize, "too many points for a kd-tree");
        if n == 0 {
            return KdTree::default();
        }
        let leaves = n.div_ceil(leaf_size).next_power_of_two();
        let start = |j: usize| (j as u64 * n as u64 / leaves as u64) as usize;
        let mut nodes = vec![Node::default(); leaves];
        // Level by level: the nodes of a level are contiguous in the heap and
        // own disjoint, contiguous ranges of points.
        let mut level = 1;
        while level < leaves {
            let per = leaves / level;
            let mut slices = Vec::with_capacity(level);
            let mut rest = &mut points[..];
            for i in 0..level {
                let len = start((i + 1) * per) - start(i * per);
                let (s, r) = rest.split_at_mut(len);
                let mid = start(i * per + per / 2) - start(i * per);
                slices.push((s, mid));
                rest = r;
            }
            let mut level_nodes = Vec::with_capacity(level);
            slices
                .into_par_iter()
                .with_min_len(64)
                .map(|(s, mid)| split(s, mid))
                .collect_into_vec(&mut level_nodes);
            nodes[level..2 * level].copy_from_slice(&level_nodes);
            level *= 2;
        }
        let mut quads = Vec::with_capacity(n / 4 + leaves);
        let mut leaf_start = Vec::with_capacity(leaves + 1);
        for j in 0..leaves {
            leaf_start.push(quads.len() as u32);
            for chunk in points[start(j)..start(j + 1)].chunks(4) {
                let mut q = Quad::EMPTY;
                for (l, p) in chunk.iter().enumerate() {
                    (q.x[l], q.y[l], q.z[l], q.id[l]) = (p[0], p[1], p[2], p[3].to_bits());
                }
                quads.push(q);
            }
        }
        leaf_start.push(quads.len() as u32);
        KdTree {
            quads,
            nodes,
            leaf_start,
            len: n,
        }
    }

    pub(crate) fn memory_bytes(&self) -> usize {
        self.quads.capacity() * std::mem::size_of::<Quad>()
            + self.nodes.capacity() * 8
            + self.leaf_start.capacity() * 4
    }

    /// Original indices in leaf order; afterwards results are leaf positions.
    pub(crate) fn reindex_to_leaf_order(&mut self) -> Vec<u32> {
        let mut order = Vec::with_capacity(self.len);
        for q in &mut self.quads {
            for id in q.id.iter_mut().filter(|id| **id != u32::MAX) {
                let original = std::mem::replace(id, order.len() as u32);
                order.push(original);
            }
        }
        order
    }

    /// The points' positions, by index (the build's, or leaf order after
    /// [`KdTree::reindex_to_leaf_order`]).
    pub(crate) fn positions(&self) -> Vec<Vec3> {
        let mut pos = vec![Vec3::ZERO; self.len];
        for q in &self.quads {
            for l in (0..4).filter(|&l| q.id[l] != u32::MAX) {
                pos[q.id[l] as usize] = Vec3::new(q.x[l], q.y[l], q.z[l]);
            }
        }
        pos
    }

    /// Calls `f(index, d2, bound)` for every point at squared distance
    /// `d2 < *bound` from `q`, leaves nearest first; `f` may shrink `bound`
    /// (each point is tested against the bound as it is then).
    #[inline(always)]
    pub(crate) fn for_each_within(
        &self,
        q: [f32; 3],
        bound: &mut f32,
        mut f: impl FnMut(u32, f32, &mut f32),
    ) {
        let q4 = splat(q);
        self.search(q, bound, |quads, bound| {
            for quad in quads {
                let d = quad.dist2(&q4);
                let mut lanes = Quad::below(d, *bound);
                while lanes != 0 {
                    let l = lanes.trailing_zeros() as usize;
                    lanes &= lanes - 1;
                    if d[l] < *bound {
                        f(quad.id[l], d[l], bound);
                    }
                }
            }
        });
    }

    /// Visits every leaf that may hold a point at squared distance < `*bound`
    /// from `q`, nearest first; `leaf` may shrink `bound`.
    #[inline(always)]
    fn search(&self, q: [f32; 3], bound: &mut f32, mut leaf: impl FnMut(&[Quad], &mut f32)) {
        if self.quads.is_empty() {
            return;
        }
        let inner = self.nodes.len();
        let mut stack = [(0u32, 0.0f32, [0.0f32; 3]); 40];
        let mut sp = 0;
        let mut node = 1;
        let mut off = [0.0f32; 3];
        loop {
            while node < inner {
                let nd = self.nodes[node];
                let d = nd.dim as usize;
                let diff = q[d] - nd.split;
                let near = 2 * node + (diff >= 0.0) as usize;
                // `off` with its `d`-th offset replaced, by selects: an
                // indexed store into the array and a wider load back stalled
                // store forwarding (a fifth of a lookup's time in profiles).
                let far_off = [
                    if d == 0 { diff } else { off[0] },
                    if d == 1 { diff } else { off[1] },
                    if d == 2 { diff } else { off[2] },
                ];
                let rd =
                    far_off[0] * far_off[0] + far_off[1] * far_off[1] + far_off[2] * far_off[2];
                if rd < *bound {
                    stack[sp] = ((near ^ 1) as u32, rd, far_off);
                    sp += 1;
                }
                node = near;
            }
            let j = node - inner;
            let (a, b) = (self.leaf_start[j] as usize, self.leaf_start[j + 1] as usize);
            leaf(&self.quads[a..b], bound);
            loop {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                let (n, rd, o) = stack[sp];
                if rd < *bound {
                    node = n as usize;
                    off = o;
                    break;
                }
            }
        }
    }
}

/// Median split of `s` at `mid` on the widest axis of its points.
fn split(s: &mut [[f32; 4]], mid: usize) -> Node {
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in s.iter() {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let dim = if ext[0] >= ext[1] && ext[0] >= ext[2] {
        0
    } else if ext[1] >= ext[2] {
        1
    } else {
        2
    };
    s.select_nth_unstable_by(mid, |a, b| a[dim].total_cmp(&b[dim]));
    Node {
        split: s[mid][dim],
        dim: dim as u32,
    }
}

/// Smallest bound `b` with `d2 < b` exactly when `d2 <= r2`.
#[inline]
pub(crate) fn inclusive(r2: f32) -> f32 {
    if r2.is_finite() {
        f32::from_bits(r2.to_bits() + 1)
    } else {
        r2
    }
}

/// Squared distance from `pt` (its first three coordinates) to `q`.
#[inline(always)]
pub(crate) fn dist2(pt: &[f32; 4], q: [f32; 3]) -> f32 {
    let (dx, dy, dz) = (pt[0] - q[0], pt[1] - q[1], pt[2] - q[2]);
    dx * dx + dy * dy + dz * dz
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every point within the bound, found through the quads, against brute
    /// force; the fill lanes are never reported; leaf order is a permutation.
    #[test]
    fn quads_find_what_brute_force_finds() {
        let mut rng = lumis_math::Pcg32::new(7, 0);
        let mut rnd = || rng.next_f32();
        for n in [1usize, 5, 17, 1000] {
            let pts: Vec<Vec3> = (0..n).map(|_| Vec3::new(rnd(), rnd(), rnd())).collect();
            let mut tree = KdTree::build(pts.iter().copied(), 16);
            assert!(tree.quads.len() * 4 >= n);
            for _ in 0..50 {
                let q = [rnd(), rnd(), rnd()];
                let r2 = 0.05 * rnd();
                let mut want: Vec<u32> = (0..n as u32)
                    .filter(|&i| dist2(&pts[i as usize].extend(0.0).to_array(), q) <= r2)
                    .collect();
                let mut got = Vec::new();
                let mut bound = inclusive(r2);
                tree.for_each_within(q, &mut bound, |i, d2, _| {
                    assert_eq!(d2, dist2(&pts[i as usize].extend(0.0).to_array(), q));
                    got.push(i);
                });
                got.sort_unstable();
                want.sort_unstable();
                assert_eq!(got, want, "n {n}");
            }
            let order = tree.reindex_to_leaf_order();
            let mut sorted = order.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..n as u32).collect::<Vec<_>>());
            let ids: Vec<u32> = tree
                .quads
                .iter()
                .flat_map(|q| q.id)
                .filter(|&i| i != u32::MAX)
                .collect();
            assert_eq!(ids, (0..n as u32).collect::<Vec<_>>());
        }
    }
}
