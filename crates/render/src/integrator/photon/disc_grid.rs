//! The radiance photons' nearest lookup in progressive iterations, on a
//! hashed uniform grid.
//!
//! There a point may be read only from within its own disc (a ball of
//! squared radius `r2[i]`, the iteration's global radius at the point), so
//! the points a query at `q` can return are those whose balls hold `q`. The
//! grid lists, for every cell, each point whose ball (padded against
//! rounding) meets the cell, nearest the cell's centre first; a query scans
//! its cell's list until the candidates are too far from the centre to
//! beat its best, and keeps the nearest point that passes the distance and
//! ball tests and the caller's own (the normal's). Every point that could
//! be returned is in the list, so the answer is the kd-tree search's (of
//! points at exactly the same distance, the lowest index), with no descent
//! and no backtracking: a gather-ray hit reads one contiguous run of
//! candidates. A grid built for some discs serves any smaller ones
//! (`radiance.rs` keeps one until the discs halve in area). The caustic
//! radius field uses it too, every sample a ball of the field's largest
//! radius (`RadiusField::with_grid`).

use super::map::dist2;
use lumis_math::Vec3;

/// A cell's side over the balls' median radius. Measured on the default
/// scene (the lookup's share of single-thread profiles, 2026-12-07, while
/// this grid was being written): 1.5 and 2 level, 1 about a quarter more,
/// 2.5 no better; at 0.5 a point is listed in about 120 cells.
const CELL_PER_RADIUS: f32 = 1.5;

/// Cells a point's ball's bounding box may cover, on average, before the
/// cells grow (42-62 on the default scene, the caustic set and the caustic
/// glass at 1.5 radii a cell; a few balls far larger than the median would
/// otherwise list each point in thousands of cells).
const MAX_PER_POINT: f64 = 128.0;

/// Bits of a cell's key per axis.
const AXIS_BITS: u32 = 21;

/// An unused slot's key.
const EMPTY: u64 = u64::MAX;

const EMPTY_SLOT: Slot = Slot {
    key: EMPTY,
    start: 0,
    end: 0,
};

/// A cell's key and its run of candidates: one cache line's quarter, so
/// a lookup's first read brings both.
#[derive(Clone, Copy, Debug)]
struct Slot {
    key: u64,
    start: u32,
    end: u32,
}

#[derive(Debug, Default)]
pub(crate) struct DiscGrid {
    lo: [f32; 3],
    h: f32,
    inv_h: f32,
    dims: [i64; 3],
    /// The cells that list candidates, hashed (linear probing, at most
    /// half full; the length a power of two). Memory follows the
    /// candidates, not the cells of the box, so that a long render's small
    /// discs do not grow it.
    slots: Vec<Slot>,
    /// Slots taken.
    cells: usize,
    /// Position of each candidate and, in `[3]`, the bits of its point's
    /// index; cell by cell, each cell's nearest its centre first.
    cand: Vec<[f32; 4]>,
}

impl DiscGrid {
    /// A grid over the balls of squared radii `r0_2 scale2` around `pos`,
    /// or None when a radius is not finite. It answers queries for any
    /// scale up to `scale2` (smaller balls meet fewer cells). Its cells
    /// grow until at most `max_cells` list candidates.
    pub(crate) fn build(
        pos: &[Vec3],
        r0_2: &[f32],
        scale2: f32,
        max_cells: usize,
    ) -> Option<DiscGrid> {
        assert_eq!(pos.len(), r0_2.len(), "one radius per point");
        if pos.is_empty() {
            return Some(DiscGrid::default());
        }
        let r2: Vec<f32> = r0_2.iter().map(|&r| r * scale2).collect();
        if r2.iter().any(|r| !r.is_finite() || *r < 0.0) {
            return None;
        }
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        let mut scale = 0.0f32;
        for (p, r) in pos.iter().zip(&r2) {
            let r = r.sqrt();
            for (d, c) in p.to_array().into_iter().enumerate() {
                lo[d] = lo[d].min(c - r);
                hi[d] = hi[d].max(c + r);
                scale = scale.max(c.abs() + r);
            }
        }
        if !scale.is_finite() {
            return None;
        }
        // Rounding in the cell of a query and in a ball's cells stays far
        // below this: a ball padded by it meets every cell a query in the
        // ball can fall in.
        let pad = scale * 1e-5;
        let lo = [lo[0] - pad, lo[1] - pad, lo[2] - pad];
        let hi = [hi[0] + pad, hi[1] + pad, hi[2] + pad];
        let radii: Vec<f32> = r2.iter().map(|r| r.sqrt() + pad).collect();
        let extent = (0..3).map(|d| hi[d] - lo[d]).fold(0.0f32, f32::max);
        let mut h = (CELL_PER_RADIUS * median(&radii))
            .max(extent / (1u32 << (AXIS_BITS - 1)) as f32)
            .max(f32::MIN_POSITIVE);
        while estimate(&radii, h) > MAX_PER_POINT * pos.len() as f64 {
            h *= 1.25;
        }
        if estimate(&radii, h) > (u32::MAX / 2) as f64 {
            return None;
        }
        // Cells grown until at most `max_cells` list candidates: count each
        // cell's candidates in the hash table, then write every cell's run
        // in place and order it (no list of (cell, point) pairs beside the
        // candidates, which doubled the build's peak memory).
        let mut g = loop {
            let inv_h = 1.0 / h;
            let mut g = DiscGrid {
                lo,
                h,
                inv_h,
                dims: [0, 1, 2].map(|d| ((hi[d] - lo[d]) * inv_h).floor() as i64 + 1),
                slots: vec![EMPTY_SLOT; 1024],
                cells: 0,
                cand: Vec::new(),
            };
            let mut too_many = false;
            g.for_each_cell(pos, &radii, |g, c, _| {
                if too_many {
                    return;
                }
                let s = g.insert(key(c));
                g.slots[s].end += 1;
                too_many = g.cells > max_cells;
            });
            if !too_many {
                break g;
            }
            h *= 1.25;
        };
        // Runs in slot order: `start` is the run's start, `end` first its
        // count and then, while filling, its cursor.
        let mut total = 0u32;
        for slot in g.slots.iter_mut().filter(|s| s.key != EMPTY) {
            slot.start = total;
            total += slot.end;
            slot.end = slot.start;
        }
        let mut cand = vec![[0.0f32; 4]; total as usize];
        g.for_each_cell(pos, &radii, |g, c, i| {
            let s = g.probe(key(c));
            let p = pos[i];
            cand[g.slots[s].end as usize] = [p.x, p.y, p.z, f32::from_bits(i as u32)];
            g.slots[s].end += 1;
        });
        for slot in g.slots.iter().filter(|s| s.key != EMPTY) {
            let centre = g.centre(cell_of(slot.key));
            let run = &mut cand[slot.start as usize..slot.end as usize];
            run.sort_unstable_by(|a, b| {
                (dist2(a, centre).total_cmp(&dist2(b, centre)))
                    .then(a[3].to_bits().cmp(&b[3].to_bits()))
            });
        }
        g.cand = cand;
        Some(g)
    }

    /// The slot of `key`, taken if new; the table doubles before it is
    /// half full.
    fn insert(&mut self, key: u64) -> usize {
        let s = self.probe(key);
        if self.slots[s].key == key {
            return s;
        }
        if 2 * (self.cells + 1) > self.slots.len() {
            let grown = vec![EMPTY_SLOT; 2 * self.slots.len()];
            let old = std::mem::replace(&mut self.slots, grown);
            for slot in old.into_iter().filter(|s| s.key != EMPTY) {
                let t = self.probe(slot.key);
                self.slots[t] = slot;
            }
            return self.insert(key);
        }
        self.slots[s].key = key;
        self.cells += 1;
        s
    }

    fn hash(&self, key: u64) -> usize {
        (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 24) as usize & (self.slots.len() - 1)
    }

    /// The slot holding `key`, or the empty one where it would go.
    #[inline]
    fn probe(&self, key: u64) -> usize {
        let mask = self.slots.len() - 1;
        let mut s = self.hash(key);
        while self.slots[s].key != key && self.slots[s].key != EMPTY {
            s = (s + 1) & mask;
        }
        s
    }

    fn centre(&self, c: [i64; 3]) -> [f32; 3] {
        [0, 1, 2].map(|d| self.lo[d] + (c[d] as f32 + 0.5) * self.h)
    }

    /// `f(grid, cell, point)` for every cell each point's ball meets.
    fn for_each_cell(
        &mut self,
        pos: &[Vec3],
        radii: &[f32],
        mut f: impl FnMut(&mut DiscGrid, [i64; 3], usize),
    ) {
        let (lo, h, inv_h, dims) = (self.lo, self.h, self.inv_h, self.dims);
        for (i, (p, &r)) in pos.iter().zip(radii).enumerate() {
            let p = p.to_array();
            let cell =
                |c: f32, d: usize| (((c - lo[d]) * inv_h).floor() as i64).clamp(0, dims[d] - 1);
            let c0 = [0, 1, 2].map(|d| cell(p[d] - r, d));
            let c1 = [0, 1, 2].map(|d| cell(p[d] + r, d));
            for z in c0[2]..=c1[2] {
                for y in c0[1]..=c1[1] {
                    for x in c0[0]..=c1[0] {
                        let c = [x, y, z];
                        let mut d2 = 0.0f32;
                        for d in 0..3 {
                            let a = lo[d] + c[d] as f32 * h;
                            let off = (a - p[d]).max(p[d] - (a + h)).max(0.0);
                            d2 += off * off;
                        }
                        if d2 <= r * r {
                            f(self, c, i);
                        }
                    }
                }
            }
        }
    }

    /// The nearest point to `q` at squared distance `d2 < bound` for which
    /// `accept(point, d2)` holds, or None, where `accept` refuses a point
    /// outside its own ball (`d2 > r0_2 scale2`, `scale2` at most the
    /// build's). Of points at the same distance, the lowest index.
    ///
    /// The scan stops at the first candidate farther from the cell's centre
    /// than `q` is plus the best distance so far: it and every later one
    /// are farther from `q` than that (the triangle inequality; a relative
    /// margin of 1e-4 covers rounding).
    #[inline]
    pub(crate) fn nearest(
        &self,
        q: Vec3,
        mut bound: f32,
        mut accept: impl FnMut(u32, f32) -> bool,
    ) -> Option<u32> {
        if self.cand.is_empty() {
            return None;
        }
        let q = q.to_array();
        let mut c = [0i64; 3];
        for d in 0..3 {
            let f = ((q[d] - self.lo[d]) * self.inv_h).floor();
            // Also refuses NaN: no ball reaches outside the grid.
            if !(f >= 0.0 && f < self.dims[d] as f32) {
                return None;
            }
            c[d] = f as i64;
        }
        let slot = self.slots[self.probe(key(c))];
        if slot.key == EMPTY {
            return None;
        }
        let (a, b) = (slot.start as usize, slot.end as usize);
        let centre = self.centre(c);
        let dq = dist2(&[q[0], q[1], q[2], 0.0], centre).sqrt();
        let reach = |bound: f32| ((dq + bound.sqrt()) * (1.0 + 1e-4)).powi(2);
        let mut stop = reach(bound);
        let mut best: Option<u32> = None;
        for pt in &self.cand[a..b] {
            if dist2(pt, centre) > stop {
                break;
            }
            let d2 = dist2(pt, q);
            let i = pt[3].to_bits();
            let nearer = d2 < bound || (d2 == bound && best.is_some_and(|b| i < b));
            if nearer && accept(i, d2) {
                bound = d2;
                best = Some(i);
                stop = reach(bound);
            }
        }
        best
    }

    /// Cells that list candidates.
    pub(crate) fn cells(&self) -> usize {
        self.cells
    }

    pub(crate) fn memory_bytes(&self) -> usize {
        self.slots.capacity() * std::mem::size_of::<Slot>() + self.cand.capacity() * 16
    }
}

fn key(c: [i64; 3]) -> u64 {
    c[0] as u64 | (c[1] as u64) << AXIS_BITS | (c[2] as u64) << (2 * AXIS_BITS)
}

/// The cell of a key.
fn cell_of(key: u64) -> [i64; 3] {
    let mask = (1u64 << AXIS_BITS) - 1;
    [0, 1, 2].map(|d| ((key >> (d as u32 * AXIS_BITS)) & mask) as i64)
}

fn median(v: &[f32]) -> f32 {
    let mut v = v.to_vec();
    let mid = v.len() / 2;
    *v.select_nth_unstable_by(mid, f32::total_cmp).1
}

/// Cells the balls' bounding boxes cover, at most, with cells of side `h`.
fn estimate(radii: &[f32], h: f32) -> f64 {
    radii
        .iter()
        .map(|&r| (2.0 * r as f64 / h as f64 + 2.0).powi(3))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::Pcg32;

    /// The nearest accepted point inside its ball, by brute force.
    fn brute(pos: &[Vec3], r2: &[f32], s: f32, q: Vec3, bound: f32, ok: &[bool]) -> Option<u32> {
        let mut best: Option<(f32, u32)> = None;
        for (i, p) in pos.iter().enumerate() {
            let d2 = (*p - q).length_squared();
            if d2 < bound && d2 <= r2[i] * s && ok[i] && best.is_none_or(|(b, _)| d2 < b) {
                best = Some((d2, i as u32));
            }
        }
        best.map(|b| b.1)
    }

    #[test]
    fn finds_what_brute_force_finds() {
        let mut rng = Pcg32::new(7, 0);
        let mut u = || rng.next_f32();
        for case in 0..4 {
            // Points on a plane, in clusters, in a box; radii from
            // tiny to a fifth of the scene, with a few large ones.
            let n = 3000;
            let pos: Vec<Vec3> = (0..n)
                .map(|i| match case {
                    0 => Vec3::new(u() * 4.0 - 2.0, 0.5, u() * 4.0 - 2.0),
                    1 => Vec3::new((i % 5) as f32 + 0.05 * u(), 0.05 * u(), 3.0 + 0.05 * u()),
                    _ => Vec3::new(u() * 2.0 + 100.0, u() * 2.0, u() * 2.0),
                })
                .collect();
            let r2: Vec<f32> = (0..n)
                .map(|i| {
                    let r = if i % 97 == 0 {
                        0.8 * u()
                    } else {
                        0.1 * u() * u()
                    };
                    if case == 3 && i % 2 == 0 {
                        0.0
                    } else {
                        r * r
                    }
                })
                .collect();
            let ok: Vec<bool> = (0..n).map(|_| u() < 0.7).collect();
            // Built for balls 1.5x the queries' (or as large) in area.
            let s = if case % 2 == 0 { 0.6 } else { 1.0 };
            let g = DiscGrid::build(&pos, &r2, 1.0, usize::MAX).expect("finite radii");
            let (mut found, mut queries) = (0, 0);
            for k in 0..20000 {
                // On points, beside them, at their balls' edges, anywhere.
                let p = pos[k % n];
                let q = match k % 4 {
                    0 => p,
                    1 => p + Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * 0.1,
                    2 => p + Vec3::new(1.0, 0.0, 0.0) * (r2[k % n] * s).sqrt(),
                    _ => Vec3::new(u() * 6.0 - 3.0, u() * 1.0, u() * 6.0 - 3.0) + p * 0.5,
                };
                let bound = if k % 3 == 0 { 0.01 } else { f32::INFINITY };
                let want = brute(&pos, &r2, s, q, bound, &ok);
                let got = g.nearest(q, bound, |i, d2| d2 <= r2[i as usize] * s && ok[i as usize]);
                assert_eq!(got, want, "case {case}, query {k} at {q:?}");
                found += want.is_some() as usize;
                queries += 1;
            }
            assert!(
                found > queries / 10,
                "case {case}: {found} of {queries} found"
            );
        }
    }

    #[test]
    fn a_few_large_balls_do_not_list_every_point_in_many_cells() {
        // One ball in 50 twenty times the others' radius.
        let mut rng = Pcg32::new(9, 0);
        let n = 5000;
        let pos: Vec<Vec3> = (0..n)
            .map(|_| Vec3::new(rng.next_f32(), 0.0, rng.next_f32()))
            .collect();
        let r2: Vec<f32> = (0..n)
            .map(|i| if i % 50 == 0 { 0.4f32 } else { 0.02 }.powi(2))
            .collect();
        let g = DiscGrid::build(&pos, &r2, 1.0, usize::MAX).expect("finite radii");
        // 41 a point; 242 with cells sized by the median radius alone.
        assert!(
            g.cand.len() <= 100 * n,
            "{} candidates for {n} points",
            g.cand.len()
        );
        let ok = vec![true; n];
        for k in 0..5000 {
            let q = Vec3::new(rng.next_f32(), 0.01 * rng.next_f32(), rng.next_f32());
            let want = brute(&pos, &r2, 1.0, q, f32::INFINITY, &ok);
            let got = g.nearest(q, f32::INFINITY, |i, d2| d2 <= r2[i as usize]);
            assert_eq!(got, want, "query {k} at {q:?}");
        }
    }

    #[test]
    fn refuses_radii_that_are_not_finite() {
        let pos = [Vec3::ZERO, Vec3::new(1.0, 0.0, 0.0)];
        assert!(DiscGrid::build(&pos, &[1.0, f32::INFINITY], 1.0, 10).is_none());
        assert!(DiscGrid::build(&pos, &[1.0, f32::NAN], 1.0, 10).is_none());
        let g = DiscGrid::build(&[], &[], 1.0, 10).expect("empty");
        assert_eq!(g.nearest(Vec3::ZERO, f32::INFINITY, |_, _| true), None);
    }
}
