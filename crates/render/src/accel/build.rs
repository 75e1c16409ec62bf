//! The BVH's build: a binned SAH over the primitives' centroids (its
//! large nodes split in parallel), into binary nodes that [`flatten`]
//! collapses into the 8-wide [`Node`]s the traversal reads.

use super::bvh::{Node, EMPTY_NODE, WIDTH};
use super::mem::huge_vec;
use crate::geometry::Aabb;
use lumis_math::Vec3;

const BINS: usize = 16;
const MAX_LEAF: usize = 8;
const TRAVERSAL_COST: f32 = 3.0;
const PARALLEL_THRESHOLD: usize = 16 * 1024;
/// Depth from which splits are at the median: the binary depth stays
/// below `MEDIAN_DEPTH + 32`, which sizes the traversal stacks.
pub(super) const MEDIAN_DEPTH: u32 = 31;

#[derive(Clone, Copy)]
struct PrimRef {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
    /// A primitive that gets a leaf of its own (an analytic shape: its test
    /// costs as much as a packet of four triangles, and its box is the only
    /// cheap way to skip it).
    alone: bool,
}

enum BuildNode {
    Leaf {
        bounds: Aabb,
        start: usize,
        count: usize,
    },
    Interior {
        bounds: Aabb,
        children: Box<[BuildNode; 2]>,
    },
}

impl BuildNode {
    fn bounds(&self) -> &Aabb {
        match self {
            BuildNode::Leaf { bounds, .. } | BuildNode::Interior { bounds, .. } => bounds,
        }
    }
}

/// The nodes, the leaf slots' primitives and the bounds of a BVH over
/// `bounds` (empty boxes skipped; `None` if all are): the SAH counts
/// primitives in blocks of `block` (a leaf of up to `block` primitives
/// costs one test), and each primitive `i` for which `alone(i)` holds gets
/// a leaf by itself.
pub(super) fn build(
    bounds: &[Aabb],
    block: usize,
    alone: impl Fn(usize) -> bool,
) -> Option<(Vec<Node>, Vec<u32>, Aabb)> {
    let mut refs: Vec<PrimRef> = bounds
        .iter()
        .enumerate()
        .filter(|(_, b)| !b.is_empty())
        .map(|(i, b)| PrimRef {
            bounds: *b,
            centroid: b.center(),
            index: i as u32,
            alone: alone(i),
        })
        .collect();
    if refs.is_empty() {
        return None;
    }
    let root = build_rec(&mut refs, 0, Level { depth: 0, block });
    let mut nodes = Vec::with_capacity(refs.len() / 4 + 1);
    flatten(&[&root], &mut nodes);
    // Copy into a huge-page backed array of the exact size.
    let mut packed = huge_vec(nodes.len());
    packed.extend_from_slice(&nodes);
    Some((
        packed,
        refs.iter().map(|r| r.index).collect(),
        *root.bounds(),
    ))
}

/// Writes a wide node holding `kids` (1 or 2 build nodes) after collapsing
/// the largest interior grandchildren into it; returns its index.
fn flatten(kids: &[&BuildNode], out: &mut Vec<Node>) -> u32 {
    let mut lanes: Vec<&BuildNode> = kids.to_vec();
    while lanes.len() < WIDTH {
        // Open the interior child with the largest surface area.
        let pick = lanes
            .iter()
            .enumerate()
            .filter(|(_, k)| matches!(k, BuildNode::Interior { .. }))
            .max_by(|a, b| {
                a.1.bounds()
                    .surface_area()
                    .total_cmp(&b.1.bounds().surface_area())
            })
            .map(|(i, _)| i);
        let Some(i) = pick else { break };
        let BuildNode::Interior { children, .. } = lanes[i] else {
            unreachable!()
        };
        lanes[i] = &children[0];
        lanes.insert(i + 1, &children[1]);
    }
    let idx = out.len();
    out.push(EMPTY_NODE);
    for (i, k) in lanes.iter().enumerate() {
        let b = k.bounds();
        let (child, count) = match k {
            BuildNode::Leaf { start, count, .. } => (*start as u32, *count as u32),
            BuildNode::Interior { children, .. } => {
                (flatten(&[&children[0], &children[1]], out), 0)
            }
        };
        let n = &mut out[idx];
        let (g, l) = (i / 4, i % 4);
        for a in 0..3 {
            n.planes[g][a][l] = b.min[a];
            n.planes[g][a + 3][l] = b.max[a];
        }
        n.child[i] = child;
        n.count[i] = count;
    }
    idx as u32
}

/// The primitives' bounds, their centroids' bounds, and how many must be alone.
fn bounds_of(refs: &[PrimRef]) -> (Aabb, Aabb, usize) {
    let mut b = Aabb::EMPTY;
    let mut c = Aabb::EMPTY;
    let mut alone = 0;
    for r in refs {
        b = b.union(&r.bounds);
        c.grow(r.centroid);
        alone += r.alone as usize;
    }
    (b, c, alone)
}

/// Where a build step is: its depth, and the SAH's block size.
#[derive(Clone, Copy)]
struct Level {
    depth: u32,
    block: usize,
}

fn build_rec(refs: &mut [PrimRef], start: usize, at: Level) -> BuildNode {
    let Level { depth, block } = at;
    // A leaf's cost: its blocks of primitives, each lone primitive one more.
    let blocks = |n: u32, alone: u32| (n - alone).div_ceil(block as u32) as f32 + alone as f32;
    let (bounds, cb, alone) = bounds_of(refs);
    let n = refs.len();
    let leaf = BuildNode::Leaf {
        bounds,
        start,
        count: n,
    };
    // Whether this may be a leaf: not too many, none that must be alone
    // among others.
    let may_leaf = n <= MAX_LEAF && (alone == 0 || n == 1);
    if n <= block.max(2) && may_leaf {
        return leaf;
    }
    let ext = cb.extent();
    let axis = if ext.x > ext.y && ext.x > ext.z {
        0
    } else if ext.y > ext.z {
        1
    } else {
        2
    };
    if depth >= MEDIAN_DEPTH {
        // Deep trees: balanced splits bound the depth (and the traversal stack) by 2 * MEDIAN_DEPTH.
        if may_leaf {
            return leaf;
        }
        return split_at(refs, start, n / 2, bounds, at);
    }
    if ext[axis] <= 0.0 {
        // All centroids coincide: split in the middle by count if too many for a leaf.
        if may_leaf {
            return leaf;
        }
        return split_at(refs, start, n / 2, bounds, at);
    }
    // Binned SAH over all three axes.
    let mut best = (f32::INFINITY, 0usize, 0usize); // cost, axis, split bin
    for ax in 0..3 {
        if ext[ax] <= 0.0 {
            continue;
        }
        let scale = BINS as f32 / ext[ax];
        // Per bin: primitives, and how many of them must be alone.
        let mut counts = [(0u32, 0u32); BINS];
        let mut boxes = [Aabb::EMPTY; BINS];
        for r in refs.iter() {
            let b = (((r.centroid[ax] - cb.min[ax]) * scale) as usize).min(BINS - 1);
            counts[b].0 += 1;
            counts[b].1 += r.alone as u32;
            boxes[b] = boxes[b].union(&r.bounds);
        }
        let mut right_area = [0f32; BINS];
        let mut right_count = [(0u32, 0u32); BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, (0u32, 0u32));
        for i in (1..BINS).rev() {
            acc = acc.union(&boxes[i]);
            cnt = (cnt.0 + counts[i].0, cnt.1 + counts[i].1);
            right_area[i] = acc.surface_area();
            right_count[i] = cnt;
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, (0u32, 0u32));
        for i in 0..BINS - 1 {
            acc = acc.union(&boxes[i]);
            cnt = (cnt.0 + counts[i].0, cnt.1 + counts[i].1);
            let right = right_count[i + 1];
            if cnt.0 == 0 || right.0 == 0 {
                continue;
            }
            let cost = blocks(cnt.0, cnt.1) * acc.surface_area()
                + blocks(right.0, right.1) * right_area[i + 1];
            if cost < best.0 {
                best = (cost, ax, i);
            }
        }
    }
    let area = bounds.surface_area().max(1e-30);
    let split_cost = TRAVERSAL_COST + best.0 / area;
    if best.0 == f32::INFINITY || (split_cost >= blocks(n as u32, alone as u32) && may_leaf) {
        if may_leaf {
            return leaf;
        }
        return split_at(refs, start, n / 2, bounds, at);
    }
    let (ax, bin) = (best.1, best.2);
    let scale = BINS as f32 / ext[ax];
    let mid = partition(refs, |r| {
        (((r.centroid[ax] - cb.min[ax]) * scale) as usize).min(BINS - 1) <= bin
    });
    if mid == 0 || mid == n {
        return split_at(refs, start, n / 2, bounds, at);
    }
    children(refs, start, mid, bounds, at)
}

fn split_at(refs: &mut [PrimRef], start: usize, mid: usize, bounds: Aabb, at: Level) -> BuildNode {
    let ext = bounds.extent();
    let axis = if ext.x > ext.y && ext.x > ext.z {
        0
    } else if ext.y > ext.z {
        1
    } else {
        2
    };
    refs.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    children(refs, start, mid, bounds, at)
}

fn children(refs: &mut [PrimRef], start: usize, mid: usize, bounds: Aabb, at: Level) -> BuildNode {
    let next = Level {
        depth: at.depth + 1,
        ..at
    };
    let big = refs.len() > PARALLEL_THRESHOLD;
    let (l, r) = refs.split_at_mut(mid);
    let (a, b) = if big {
        rayon::join(
            || build_rec(l, start, next),
            || build_rec(r, start + mid, next),
        )
    } else {
        (build_rec(l, start, next), build_rec(r, start + mid, next))
    };
    BuildNode::Interior {
        bounds,
        children: Box::new([a, b]),
    }
}

fn partition(refs: &mut [PrimRef], pred: impl Fn(&PrimRef) -> bool) -> usize {
    let mut i = 0;
    for j in 0..refs.len() {
        if pred(&refs[j]) {
            refs.swap(i, j);
            i += 1;
        }
    }
    i
}
