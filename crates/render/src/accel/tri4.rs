//! Leaf primitives in packets of four, laid out for one ray against four
//! triangles at once.
//!
//! The BVH is built with leaves aligned to four slots
//! ([`Bvh::build_aligned`](super::Bvh::build_aligned)), so a leaf is one or
//! two whole packets. A packet holds its triangles' vertices as SIMD lanes;
//! the watertight test's shear and edge functions run on the four lanes
//! together, and only the lanes whose edge functions say "inside" (usually
//! none, at most one or two) finish in scalar code, in
//! [`watertight_tail`], with the current `tmax`, in slot order. Each lane's
//! arithmetic is the scalar test's, in the same order, and lanes whose
//! edge functions are zero go through the scalar test whole (its
//! double-precision retry), so hits are bit for bit those of
//! [`intersect_triangle`] slot by slot. Analytic primitives keep their lanes
//! and are tested by the caller's function in the same slot order.

use super::mem::huge_vec;
use crate::geometry::triangle::{intersect_triangle, watertight_tail, RayShear};
use crate::geometry::Ray;
use lumis_math::{Vec2, Vec3, Vec4};

/// A slot of the aligned BVH's `order` that holds no primitive.
pub const PADDING: u32 = u32::MAX;

/// Four leaf slots (176 bytes).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct TriPacket {
    /// `v[vertex][axis]`, lane `i` for slot `i`.
    v: [[Vec4; 3]; 3],
    /// The caller's id of each lane's primitive (`PADDING` for none).
    id: [u32; 4],
    /// Bit `i`: lane `i` is a triangle (else analytic, or padding).
    tris: u32,
}

const EMPTY: TriPacket = TriPacket {
    v: [[Vec4::ZERO; 3]; 3],
    id: [PADDING; 4],
    tris: 0,
};

impl TriPacket {
    fn lane(&self, l: usize) -> [Vec3; 3] {
        std::array::from_fn(|j| Vec3::new(self.v[j][0][l], self.v[j][1][l], self.v[j][2][l]))
    }
}

/// The per-ray constants of the packet test.
pub struct PacketRay {
    sh: RayShear,
    /// The origin's sheared-frame coordinates `kx, ky, kz`, splatted.
    o: [Vec4; 3],
    sx: Vec4,
    sy: Vec4,
}

impl PacketRay {
    #[inline(always)]
    pub fn new(ray: &Ray) -> PacketRay {
        let sh = RayShear::new(ray.d);
        PacketRay {
            o: [sh.kx, sh.ky, sh.kz].map(|k| Vec4::splat(ray.o[k])),
            sx: Vec4::splat(sh.sx),
            sy: Vec4::splat(sh.sy),
            sh,
        }
    }
}

/// The edge functions of a packet's four lanes and the vertices' `z` in the
/// ray's frame (before scaling), as the scalar test computes them.
struct Edges {
    u: [f32; 4],
    v: [f32; 4],
    w: [f32; 4],
    z: [[f32; 4]; 3],
    /// Lanes inside (or on) all three edges whose distance the scalar end
    /// would not refuse against the `tmax` given (it only shrinks), or
    /// with a zero edge function.
    candidates: u32,
    /// Lanes with a zero edge function: the scalar test redoes them.
    zero: u32,
}

#[inline(always)]
fn edges(p: &TriPacket, r: &PacketRay, tmax: f32) -> Edges {
    let (kx, ky, kz) = (r.sh.kx, r.sh.ky, r.sh.kz);
    let mut x = [Vec4::ZERO; 3];
    let mut y = [Vec4::ZERO; 3];
    let mut z = [Vec4::ZERO; 3];
    for j in 0..3 {
        let az = p.v[j][kz] - r.o[2];
        x[j] = (p.v[j][kx] - r.o[0]) - r.sx * az;
        y[j] = (p.v[j][ky] - r.o[1]) - r.sy * az;
        z[j] = az;
    }
    // a = vertex 0, b = vertex 1, c = vertex 2, as in `intersect_triangle`.
    let u = x[2] * y[1] - y[2] * x[1];
    let v = x[0] * y[2] - y[0] * x[2];
    let w = x[1] * y[0] - y[1] * x[0];
    let zero4 = Vec4::ZERO;
    let zero = (u.cmpeq(zero4) | v.cmpeq(zero4) | w.cmpeq(zero4)).bitmask();
    let neg = (u.cmplt(zero4) | v.cmplt(zero4) | w.cmplt(zero4)).bitmask();
    let pos = (u.cmpgt(zero4) | v.cmpgt(zero4) | w.cmpgt(zero4)).bitmask();
    // The distance tests of `watertight_tail`, the same arithmetic lane by
    // lane: a lane they refuse (the line meets the triangle behind the
    // origin or beyond `tmax`, the usual case for one of the two walls a
    // ray's line crosses in a room) skips the scalar end.
    let sz = Vec4::splat(r.sh.sz);
    let det = u + v + w;
    let tt = u * (sz * z[0]) + v * (sz * z[1]) + w * (sz * z[2]);
    let td = Vec4::splat(tmax) * det;
    let (below, above) = (det.cmplt(zero4), det.cmpgt(zero4));
    let refused = det.cmpeq(zero4)
        | (below & (tt.cmpge(zero4) | tt.cmplt(td)))
        | (above & (tt.cmple(zero4) | tt.cmpgt(td)));
    Edges {
        u: u.to_array(),
        v: v.to_array(),
        w: w.to_array(),
        z: z.map(|z| z.to_array()),
        candidates: (!(neg & pos) & !refused.bitmask()) | zero,
        zero,
    }
}

/// The packets of an aligned BVH's leaves.
#[derive(Clone, Debug, Default)]
pub struct TriPackets {
    packets: Vec<TriPacket>,
}

impl TriPackets {
    /// From the aligned BVH's `order` (a multiple of four long): `slot(i)`
    /// gives the caller's id of primitive `i` and its vertices if it is a
    /// triangle; it is called for the primitives in `order`'s order.
    pub fn build(
        order: &[u32],
        mut slot: impl FnMut(u32) -> (u32, Option<[Vec3; 3]>),
    ) -> TriPackets {
        debug_assert!(order.len().is_multiple_of(4));
        let mut packets = huge_vec(order.len() / 4);
        packets.extend(order.chunks(4).map(|lanes| {
            let mut p = EMPTY;
            for (l, &i) in lanes.iter().enumerate().filter(|(_, &i)| i != PADDING) {
                let (id, tri) = slot(i);
                p.id[l] = id;
                if let Some(v) = tri {
                    p.tris |= 1 << l;
                    for (j, vj) in v.iter().enumerate() {
                        for a in 0..3 {
                            p.v[j][a][l] = vj[a];
                        }
                    }
                }
            }
            p
        }));
        TriPackets { packets }
    }

    pub fn memory_bytes(&self) -> usize {
        self.packets.len() * std::mem::size_of::<TriPacket>()
    }

    /// The packet holding slot `first` and the mask of its lanes from
    /// `first` up to (not including) slot `end`.
    #[inline(always)]
    fn lanes(&self, first: u32, end: u32) -> (&TriPacket, u32) {
        let o = first % 4;
        let n = (end - first).min(4 - o);
        (&self.packets[first as usize / 4], ((1u32 << n) - 1) << o)
    }

    /// Where leaf slot `start`'s packet is, for a prefetch (past the end
    /// for a slot that is not there: the address is never read).
    #[inline(always)]
    pub fn address(&self, start: u32) -> *const u8 {
        self.packets.as_ptr().wrapping_add(start as usize / 4) as *const u8
    }

    /// Closest hit in `(0, tmax)` among leaf slots `start..start + count`
    /// (a leaf of several slots starts a packet; one of one slot may share
    /// it): `(t, id, barycentrics)`. `analytic(id, ray, tmax)` tests the
    /// lanes that are not triangles.
    #[inline(always)]
    pub fn closest(
        &self,
        (start, count): (u32, u32),
        ray: &Ray,
        pr: &PacketRay,
        mut tmax: f32,
        mut analytic: impl FnMut(u32, &Ray, f32) -> Option<f32>,
    ) -> Option<(f32, u32, Vec2)> {
        let mut best = None;
        let end = start + count;
        let mut first = start;
        while first < end {
            let (p, lanes) = self.lanes(first, end);
            first += lanes.count_ones();
            let (tris, others) = (p.tris & lanes, !p.tris & lanes);
            let e = (tris != 0).then(|| edges(p, pr, tmax));
            let mut todo = others | e.as_ref().map_or(0, |e| e.candidates & tris);
            while todo != 0 {
                let l = todo.trailing_zeros() as usize;
                todo &= todo - 1;
                let hit = match &e {
                    Some(e) if tris >> l & 1 == 1 => lane_hit(p, e, l, ray, pr, tmax),
                    _ => analytic(p.id[l], ray, tmax).map(|t| (t, 0.0, 0.0)),
                };
                if let Some((t, b1, b2)) = hit {
                    tmax = t;
                    best = Some((t, p.id[l], Vec2::new(b1, b2)));
                }
            }
        }
        best
    }

    /// Whether any of leaf slots `start..start + count` blocks the ray in
    /// `(0, tmax)`.
    #[inline(always)]
    pub fn any(
        &self,
        (start, count): (u32, u32),
        ray: &Ray,
        pr: &PacketRay,
        tmax: f32,
        mut analytic: impl FnMut(u32, &Ray, f32) -> bool,
    ) -> bool {
        let end = start + count;
        let mut first = start;
        while first < end {
            let (p, lanes) = self.lanes(first, end);
            first += lanes.count_ones();
            let (tris, others) = (p.tris & lanes, !p.tris & lanes);
            if tris != 0 {
                let e = edges(p, pr, tmax);
                let mut todo = e.candidates & tris;
                while todo != 0 {
                    let l = todo.trailing_zeros() as usize;
                    todo &= todo - 1;
                    if lane_hit(p, &e, l, ray, pr, tmax).is_some() {
                        return true;
                    }
                }
            }
            let mut todo = others;
            while todo != 0 {
                let l = todo.trailing_zeros() as usize;
                todo &= todo - 1;
                if analytic(p.id[l], ray, tmax) {
                    return true;
                }
            }
        }
        false
    }
}

/// Finishes lane `l`'s test in scalar code with the current `tmax`.
#[inline(always)]
fn lane_hit(
    p: &TriPacket,
    e: &Edges,
    l: usize,
    ray: &Ray,
    pr: &PacketRay,
    tmax: f32,
) -> Option<(f32, f32, f32)> {
    if e.zero >> l & 1 == 1 {
        return intersect_triangle(ray, &pr.sh, &p.lane(l), tmax);
    }
    let sz = pr.sh.sz;
    let z = [sz * e.z[0][l], sz * e.z[1][l], sz * e.z[2][l]];
    watertight_tail(e.u[l], e.v[l], e.w[l], z, tmax)
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::Pcg32;

    /// Random rays against random leaves of triangles: the packet test
    /// returns the scalar test's hit, slot by slot, bit for bit, including
    /// rays through shared vertices and edges (zero edge functions).
    #[test]
    fn packets_match_the_scalar_test_bit_for_bit() {
        let mut rng = Pcg32::new(7, 1);
        let grid = |rng: &mut Pcg32| {
            Vec3::new(
                (rng.next_f32() * 4.0).floor() * 0.25,
                (rng.next_f32() * 4.0).floor() * 0.25,
                (rng.next_f32() * 4.0).floor() * 0.25,
            )
        };
        let mut hits = 0;
        for round in 0..4000 {
            let count: usize = 1 + round % 7;
            // Vertices on a coarse grid, so edges and vertices are shared and
            // rays from grid points hit them exactly.
            let tris: Vec<[Vec3; 3]> = (0..count)
                .map(|_| [grid(&mut rng), grid(&mut rng), grid(&mut rng)])
                .collect();
            let order: Vec<u32> = (0..count as u32)
                .chain(std::iter::repeat(PADDING))
                .take(count.next_multiple_of(4))
                .collect();
            let packets = TriPackets::build(&order, |i| (i, Some(tris[i as usize])));
            let o = grid(&mut rng) * 2.0 - Vec3::splat(0.5);
            let d = if round % 3 == 0 {
                Vec3::new(0.0, 0.0, if round % 2 == 0 { 1.0 } else { -1.0 })
            } else {
                (grid(&mut rng) - o + Vec3::splat(1e-3 * rng.next_f32())).normalize_or_zero()
            };
            if d == Vec3::ZERO {
                continue;
            }
            let ray = Ray::new(o, d);
            let tmax = if round % 5 == 0 { 1.0 } else { f32::INFINITY };
            let sh = RayShear::new(d);
            let mut want = None;
            let mut t_cur = tmax;
            for (i, v) in tris.iter().enumerate() {
                if let Some((t, b1, b2)) = intersect_triangle(&ray, &sh, v, t_cur) {
                    t_cur = t;
                    want = Some((t.to_bits(), i as u32, b1.to_bits(), b2.to_bits()));
                }
            }
            let pr = PacketRay::new(&ray);
            let got = packets
                .closest((0, count as u32), &ray, &pr, tmax, |_, _, _| None)
                .map(|(t, id, b)| (t.to_bits(), id, b.x.to_bits(), b.y.to_bits()));
            assert_eq!(got, want, "round {round}");
            let any = packets.any((0, count as u32), &ray, &pr, tmax, |_, _, _| false);
            assert_eq!(any, want.is_some(), "round {round}");
            hits += want.is_some() as u32;
            // Leaves of one slot anywhere in a packet, and of the slots
            // from any lane on: each sees its own triangles only.
            for first in 0..count {
                for n in [1, count - first] {
                    let leaf = (first as u32, n as u32);
                    let (mut want, mut t_cur) = (None, tmax);
                    for (i, v) in tris.iter().enumerate().skip(first).take(n) {
                        if let Some((t, b1, b2)) = intersect_triangle(&ray, &sh, v, t_cur) {
                            t_cur = t;
                            want = Some((t.to_bits(), i as u32, b1.to_bits(), b2.to_bits()));
                        }
                    }
                    let got = packets
                        .closest(leaf, &ray, &pr, tmax, |_, _, _| None)
                        .map(|(t, id, b)| (t.to_bits(), id, b.x.to_bits(), b.y.to_bits()));
                    assert_eq!(got, want, "round {round}, leaf {leaf:?}");
                    let any = packets.any(leaf, &ray, &pr, tmax, |_, _, _| false);
                    assert_eq!(any, want.is_some(), "round {round}, leaf {leaf:?}");
                }
            }
        }
        assert!(hits > 400, "too few hits to test anything: {hits}");
    }
}
