//! The photon map: photons and a kd-tree over their positions for k-nearest
//! and fixed-radius queries.
//!
//! The tree is complete and implicit: `2^d` leaves of equal size (at most
//! `leaf_size` points), each inner node a median split on the widest axis of
//! its points, stored heap-ordered (children of `i` are `2i`, `2i + 1`).
//! Leaves hold copies of the positions (with the point index) contiguously,
//! so a query reads 16 bytes per candidate; the photons themselves are
//! reordered into leaf order so that a query's photons are close in memory.
//! Traversal is near-first with an explicit stack and prunes cells by their
//! exact distance lower bound (per-axis offsets, Arya & Mount 1993).

use super::photon::Photon;
use lumis_math::{Rgb, Vec3, PI};
use rayon::prelude::*;

/// Points per leaf at most (the average is between half and all of it):
/// measured best for k = 50 among 1M photons.
const MAP_LEAF: usize = 64;

#[derive(Clone, Copy, Debug, Default)]
struct Node {
    split: f32,
    dim: u32,
}

/// A static kd-tree over points; query results are the points' indices in
/// the slice it was built from.
#[derive(Debug, Default)]
pub(crate) struct KdTree {
    /// Leaf order; `[3]` holds the index bits.
    points: Vec<[f32; 4]>,
    /// Heap-indexed inner nodes; `nodes.len()` is the leaf count (0 unused).
    nodes: Vec<Node>,
    leaf_start: Vec<u32>,
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
        let leaf_start: Vec<u32> = (0..=leaves)
            .map(|j| (j as u64 * n as u64 / leaves as u64) as u32)
            .collect();
        let mut nodes = vec![Node::default(); leaves];
        // Level by level: the nodes of a level are contiguous in the heap and
        // own disjoint, contiguous ranges of points.
        let mut level = 1;
        while level < leaves {
            let per = leaves / level;
            let mut slices = Vec::with_capacity(level);
            let mut rest = &mut points[..];
            for i in 0..level {
                let len = (leaf_start[(i + 1) * per] - leaf_start[i * per]) as usize;
                let (s, r) = rest.split_at_mut(len);
                let mid = (leaf_start[i * per + per / 2] - leaf_start[i * per]) as usize;
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
        KdTree {
            points,
            nodes,
            leaf_start,
        }
    }

    pub(crate) fn memory_bytes(&self) -> usize {
        self.points.capacity() * 16 + self.nodes.capacity() * 8 + self.leaf_start.capacity() * 4
    }

    /// Original indices in leaf order; afterwards results are leaf positions.
    pub(crate) fn reindex_to_leaf_order(&mut self) -> Vec<u32> {
        let mut order = Vec::with_capacity(self.points.len());
        for (i, p) in self.points.iter_mut().enumerate() {
            order.push(p[3].to_bits());
            p[3] = f32::from_bits(i as u32);
        }
        order
    }

    /// Visits every leaf that may hold a point at squared distance < `*bound`
    /// from `q`, nearest first; `leaf` may shrink `bound`.
    #[inline(always)]
    pub(crate) fn search(
        &self,
        q: [f32; 3],
        bound: &mut f32,
        mut leaf: impl FnMut(&[[f32; 4]], &mut f32),
    ) {
        if self.points.is_empty() {
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
            leaf(&self.points[a..b], bound);
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

/// Photons and the kd-tree over their positions. `Send + Sync`.
///
/// The photons are stored in the tree's leaf order (not the order given to
/// [`PhotonMap::build`]) so that a query's photons are close in memory;
/// [`PhotonMap::original_index`] maps back.
#[derive(Debug)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    /// Index in the input of each stored photon.
    order: Vec<u32>,
    tree: KdTree,
    emitted: u64,
}

impl PhotonMap {
    /// `emitted`: photons emitted in the pass that built this map (the N of
    /// the estimates). Query results index [`PhotonMap::photons`].
    pub fn build(photons: Vec<Photon>, emitted: u64) -> PhotonMap {
        let mut tree = KdTree::build(photons.iter().map(Photon::pos), MAP_LEAF);
        let order = tree.reindex_to_leaf_order();
        let photons = order.iter().map(|&i| photons[i as usize]).collect();
        PhotonMap {
            photons,
            order,
            tree,
            emitted,
        }
    }

    /// Index in the `Vec` given to [`PhotonMap::build`] of stored photon `i`.
    #[inline]
    pub fn original_index(&self, i: u32) -> u32 {
        self.order[i as usize]
    }

    pub fn len(&self) -> usize {
        self.photons.len()
    }

    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    pub fn emitted(&self) -> u64 {
        self.emitted
    }

    pub fn memory_bytes(&self) -> usize {
        self.photons.capacity() * std::mem::size_of::<Photon>()
            + self.order.capacity() * 4
            + self.tree.memory_bytes()
    }

    #[inline]
    pub fn photon(&self, i: u32) -> &Photon {
        &self.photons[i as usize]
    }

    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }

    /// Up to `k` nearest photons within `max_radius` of `p`, written into
    /// `out` as (index, squared distance) in no particular order (a max-heap).
    /// Returns the squared radius of the disc they cover: the largest squared
    /// distance among them if `k` were found, else `max_radius^2`.
    pub fn knn(&self, p: Vec3, k: usize, max_radius: f32, out: &mut Vec<(u32, f32)>) -> f32 {
        out.clear();
        let r2 = max_radius * max_radius;
        if k == 0 || !(max_radius >= 0.0) {
            return r2.max(0.0);
        }
        let q = p.to_array();
        let mut bound = inclusive(r2);
        self.tree.search(q, &mut bound, |pts, bound| {
            for pt in pts {
                let d2 = dist2(pt, q);
                if d2 < *bound {
                    let e = (pt[3].to_bits(), d2);
                    if out.len() < k {
                        heap_push(out, e);
                        if out.len() == k {
                            *bound = out[0].1;
                        }
                    } else {
                        heap_replace_top(out, e);
                        *bound = out[0].1;
                    }
                }
            }
        });
        if out.len() == k {
            out[0].1
        } else {
            r2
        }
    }

    /// All photons within `radius` of `p` (distance <= radius), in no order.
    pub fn within(&self, p: Vec3, radius: f32, out: &mut Vec<(u32, f32)>) {
        out.clear();
        if !(radius >= 0.0) {
            return;
        }
        let q = p.to_array();
        let mut bound = inclusive(radius * radius);
        self.tree.search(q, &mut bound, |pts, bound| {
            for pt in pts {
                let d2 = dist2(pt, q);
                if d2 < *bound {
                    out.push((pt[3].to_bits(), d2));
                }
            }
        });
    }
}

/// Irradiance estimate at `p` with normal `n` from the `k` nearest photons
/// within `max_radius`, counting those arriving from `n`'s side
/// (`dot(dir, n) > 0`): `E = sum(power) / (pi r^2)`. Returns `(E, r^2)`.
pub fn irradiance_knn(
    map: &PhotonMap,
    p: Vec3,
    n: Vec3,
    k: usize,
    max_radius: f32,
    scratch: &mut Vec<(u32, f32)>,
) -> (Rgb, f32) {
    let r2 = map.knn(p, k, max_radius, scratch);
    let mut sum = Rgb::BLACK;
    for &(i, _) in scratch.iter() {
        let ph = map.photon(i);
        if ph.dir_unnormalized().dot(n) > 0.0 {
            sum += ph.power();
        }
    }
    if r2 > 0.0 && sum != Rgb::BLACK {
        (sum / (PI * r2), r2)
    } else {
        (Rgb::BLACK, r2)
    }
}

/// Irradiance estimate at `p` with normal `n` from every photon within
/// `radius` arriving from `n`'s side, except one lying exactly at `p`:
/// `E = sum(power) / (pi r^2)`. (A point that is itself a photon of the
/// map would otherwise always count itself, however small the disc.)
pub fn irradiance_within(
    map: &PhotonMap,
    p: Vec3,
    n: Vec3,
    radius: f32,
    scratch: &mut Vec<(u32, f32)>,
) -> Rgb {
    map.within(p, radius, scratch);
    let mut sum = Rgb::BLACK;
    for &(i, d2) in scratch.iter() {
        let ph = map.photon(i);
        if d2 > 0.0 && ph.dir_unnormalized().dot(n) > 0.0 {
            sum += ph.power();
        }
    }
    if radius > 0.0 {
        sum / (PI * radius * radius)
    } else {
        Rgb::BLACK
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

#[inline(always)]
pub(crate) fn dist2(pt: &[f32; 4], q: [f32; 3]) -> f32 {
    let (dx, dy, dz) = (pt[0] - q[0], pt[1] - q[1], pt[2] - q[2]);
    dx * dx + dy * dy + dz * dz
}

/// Max-heap on the distance.
#[inline]
fn heap_push(h: &mut Vec<(u32, f32)>, e: (u32, f32)) {
    let mut i = h.len();
    h.push(e);
    while i > 0 {
        let parent = (i - 1) / 2;
        if h[parent].1 >= e.1 {
            break;
        }
        h[i] = h[parent];
        i = parent;
    }
    h[i] = e;
}

#[inline]
fn heap_replace_top(h: &mut [(u32, f32)], e: (u32, f32)) {
    let n = h.len();
    let mut i = 0;
    loop {
        let l = 2 * i + 1;
        if l >= n {
            break;
        }
        let c = if l + 1 < n && h[l + 1].1 > h[l].1 {
            l + 1
        } else {
            l
        };
        if h[c].1 <= e.1 {
            break;
        }
        h[i] = h[c];
        i = c;
    }
    h[i] = e;
}
