//! Bounding volume hierarchy: binned SAH build (parallel for large nodes),
//! depth-first flattened nodes, closest-hit and any-hit traversal.
//!
//! The BVH knows only boxes; primitives are tested through a callback that
//! receives the leaf slot (an index into `order`), so the caller can keep
//! primitive data in BVH order for locality.

use crate::geometry::{Aabb, Ray};
use lumis_math::Vec3;
use lumis_math::Vec3A;

const BINS: usize = 16;
const MAX_LEAF: usize = 8;
const TRAVERSAL_COST: f32 = 1.0;
const PARALLEL_THRESHOLD: usize = 16 * 1024;
const MEDIAN_DEPTH: u32 = 31;

/// A 32-byte node: leaves hold `count > 0` primitives from `offset`; interior
/// nodes (`count == 0`) have their left child next and their right child at `offset`.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub struct Node {
    min: [f32; 3],
    count: u32,
    max: [f32; 3],
    offset: u32,
}

#[derive(Clone, Debug, Default)]
pub struct Bvh {
    pub nodes: Vec<Node>,
    /// Leaf slot → index of the primitive in the caller's list.
    pub order: Vec<u32>,
}

#[derive(Clone, Copy)]
struct PrimRef {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
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

impl Bvh {
    /// Builds over primitives given by their bounds. Empty boxes are skipped.
    pub fn build(bounds: &[Aabb]) -> Bvh {
        let mut refs: Vec<PrimRef> = bounds
            .iter()
            .enumerate()
            .filter(|(_, b)| !b.is_empty())
            .map(|(i, b)| PrimRef {
                bounds: *b,
                centroid: b.center(),
                index: i as u32,
            })
            .collect();
        if refs.is_empty() {
            return Bvh::default();
        }
        let root = build_rec(&mut refs, 0, 0);
        let mut nodes = Vec::with_capacity(2 * refs.len() / 2 + 1);
        flatten(&root, &mut nodes);
        Bvh {
            nodes,
            order: refs.iter().map(|r| r.index).collect(),
        }
    }

    pub fn bounds(&self) -> Aabb {
        match self.nodes.first() {
            Some(n) => Aabb {
                min: Vec3::from(n.min),
                max: Vec3::from(n.max),
            },
            None => Aabb::EMPTY,
        }
    }

    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node>() + self.order.len() * 4
    }

    /// Closest hit: `test(slot, ray, tmax)` returns the hit distance if the
    /// primitive is hit closer than `tmax`. Returns `(t, slot)`.
    #[inline]
    pub fn closest(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, &Ray, f32) -> Option<f32>,
    ) -> Option<(f32, u32)> {
        if self.nodes.is_empty() {
            return None;
        }
        let o = Vec3A::from(ray.o);
        let inv_d = Vec3A::ONE / Vec3A::from(ray.d);
        let mut tmax = ray.tmax;
        let mut best = None;
        let mut stack = [0u32; 64];
        let mut sp = 0usize;
        let mut idx = 0u32;
        if hit_box(&self.nodes[0], o, inv_d, tmax) == f32::INFINITY {
            return None;
        }
        loop {
            let node = &self.nodes[idx as usize];
            if node.count > 0 {
                for slot in node.offset..node.offset + node.count {
                    if let Some(t) = test(slot, ray, tmax) {
                        tmax = t;
                        best = Some((t, slot));
                    }
                }
            } else {
                let (l, r) = (idx + 1, node.offset);
                let tl = hit_box(&self.nodes[l as usize], o, inv_d, tmax);
                let tr = hit_box(&self.nodes[r as usize], o, inv_d, tmax);
                match (tl < f32::INFINITY, tr < f32::INFINITY) {
                    (true, true) => {
                        let (near, far) = if tl <= tr { (l, r) } else { (r, l) };
                        stack[sp] = far;
                        sp += 1;
                        idx = near;
                        continue;
                    }
                    (true, false) => {
                        idx = l;
                        continue;
                    }
                    (false, true) => {
                        idx = r;
                        continue;
                    }
                    (false, false) => {}
                }
            }
            // Pop, skipping nodes that are now farther than the closest hit.
            loop {
                if sp == 0 {
                    return best;
                }
                sp -= 1;
                idx = stack[sp];
                if hit_box(&self.nodes[idx as usize], o, inv_d, tmax) < f32::INFINITY {
                    break;
                }
            }
        }
    }

    /// Any hit closer than `ray.tmax`: `test(slot, ray, tmax)` says whether the primitive blocks.
    #[inline]
    pub fn any(&self, ray: &Ray, mut test: impl FnMut(u32, &Ray, f32) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let o = Vec3A::from(ray.o);
        let inv_d = Vec3A::ONE / Vec3A::from(ray.d);
        let tmax = ray.tmax;
        let mut stack = [0u32; 64];
        let mut sp = 0usize;
        if hit_box(&self.nodes[0], o, inv_d, tmax) == f32::INFINITY {
            return false;
        }
        let mut idx = 0u32;
        loop {
            let node = &self.nodes[idx as usize];
            if node.count > 0 {
                for slot in node.offset..node.offset + node.count {
                    if test(slot, ray, tmax) {
                        return true;
                    }
                }
            } else {
                let (l, r) = (idx + 1, node.offset);
                let hl = hit_box(&self.nodes[l as usize], o, inv_d, tmax) < f32::INFINITY;
                let hr = hit_box(&self.nodes[r as usize], o, inv_d, tmax) < f32::INFINITY;
                if hl && hr {
                    stack[sp] = r;
                    sp += 1;
                    idx = l;
                    continue;
                } else if hl {
                    idx = l;
                    continue;
                } else if hr {
                    idx = r;
                    continue;
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            idx = stack[sp];
        }
    }
}

/// Entry distance of the ray into the node's box, or infinity on a miss.
#[inline(always)]
fn hit_box(n: &Node, o: Vec3A, inv_d: Vec3A, tmax: f32) -> f32 {
    let t0 = (Vec3A::from(n.min) - o) * inv_d;
    let t1 = (Vec3A::from(n.max) - o) * inv_d;
    let tnear = t0.min(t1).max_element().max(0.0);
    // Conservative far bound (Ize 2013) so rounding never loses a hit.
    let tfar = t0.max(t1).min_element() * (1.0 + 2.0 * 3.0 * f32::EPSILON * 0.5);
    if tnear <= tfar.min(tmax) {
        tnear
    } else {
        f32::INFINITY
    }
}

fn bounds_of(refs: &[PrimRef]) -> (Aabb, Aabb) {
    let mut b = Aabb::EMPTY;
    let mut c = Aabb::EMPTY;
    for r in refs {
        b = b.union(&r.bounds);
        c.grow(r.centroid);
    }
    (b, c)
}

fn build_rec(refs: &mut [PrimRef], start: usize, depth: u32) -> BuildNode {
    let (bounds, cb) = bounds_of(refs);
    let n = refs.len();
    let leaf = BuildNode::Leaf {
        bounds,
        start,
        count: n,
    };
    if n <= 2 {
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
        if n <= MAX_LEAF {
            return leaf;
        }
        return split_at(refs, start, n / 2, bounds, depth);
    }
    if ext[axis] <= 0.0 {
        // All centroids coincide: split in the middle by count if too many for a leaf.
        if n <= MAX_LEAF {
            return leaf;
        }
        return split_at(refs, start, n / 2, bounds, depth);
    }
    // Binned SAH over all three axes.
    let mut best = (f32::INFINITY, 0usize, 0usize); // cost, axis, split bin
    for ax in 0..3 {
        if ext[ax] <= 0.0 {
            continue;
        }
        let scale = BINS as f32 / ext[ax];
        let mut counts = [0u32; BINS];
        let mut boxes = [Aabb::EMPTY; BINS];
        for r in refs.iter() {
            let b = (((r.centroid[ax] - cb.min[ax]) * scale) as usize).min(BINS - 1);
            counts[b] += 1;
            boxes[b] = boxes[b].union(&r.bounds);
        }
        let mut right_area = [0f32; BINS];
        let mut right_count = [0u32; BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0u32);
        for i in (1..BINS).rev() {
            acc = acc.union(&boxes[i]);
            cnt += counts[i];
            right_area[i] = acc.surface_area();
            right_count[i] = cnt;
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0u32);
        for i in 0..BINS - 1 {
            acc = acc.union(&boxes[i]);
            cnt += counts[i];
            if cnt == 0 || right_count[i + 1] == 0 {
                continue;
            }
            let cost =
                cnt as f32 * acc.surface_area() + right_count[i + 1] as f32 * right_area[i + 1];
            if cost < best.0 {
                best = (cost, ax, i);
            }
        }
    }
    let area = bounds.surface_area().max(1e-30);
    let split_cost = TRAVERSAL_COST + best.0 / area;
    if best.0 == f32::INFINITY || (split_cost >= n as f32 && n <= MAX_LEAF) {
        if n <= MAX_LEAF {
            return leaf;
        }
        return split_at(refs, start, n / 2, bounds, depth);
    }
    let (ax, bin) = (best.1, best.2);
    let scale = BINS as f32 / ext[ax];
    let mid = partition(refs, |r| {
        (((r.centroid[ax] - cb.min[ax]) * scale) as usize).min(BINS - 1) <= bin
    });
    if mid == 0 || mid == n {
        return split_at(refs, start, n / 2, bounds, depth);
    }
    children(refs, start, mid, bounds, depth)
}

fn split_at(refs: &mut [PrimRef], start: usize, mid: usize, bounds: Aabb, depth: u32) -> BuildNode {
    let ext = bounds.extent();
    let axis = if ext.x > ext.y && ext.x > ext.z {
        0
    } else if ext.y > ext.z {
        1
    } else {
        2
    };
    refs.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    children(refs, start, mid, bounds, depth)
}

fn children(refs: &mut [PrimRef], start: usize, mid: usize, bounds: Aabb, depth: u32) -> BuildNode {
    let big = refs.len() > PARALLEL_THRESHOLD;
    let (l, r) = refs.split_at_mut(mid);
    let (a, b) = if big {
        rayon::join(
            || build_rec(l, start, depth + 1),
            || build_rec(r, start + mid, depth + 1),
        )
    } else {
        (
            build_rec(l, start, depth + 1),
            build_rec(r, start + mid, depth + 1),
        )
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

fn flatten(node: &BuildNode, out: &mut Vec<Node>) -> u32 {
    let idx = out.len() as u32;
    match node {
        BuildNode::Leaf {
            bounds,
            start,
            count,
        } => {
            out.push(Node {
                min: bounds.min.into(),
                count: *count as u32,
                max: bounds.max.into(),
                offset: *start as u32,
            });
        }
        BuildNode::Interior { bounds, children } => {
            out.push(Node {
                min: bounds.min.into(),
                count: 0,
                max: bounds.max.into(),
                offset: 0,
            });
            flatten(&children[0], out);
            let right = flatten(&children[1], out);
            out[idx as usize].offset = right;
        }
    }
    idx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_and_single() {
        let b = Bvh::build(&[]);
        assert!(b
            .closest(&Ray::new(Vec3::ZERO, Vec3::X), |_, _, _| Some(1.0))
            .is_none());
        let one = Bvh::build(&[Aabb {
            min: Vec3::splat(1.0),
            max: Vec3::splat(2.0),
        }]);
        let r = Ray::new(Vec3::ZERO, Vec3::ONE.normalize());
        assert_eq!(one.closest(&r, |_, _, _| Some(1.5)).map(|h| h.1), Some(0));
        let miss = Ray::new(Vec3::ZERO, -Vec3::ONE.normalize());
        assert!(!one.any(&miss, |_, _, _| true));
    }

    #[test]
    fn node_is_32_bytes() {
        assert_eq!(std::mem::size_of::<Node>(), 32);
    }
}
