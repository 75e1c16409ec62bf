//! The BVH's build: a binned SAH over the primitives' centroids (its
//! large nodes split in parallel), into binary nodes that [`flatten`]
//! collapses into the 8-wide [`Node`]s the traversal reads.

use super::bvh::{Node, EMPTY_NODE, WIDTH};
use super::mem::huge_vec;
use crate::geometry::Aabb;
use lumis_math::{Vec3, Vec3A};

const BINS: usize = 16;
const MAX_LEAF: usize = 8;
const TRAVERSAL_COST: f32 = 3.0;
const PARALLEL_THRESHOLD: usize = 16 * 1024;
/// Depth from which splits are at the median: the binary depth stays
/// below `MEDIAN_DEPTH + 32`, which sizes the traversal stacks.
pub(super) const MEDIAN_DEPTH: u32 = 31;

/// A box in SIMD lanes: unions are one `min` and one `max` (the build's
/// boxes hold no NaN, where the lanes' and `f32::min`'s rules differ, so
/// every box equals the scalar [`Aabb`]'s).
#[derive(Clone, Copy)]
struct Box3 {
    lo: Vec3A,
    hi: Vec3A,
}

impl Box3 {
    const EMPTY: Box3 = Box3 {
        lo: Vec3A::INFINITY,
        hi: Vec3A::NEG_INFINITY,
    };

    #[inline(always)]
    fn union(self, o: Box3) -> Box3 {
        Box3 {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    #[inline(always)]
    fn grow(self, p: Vec3A) -> Box3 {
        Box3 {
            lo: self.lo.min(p),
            hi: self.hi.max(p),
        }
    }

    /// [`Aabb::surface_area`] of a box known not to be empty (the same
    /// arithmetic, without the test).
    #[inline(always)]
    fn area(self) -> f32 {
        let e = self.hi - self.lo;
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    fn aabb(self) -> Aabb {
        Aabb {
            min: self.lo.into(),
            max: self.hi.into(),
        }
    }
}

#[derive(Clone, Copy)]
struct PrimRef {
    bounds: Box3,
    index: u32,
    /// A primitive that gets a leaf of its own (an analytic shape: its test
    /// costs as much as a packet of four triangles, and its box is the only
    /// cheap way to skip it).
    alone: bool,
}

impl PrimRef {
    /// The box's centre, as [`Aabb::center`] computes it.
    #[inline(always)]
    fn centroid(&self) -> Vec3A {
        0.5 * (self.bounds.lo + self.bounds.hi)
    }
}

/// One bin of the SAH: its primitives' box, how many, and how many of them
/// must be alone.
#[derive(Clone, Copy)]
struct Bin {
    bounds: Box3,
    count: u32,
    alone: u32,
}

const EMPTY_BIN: Bin = Bin {
    bounds: Box3::EMPTY,
    count: 0,
    alone: 0,
};

/// The bin of centroid coordinate `c` on an axis whose centroids start at
/// `min` and span `BINS / scale`.
#[inline(always)]
fn bin_of(c: f32, min: f32, scale: f32) -> usize {
    (((c - min) * scale) as usize).min(BINS - 1)
}

/// [`bin_of`] on the three axes at once.
#[inline(always)]
fn bins_of(c: Vec3A, min: Vec3A, scale: Vec3A) -> [usize; 3] {
    // Clamped to [0, BINS - 1] first (a NaN lane to 0, by `max`'s rule),
    // where truncation is what the saturating `as usize` gives.
    let f = ((c - min) * scale)
        .max(Vec3A::ZERO)
        .min(Vec3A::splat((BINS - 1) as f32));
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_cvtsi128_si32, _mm_cvttps_epi32, _mm_shuffle_epi32};
        // SAFETY: these intrinsics need SSE2 only, part of the x86_64
        // baseline every build targets; they read and write registers only.
        unsafe {
            let i = _mm_cvttps_epi32(f.into());
            [
                _mm_cvtsi128_si32(i) as usize,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<1>(i)) as usize,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<2>(i)) as usize,
            ]
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    [f.x as usize, f.y as usize, f.z as usize]
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
/// `bounds` (empty boxes skipped, and boxes with a NaN: such a primitive
/// cannot be hit, and in the SIMD unions a NaN would replace, not join,
/// its neighbours' extent; `None` if all are skipped): the SAH counts
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
        .filter(|(_, b)| !b.is_empty() && !b.min.is_nan() && !b.max.is_nan())
        .map(|(i, b)| PrimRef {
            bounds: Box3 {
                lo: b.min.into(),
                hi: b.max.into(),
            },
            index: i as u32,
            alone: alone(i),
        })
        .collect();
    if refs.is_empty() {
        return None;
    }
    assert!(block.is_power_of_two(), "blocks of {block} primitives");
    let span = span_of(&refs);
    let root = build_rec(&mut refs, 0, Level { depth: 0, block }, span);
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

/// What a build step knows of its primitives before it reads them: their
/// bounds, their centroids' bounds, and how many must be alone (a split
/// hands them to its two sides, so each level reads the primitives twice,
/// to bin and to partition, not three times).
#[derive(Clone, Copy)]
struct Span {
    bounds: Box3,
    centroids: Box3,
    alone: u32,
}

/// The [`Span`] of `refs`, read from them.
fn span_of(refs: &[PrimRef]) -> Span {
    let mut s = Span {
        bounds: Box3::EMPTY,
        centroids: Box3::EMPTY,
        alone: 0,
    };
    for r in refs {
        s.bounds = s.bounds.union(r.bounds);
        s.centroids = s.centroids.grow(r.centroid());
        s.alone += r.alone as u32;
    }
    s
}

/// Where a build step is: its depth, and the SAH's block size.
#[derive(Clone, Copy)]
struct Level {
    depth: u32,
    block: usize,
}

fn build_rec(refs: &mut [PrimRef], start: usize, at: Level, span: Span) -> BuildNode {
    let Level { depth, block } = at;
    // A leaf's cost: its blocks of primitives, each lone primitive one more
    // (`block` is a power of two: a shift, not a division).
    let shift = block.trailing_zeros();
    let blocks =
        |n: u32, alone: u32| ((n - alone + (block as u32 - 1)) >> shift) as f32 + alone as f32;
    let (bounds, cb, alone) = (
        span.bounds.aabb(),
        span.centroids.aabb(),
        span.alone as usize,
    );
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
    let axis = longest_axis(ext);
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
    // Binned SAH over all three axes, binned in one pass.
    let scales: [f32; 3] = std::array::from_fn(|ax| {
        if ext[ax] > 0.0 {
            BINS as f32 / ext[ax]
        } else {
            0.0
        }
    });
    let (cmin, scale3) = (span.centroids.lo, Vec3A::from(scales));
    let mut bins = [[EMPTY_BIN; BINS]; 3];
    for r in refs.iter() {
        let b = bins_of(r.centroid(), cmin, scale3);
        for (ax, bins) in bins.iter_mut().enumerate() {
            let bin = &mut bins[b[ax] & (BINS - 1)];
            bin.count += 1;
            bin.alone += r.alone as u32;
            bin.bounds = bin.bounds.union(r.bounds);
        }
    }
    let mut best = (f32::INFINITY, 0usize, 0usize); // cost, axis, split bin
    for (ax, bins) in bins.iter().enumerate() {
        if ext[ax] <= 0.0 {
            continue;
        }
        let mut right_area = [0f32; BINS];
        let mut right_count = [(0u32, 0u32); BINS];
        let (mut acc, mut cnt) = (Box3::EMPTY, (0u32, 0u32));
        for i in (1..BINS).rev() {
            acc = acc.union(bins[i].bounds);
            cnt = (cnt.0 + bins[i].count, cnt.1 + bins[i].alone);
            // Read below only where the box holds primitives.
            right_area[i] = acc.area();
            right_count[i] = cnt;
        }
        let (mut acc, mut cnt) = (Box3::EMPTY, (0u32, 0u32));
        for i in 0..BINS - 1 {
            acc = acc.union(bins[i].bounds);
            cnt = (cnt.0 + bins[i].count, cnt.1 + bins[i].alone);
            let right = right_count[i + 1];
            if cnt.0 == 0 || right.0 == 0 {
                continue;
            }
            let cost =
                blocks(cnt.0, cnt.1) * acc.area() + blocks(right.0, right.1) * right_area[i + 1];
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
    let (mid, centroids) = partition(refs, |c| bin_of(c[ax], cb.min[ax], scales[ax]) <= bin);
    if mid == 0 || mid == n {
        return split_at(refs, start, n / 2, bounds, at);
    }
    // Each side's box and lone primitives are those of its bins.
    let side = |bins: &[Bin], centroids: Box3| {
        let mut s = Span {
            bounds: Box3::EMPTY,
            centroids,
            alone: 0,
        };
        for b in bins {
            s.bounds = s.bounds.union(b.bounds);
            s.alone += b.alone;
        }
        s
    };
    let (l, r) = bins[ax].split_at(bin + 1);
    let spans = [side(l, centroids[0]), side(r, centroids[1])];
    children(refs, start, mid, bounds, at, spans)
}

/// The axis along which `ext` is longest (the last of equals).
fn longest_axis(ext: Vec3) -> usize {
    if ext.x > ext.y && ext.x > ext.z {
        0
    } else if ext.y > ext.z {
        1
    } else {
        2
    }
}

fn split_at(refs: &mut [PrimRef], start: usize, mid: usize, bounds: Aabb, at: Level) -> BuildNode {
    let axis = longest_axis(bounds.extent());
    refs.select_nth_unstable_by(mid, |a, b| {
        a.centroid()[axis].total_cmp(&b.centroid()[axis])
    });
    let spans = [span_of(&refs[..mid]), span_of(&refs[mid..])];
    children(refs, start, mid, bounds, at, spans)
}

fn children(
    refs: &mut [PrimRef],
    start: usize,
    mid: usize,
    bounds: Aabb,
    at: Level,
    [sl, sr]: [Span; 2],
) -> BuildNode {
    let next = Level {
        depth: at.depth + 1,
        ..at
    };
    let big = refs.len() > PARALLEL_THRESHOLD;
    let (l, r) = refs.split_at_mut(mid);
    let (a, b) = if big {
        rayon::join(
            || build_rec(l, start, next, sl),
            || build_rec(r, start + mid, next, sr),
        )
    } else {
        (
            build_rec(l, start, next, sl),
            build_rec(r, start + mid, next, sr),
        )
    };
    BuildNode::Interior {
        bounds,
        children: Box::new([a, b]),
    }
}

/// Moves the primitives whose centroid passes `left` to the front; returns
/// how many there are and the bounds of the two sides' centroids.
fn partition(refs: &mut [PrimRef], left: impl Fn(Vec3A) -> bool) -> (usize, [Box3; 2]) {
    let mut i = 0;
    let mut centroids = [Box3::EMPTY; 2];
    for j in 0..refs.len() {
        let c = refs[j].centroid();
        if left(c) {
            centroids[0] = centroids[0].grow(c);
            refs.swap(i, j);
            i += 1;
        } else {
            centroids[1] = centroids[1].grow(c);
        }
    }
    (i, centroids)
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::{Pcg32, Vec3};

    /// The three-axis SIMD binning gives every axis the scalar rule's bin,
    /// at the ends of the range and off it: centroids on the first and the
    /// last plane, just past the last, below the first, NaN, infinite, and
    /// an axis of zero extent (scale 0).
    #[test]
    fn three_axis_bins_are_the_scalar_bins() {
        let mut rng = Pcg32::new(3, 9);
        let odd = [
            0.0,
            -0.0,
            1.0,
            1.0 + f32::EPSILON,
            -1e-7,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            1e30,
        ];
        for round in 0..20_000 {
            let min = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 4.0 - 2.0;
            let ext = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 3.0;
            let mut scale = ext.map(|e| BINS as f32 / e);
            if round % 7 == 0 {
                scale.y = 0.0;
            }
            let c = Vec3::from_array(std::array::from_fn(|ax| {
                let u = rng.next_f32();
                if round % 3 == 0 {
                    // On a plane, past the ends, or not a number at all.
                    let k = (u * odd.len() as f32) as usize % odd.len();
                    min[ax] + odd[k] * ext[ax]
                } else {
                    min[ax] + u * ext[ax]
                }
            }));
            let got = bins_of(c.into(), min.into(), scale.into());
            for ax in 0..3 {
                assert_eq!(
                    got[ax] & (BINS - 1),
                    bin_of(c[ax], min[ax], scale[ax]),
                    "round {round}, axis {ax}: c {c}, min {min}, scale {scale}"
                );
            }
        }
    }

    /// Boxes with a NaN (a mesh vertex that is not a number) are left out,
    /// and every other box stays inside its node's: a ray through the
    /// middle of each finds it.
    #[test]
    fn boxes_with_a_nan_leave_the_others_whole() {
        let mut rng = Pcg32::new(8, 5);
        let boxes: Vec<Aabb> = (0..3000)
            .map(|i| {
                let c = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 10.0;
                let mut b = Aabb {
                    min: c,
                    max: c + Vec3::splat(0.05 + 0.1 * rng.next_f32()),
                };
                if i % 7 == 3 {
                    b.min[i % 3] = f32::NAN;
                }
                if i % 11 == 5 {
                    b.max[(i + 1) % 3] = f32::NAN;
                }
                b
            })
            .collect();
        let nan = |b: &Aabb| b.min.is_nan() || b.max.is_nan();
        for block in [1, 4] {
            let bvh = match block {
                1 => super::super::Bvh::build(&boxes),
                _ => super::super::Bvh::build_aligned(&boxes, block, |_| false),
            };
            let kept: Vec<u32> = bvh
                .order
                .iter()
                .copied()
                .filter(|&i| i != u32::MAX)
                .collect();
            assert_eq!(kept.len(), boxes.iter().filter(|b| !nan(b)).count());
            assert!(kept.iter().all(|&i| !nan(&boxes[i as usize])));
            for (i, b) in boxes.iter().enumerate().filter(|(_, b)| !nan(b)) {
                let c = b.center();
                let ray = crate::geometry::Ray::new(c - Vec3::X * 20.0, Vec3::X);
                let found = bvh.any(&ray, |slot, _, _| bvh.order[slot as usize] == i as u32);
                assert!(found, "box {i} lost (blocks of {block})");
            }
        }
    }

    /// The SIMD box's area is `Aabb::surface_area` bit for bit, so the
    /// SAH picks the splits it picked with scalar boxes.
    #[test]
    fn simd_box_area_is_the_aabb_area() {
        let mut rng = Pcg32::new(4, 2);
        for _ in 0..20_000 {
            let a = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 10.0 - 5.0;
            let mut e = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            if rng.next_f32() < 0.2 {
                e.x = 0.0; // flat
            }
            let b = Aabb { min: a, max: a + e };
            let simd = Box3 {
                lo: b.min.into(),
                hi: b.max.into(),
            };
            assert_eq!(simd.area().to_bits(), b.surface_area().to_bits(), "{b:?}");
            let u = simd.union(Box3::EMPTY).union(simd);
            assert_eq!(u.aabb(), b.union(&Aabb::EMPTY));
        }
    }
}
