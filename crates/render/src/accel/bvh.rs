//! Bounding volume hierarchy: depth-first flattened 8-wide nodes (built in
//! `build.rs`), closest-hit and any-hit traversal.
//!
//! The BVH knows only boxes; primitives are tested through a callback that
//! receives the leaf slot (an index into `order`), so the caller can keep
//! primitive data in BVH order for locality.

use super::build::{self, MEDIAN_DEPTH};
use super::mem::prefetch_lines;
use crate::geometry::{Aabb, Ray};
use lumis_math::Vec3;
use lumis_math::Vec4;
use std::mem::MaybeUninit;

/// Boxes are culled against `tmax * CULL_SLACK`: a primitive's computed hit
/// distance may round a few ulps below its box's computed entry distance, and
/// such a hit must not be lost when it is just closer than the current `tmax`.
const CULL_SLACK: f32 = 1.0 + 32.0 * f32::EPSILON;

/// Children per node.
pub(super) const WIDTH: usize = 8;

/// An 8-wide node (256 bytes, four cache lines): the boxes of up to eight
/// children in SoA form, two groups of four, so two SIMD slab tests handle
/// all of them. Traversal is bound by the latency of dependent node loads;
/// eight children per node make the tree a third shallower than four, and
/// the four lines of a node load in parallel.
/// Child `i` is a leaf of `count[i] > 0` primitives from slot `child[i]`, an
/// interior node at index `child[i]` (`count[i] == 0`), or unused (empty box).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub struct Node {
    /// Per group of four children: min x, min y, min z, max x, max y, max z.
    pub(super) planes: [[Vec4; 6]; 2],
    pub(super) child: [u32; WIDTH],
    pub(super) count: [u32; WIDTH],
}

const EMPTY_GROUP: [Vec4; 6] = [
    Vec4::INFINITY,
    Vec4::INFINITY,
    Vec4::INFINITY,
    Vec4::NEG_INFINITY,
    Vec4::NEG_INFINITY,
    Vec4::NEG_INFINITY,
];

pub(super) const EMPTY_NODE: Node = Node {
    planes: [EMPTY_GROUP; 2],
    child: [0; WIDTH],
    count: [0; WIDTH],
};

/// Traversal stack size. Each node level pushes at most `WIDTH - 1` entries
/// and the build bounds the binary depth by `MEDIAN_DEPTH + 32`, so this never overflows.
const STACK: usize = (WIDTH - 1) * (MEDIAN_DEPTH as usize + 34);

#[derive(Clone, Debug, Default)]
pub struct Bvh {
    pub nodes: Vec<Node>,
    /// Leaf slot → index of the primitive in the caller's list.
    pub order: Vec<u32>,
    bounds: Aabb,
}

/// Per-ray constants of the slab test.
struct RayBoxes {
    o: [Vec4; 3],
    inv_d: [Vec4; 3],
    /// Plane index (into `Node::planes`) of the near and far slab plane per axis.
    near: [usize; 3],
    far: [usize; 3],
}

impl RayBoxes {
    #[inline(always)]
    fn new(ray: &Ray) -> RayBoxes {
        let inv = Vec3::ONE / ray.d;
        let neg = [
            ray.d.x.is_sign_negative(),
            ray.d.y.is_sign_negative(),
            ray.d.z.is_sign_negative(),
        ];
        RayBoxes {
            o: [
                Vec4::splat(ray.o.x),
                Vec4::splat(ray.o.y),
                Vec4::splat(ray.o.z),
            ],
            inv_d: [Vec4::splat(inv.x), Vec4::splat(inv.y), Vec4::splat(inv.z)],
            near: [
                3 * neg[0] as usize,
                1 + 3 * neg[1] as usize,
                2 + 3 * neg[2] as usize,
            ],
            far: [
                3 - 3 * neg[0] as usize,
                4 - 3 * neg[1] as usize,
                5 - 3 * neg[2] as usize,
            ],
        }
    }

    /// Entry distances of the eight children and the mask of those hit before `tmax`.
    #[inline(always)]
    fn test(&self, n: &Node, tmax: f32) -> ([f32; WIDTH], u32) {
        let (t0, m0) = self.test4(&n.planes[0], tmax);
        let (t1, m1) = self.test4(&n.planes[1], tmax);
        let (a, b) = (t0.to_array(), t1.to_array());
        (
            [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]],
            m0 | (m1 << 4),
        )
    }

    /// Entry distances of four children and the mask of those hit before `tmax`.
    ///
    /// With a zero direction component and the origin exactly on a slab plane,
    /// `0 * inf` gives NaN; glam's `min`/`max` (SSE `minps`/`maxps` and the
    /// scalar fallback alike) return the second operand when either is NaN, so
    /// folding each axis in as the *first* operand drops the NaN, treating
    /// the ray as inside that (closed) slab.
    #[inline(always)]
    fn test4(&self, p: &[Vec4; 6], tmax: f32) -> (Vec4, u32) {
        let tn0 = (p[self.near[0]] - self.o[0]) * self.inv_d[0];
        let tn1 = (p[self.near[1]] - self.o[1]) * self.inv_d[1];
        let tn2 = (p[self.near[2]] - self.o[2]) * self.inv_d[2];
        let tf0 = (p[self.far[0]] - self.o[0]) * self.inv_d[0];
        let tf1 = (p[self.far[1]] - self.o[1]) * self.inv_d[1];
        let tf2 = (p[self.far[2]] - self.o[2]) * self.inv_d[2];
        let tnear = tn2.max(tn1.max(tn0.max(Vec4::ZERO)));
        // Conservative far bound (Ize 2013) so rounding never loses a hit.
        let tfar = tf2.min(tf1.min(tf0)) * (1.0 + 2.0 * 3.0 * f32::EPSILON * 0.5);
        let tfar = tfar.min(Vec4::splat(tmax));
        (tnear, tnear.cmple(tfar).bitmask())
    }
}

#[derive(Clone, Copy, Default)]
struct Entry {
    child: u32,
    count: u32,
    t: f32,
}

impl Bvh {
    /// Builds over primitives given by their bounds. Empty boxes, and boxes
    /// with a NaN, are skipped.
    pub fn build(bounds: &[Aabb]) -> Bvh {
        Bvh::build_blocks(bounds, 1, |_| false)
    }

    /// [`Bvh::build`] whose SAH counts primitives in blocks of `block`
    /// (a leaf of up to `block` primitives costs one test), with each
    /// primitive `i` for which `alone(i)` holds in a leaf by itself.
    fn build_blocks(bounds: &[Aabb], block: usize, alone: impl Fn(usize) -> bool) -> Bvh {
        match build::build(bounds, block, alone) {
            Some((nodes, order, bounds)) => Bvh {
                nodes,
                order,
                bounds,
            },
            None => Bvh::default(),
        }
    }

    /// [`Bvh::build`] with every leaf of more than one primitive starting
    /// at a multiple of `align` slots, so a caller can keep its primitives
    /// in packets of `align` and test such a leaf a packet at a time; the
    /// slots between leaves are padding, `u32::MAX` in `order`. Leaves of
    /// one primitive share packets. Each primitive `i` for which
    /// `alone(i)` holds gets a leaf of its own.
    pub fn build_aligned(bounds: &[Aabb], align: usize, alone: impl Fn(usize) -> bool) -> Bvh {
        let mut bvh = Bvh::build_blocks(bounds, align, alone);
        let mut leaves = Vec::new();
        for (n, node) in bvh.nodes.iter().enumerate() {
            for i in 0..WIDTH {
                if node.count[i] > 0 {
                    leaves.push((node.child[i], n, i));
                }
            }
        }
        leaves.sort_unstable();
        let mut order = Vec::with_capacity(bvh.order.len() + leaves.len() * (align - 1));
        for (start, n, i) in leaves {
            let node = &mut bvh.nodes[n];
            if node.count[i] > 1 {
                order.resize(order.len().next_multiple_of(align), u32::MAX);
            }
            node.child[i] = order.len() as u32;
            order.extend_from_slice(&bvh.order[start as usize..(start + node.count[i]) as usize]);
        }
        order.resize(order.len().next_multiple_of(align), u32::MAX);
        bvh.order = order;
        bvh
    }

    pub fn bounds(&self) -> Aabb {
        if self.nodes.is_empty() {
            Aabb::EMPTY
        } else {
            self.bounds
        }
    }

    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node>() + self.order.len() * 4
    }

    /// Where slot `start`'s entry of `order` is, for a prefetch.
    #[inline(always)]
    fn slot_address(&self, start: u32) -> *const u8 {
        self.order.as_ptr().wrapping_add(start as usize) as *const u8
    }

    /// Starts loading child `i` of `node`: the first four cache lines of its
    /// node, or of its primitives (`leaf_at(start)` is where the caller
    /// keeps slot `start`'s). Both addresses are computed and one is
    /// picked without a branch: whether a child is a leaf is unpredictable.
    #[inline(always)]
    fn prefetch_child(&self, node: &Node, i: usize, leaf_at: &impl Fn(u32) -> *const u8) {
        let (child, count) = (node.child[i], node.count[i]);
        let inner = self.nodes.as_ptr().wrapping_add(child as usize) as usize;
        let leaf = leaf_at(child) as usize & !63;
        prefetch_lines::<4>(if count > 0 { leaf } else { inner } as *const u8);
    }

    /// Closest hit: `test(slot, ray, tmax)` returns the hit distance if the
    /// primitive is hit closer than `tmax`. Returns `(t, slot)`. A hit
    /// leaf's `order` entries are prefetched (a caller that keeps its
    /// primitives in slot order prefetches them with [`Bvh::closest_hinted`]).
    #[inline]
    pub fn closest(
        &self,
        ray: &Ray,
        test: impl FnMut(u32, &Ray, f32) -> Option<f32>,
    ) -> Option<(f32, u32)> {
        self.closest_hinted(ray, test, |start| self.slot_address(start))
    }

    /// [`Bvh::closest`] that also prefetches each leaf's primitives as soon
    /// as its box is hit (before the leaf is tested, if ever), from
    /// `leaf_at(start)`, the address of slot `start`'s (any address will
    /// do: a prefetch never faults).
    #[inline]
    pub fn closest_hinted(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, &Ray, f32) -> Option<f32>,
        leaf_at: impl Fn(u32) -> *const u8,
    ) -> Option<(f32, u32)> {
        self.closest_leaves(
            ray,
            |start, count, r, mut tmax| {
                let mut best = None;
                for slot in start..start + count {
                    if let Some(t) = test(slot, r, tmax) {
                        tmax = t;
                        best = Some((t, slot));
                    }
                }
                best
            },
            leaf_at,
        )
    }

    /// [`Bvh::closest_hinted`] with the primitives tested a leaf at a time:
    /// `test(start, count, ray, tmax)` returns the closest hit `(t, slot)`
    /// with `t < tmax` among slots `start..start + count`.
    #[inline]
    pub fn closest_leaves(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, u32, &Ray, f32) -> Option<(f32, u32)>,
        leaf_at: impl Fn(u32) -> *const u8,
    ) -> Option<(f32, u32)> {
        if self.nodes.is_empty() {
            return None;
        }
        let rb = RayBoxes::new(ray);
        let mut tmax = ray.tmax;
        let mut tcull = tmax * CULL_SLACK;
        let mut best = None;
        // Left uninitialised: zeroing 5 KiB per ray cost 13% of a path render
        // of a small scene. Slots `0..sp` are always written before read.
        let mut stack = [const { MaybeUninit::<Entry>::uninit() }; STACK];
        let mut sp = 0usize;
        let mut cur = Entry {
            child: 0,
            count: 0,
            t: 0.0,
        };
        loop {
            if cur.count > 0 {
                if let Some((t, slot)) = test(cur.child, cur.count, ray, tmax) {
                    tmax = t;
                    tcull = t * CULL_SLACK;
                    best = Some((t, slot));
                }
            } else {
                let node = &self.nodes[cur.child as usize];
                let (tnear, mut mask) = rb.test(node, tcull);
                if mask != 0 {
                    let tn = tnear;
                    // Push the hit children far to near; continue with the nearest.
                    let base = sp;
                    while mask != 0 {
                        let i = mask.trailing_zeros() as usize & (WIDTH - 1);
                        mask &= mask - 1;
                        self.prefetch_child(node, i, &leaf_at);
                        let e = Entry {
                            child: node.child[i],
                            count: node.count[i],
                            t: tn[i],
                        };
                        let mut j = sp;
                        // SAFETY: `base <= j - 1 < sp`: slots below `sp` are written.
                        while j > base && unsafe { stack[j - 1].assume_init() }.t < e.t {
                            stack[j] = stack[j - 1];
                            j -= 1;
                        }
                        stack[j] = MaybeUninit::new(e);
                        sp += 1;
                    }
                    sp -= 1;
                    // SAFETY: the loop above wrote slots up to the old `sp`.
                    cur = unsafe { stack[sp].assume_init() };
                    continue;
                }
            }
            // Pop, skipping entries that are now farther than the closest hit.
            loop {
                if sp == 0 {
                    return best;
                }
                sp -= 1;
                // SAFETY: `sp` was above this slot, so it was written.
                let e = unsafe { stack[sp].assume_init() };
                if e.t <= tcull {
                    cur = e;
                    break;
                }
            }
        }
    }

    /// Any hit closer than `ray.tmax`: `test(slot, ray, tmax)` says whether the primitive blocks.
    #[inline]
    pub fn any(&self, ray: &Ray, test: impl FnMut(u32, &Ray, f32) -> bool) -> bool {
        self.any_hinted(ray, test, |start| self.slot_address(start))
    }

    /// [`Bvh::any`] with leaf prefetches as in [`Bvh::closest_hinted`].
    #[inline]
    pub fn any_hinted(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, &Ray, f32) -> bool,
        leaf_at: impl Fn(u32) -> *const u8,
    ) -> bool {
        self.any_leaves(
            ray,
            |start, count, r, tmax| (start..start + count).any(|slot| test(slot, r, tmax)),
            leaf_at,
        )
    }

    /// [`Bvh::any_hinted`] with the primitives tested a leaf at a time:
    /// `test(start, count, ray, tmax)` says whether any of slots
    /// `start..start + count` blocks the ray.
    #[inline]
    pub fn any_leaves(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, u32, &Ray, f32) -> bool,
        leaf_at: impl Fn(u32) -> *const u8,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let rb = RayBoxes::new(ray);
        let tmax = ray.tmax;
        // Uninitialised as in `closest_hinted`; slots `0..sp` are written.
        let mut stack = [const { MaybeUninit::<(u32, u32)>::uninit() }; STACK];
        let mut sp = 0usize;
        let (mut child, mut count) = (0u32, 0u32);
        loop {
            if count > 0 {
                if test(child, count, ray, tmax) {
                    return true;
                }
            } else {
                let node = &self.nodes[child as usize];
                let (_, mut mask) = rb.test(node, tmax * CULL_SLACK);
                while mask != 0 {
                    let i = mask.trailing_zeros() as usize & (WIDTH - 1);
                    mask &= mask - 1;
                    self.prefetch_child(node, i, &leaf_at);
                    stack[sp] = MaybeUninit::new((node.child[i], node.count[i]));
                    sp += 1;
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            // SAFETY: every push wrote its slot before raising `sp` past it.
            (child, count) = unsafe { stack[sp].assume_init() };
        }
    }
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
    fn lone_primitives_get_leaves_of_their_own() {
        // Small boxes in clusters, every third one to be alone: a leaf
        // holding one of those holds nothing else, and every box is in
        // exactly one leaf.
        let mut rng = lumis_math::Pcg32::new(5, 1);
        let boxes: Vec<Aabb> = (0..500)
            .map(|i| {
                let c = Vec3::new((i % 7) as f32, rng.next_f32() * 0.1, rng.next_f32() * 0.1);
                Aabb {
                    min: c,
                    max: c + Vec3::splat(0.01 + 0.05 * rng.next_f32()),
                }
            })
            .collect();
        let alone = |i: usize| i.is_multiple_of(3);
        let bvh = Bvh::build_aligned(&boxes, 4, alone);
        let mut seen = vec![0u32; boxes.len()];
        for node in &bvh.nodes {
            for i in 0..WIDTH {
                let (start, count) = (node.child[i] as usize, node.count[i] as usize);
                let slots = &bvh.order[start..start + count];
                for &p in slots {
                    seen[p as usize] += 1;
                    assert!(
                        count == 1 || !alone(p as usize),
                        "{p} shares a leaf of {count}"
                    );
                }
            }
        }
        assert!(seen.iter().all(|&n| n == 1));
    }

    #[test]
    fn node_is_256_bytes() {
        assert_eq!(std::mem::size_of::<Node>(), 256);
    }

    #[test]
    fn nan_dropping_min_max() {
        // The slab test relies on min/max returning the second operand on NaN.
        let nan = Vec4::splat(f32::NAN);
        assert_eq!(nan.max(Vec4::ONE), Vec4::ONE);
        assert_eq!(nan.min(Vec4::ONE), Vec4::ONE);
    }

    #[test]
    fn ray_in_box_face_plane() {
        let b = Bvh::build(&[Aabb {
            min: Vec3::new(0.0, 0.0, 0.0),
            max: Vec3::new(1.0, 1.0, 1.0),
        }]);
        for (o, d) in [
            (Vec3::new(-1.0, 0.0, 0.5), Vec3::X),
            (Vec3::new(-1.0, 1.0, 1.0), Vec3::X),
            (Vec3::new(2.0, 1.0, 0.0), -Vec3::X),
            (Vec3::new(0.5, 0.0, 2.0), Vec3::new(0.0, -0.0, -1.0)),
        ] {
            assert!(b.any(&Ray::new(o, d), |_, _, _| true), "{o} {d}");
        }
        assert!(
            !b.any(&Ray::new(Vec3::new(-1.0, 1.5, 0.5), Vec3::X), |_, _, _| {
                true
            })
        );
    }
}
