//! Caustic photons traced in the order of where they first meet a
//! specular shape, so that photons traced one after another read the same
//! part of the BVH and the same triangles (a caustic path stays coherent
//! through smooth glass: neighbouring rays take neighbouring paths). On a
//! tessellated scene whose BVH does not fit in the cache, photons traced
//! in their own order wait on memory at almost every node.
//!
//! A batch of photons is emitted first, only to find each one's first ray
//! and its key ([`Targets::order_key`]); the photons that are traced at all
//! are then sorted by key and traced again from the start of their streams
//! (emitting a photon twice costs a few percent of tracing it), and what
//! they store is put back in photon order, so the maps are exactly those
//! of tracing the photons one by one.

use super::aim::Targets;
use super::trace::{Job, Traced};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Geometry (acceleration structures and shapes) above which sorting pays:
/// about a core's L2 cache. Where the geometry fits, the photons' second
/// emission is not won back (`tracing` of 5M caustic photons, medians of 8
/// alternating runs: the default scene's 2 KiB 1.06x the time, a 3.3 MiB
/// glass box 0.97x, the 13 MiB one 0.93x, the 8M-triangle one 0.83x).
pub const SORT_ABOVE_BYTES: usize = 2 << 20;
/// Photons emitted per batch: the more photons are sorted together, the
/// closer neighbours are (the glass box traces about 8% of its caustic
/// photons; with batches of 2^18 a run of 5M took 1.1x the time of
/// one sort of all). The keys take 8 bytes per traced photon, at most
/// 32 MiB, where the map takes 36 per photon it stores.
const BATCH: u64 = 1 << 22;
/// Photons emitted per parallel task while finding keys.
const KEY_CHUNK: u64 = 4096;
/// Sorted photons per parallel task while tracing.
const TRACE_CHUNK: usize = 256;

/// [`super::trace::trace_photons`] for caustic photons whose first ray
/// `starts` bounds: `None` once `cancel` is set.
pub(super) fn trace_by_first_hit(
    job: &Job,
    starts: &Targets,
    cancel: &AtomicBool,
) -> Option<Traced> {
    let mut all = Traced::default();
    let mut first = 0;
    while first < job.n_emit {
        let end = (first + BATCH).min(job.n_emit);
        let keys = sorted_keys(job, starts, first..end, cancel);
        let parts: Vec<(Traced, Vec<Span>)> = keys
            .par_chunks(TRACE_CHUNK)
            .map(|part| {
                let mut out = Traced::default();
                let mut spans = Vec::with_capacity(part.len());
                if cancel.load(Ordering::Relaxed) {
                    return (out, spans);
                }
                let mut sampler = job.sampler();
                let mut rays = 0u64;
                for &(_, offset) in part {
                    job.trace(first + offset as u64, &mut sampler, &mut out, &mut rays);
                    spans.push(Span::after(offset, &out));
                }
                job.count(rays);
                (out, spans)
            })
            .collect();
        if cancel.load(Ordering::Relaxed) {
            return None;
        }
        append_in_photon_order(&mut all, &parts);
        first = end;
    }
    Some(all)
}

/// `(key, photon - range.start)` of the photons in `range` that are
/// traced, sorted.
fn sorted_keys(
    job: &Job,
    starts: &Targets,
    range: std::ops::Range<u64>,
    cancel: &AtomicBool,
) -> Vec<(u32, u32)> {
    let chunks = (range.end - range.start).div_ceil(KEY_CHUNK);
    let mut keys: Vec<(u32, u32)> = (0..chunks)
        .into_par_iter()
        .flat_map_iter(|c| {
            let mut keys = Vec::new();
            if cancel.load(Ordering::Relaxed) {
                return keys;
            }
            let mut sampler = job.sampler();
            let from = range.start + c * KEY_CHUNK;
            for i in from..(from + KEY_CHUNK).min(range.end) {
                if let Some(ray) = job.first_ray(i, &mut sampler) {
                    let offset = (i - range.start) as u32;
                    keys.push((starts.order_key(&ray).unwrap_or(u32::MAX), offset));
                }
            }
            keys
        })
        .collect();
    // Keys are unique with the photon's index: the order is deterministic.
    keys.par_sort_unstable();
    keys
}

/// Where one traced photon's results end in its task's [`Traced`].
#[derive(Clone, Copy)]
struct Span {
    /// The photon's offset in its batch.
    offset: u32,
    photons: u32,
    volume: u32,
    connections: u32,
}

impl Span {
    /// A task's counts fit in `u32`: 2^32 photons would take 96 GiB.
    fn after(offset: u32, out: &Traced) -> Span {
        Span {
            offset,
            photons: out.photons.len() as u32,
            volume: out.volume.len() as u32,
            connections: out.connections.len() as u32,
        }
    }

    fn ranges(&self, end: &Span) -> [std::ops::Range<usize>; 3] {
        let r = |a: u32, b: u32| a as usize..b as usize;
        [
            r(self.photons, end.photons),
            r(self.volume, end.volume),
            r(self.connections, end.connections),
        ]
    }
}

/// Appends the tasks' results to `all` in photon order.
fn append_in_photon_order(all: &mut Traced, parts: &[(Traced, Vec<Span>)]) {
    let total = |f: fn(&Traced) -> usize| parts.iter().map(|(t, _)| f(t)).sum::<usize>();
    all.photons.reserve_exact(total(|t| t.photons.len()));
    all.normals.reserve_exact(total(|t| t.normals.len()));
    all.volume.reserve_exact(total(|t| t.volume.len()));
    all.connections
        .reserve_exact(total(|t| t.connections.len()));
    // (photon's offset, task, index of its span in the task)
    let mut at: Vec<(u32, u32, u32)> = parts
        .iter()
        .enumerate()
        .flat_map(|(t, (_, spans))| {
            spans
                .iter()
                .enumerate()
                .map(move |(k, s)| (s.offset, t as u32, k as u32))
        })
        .collect();
    at.sort_unstable();
    for (_, t, k) in at {
        let (out, spans) = &parts[t as usize];
        let end = &spans[k as usize];
        let start = match k {
            0 => Span::after(end.offset, &Traced::default()),
            _ => spans[k as usize - 1],
        };
        let [p, v, c] = start.ranges(end);
        all.photons.extend_from_slice(&out.photons[p.clone()]);
        all.normals.extend_from_slice(&out.normals[p]);
        all.volume.extend_from_slice(&out.volume[v]);
        all.connections.extend_from_slice(&out.connections[c]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::photon::photon::Photon;
    use lumis_math::{Rgb, Vec3};

    /// Results traced in two tasks, out of photon order and some photons
    /// storing none or several, come back in photon order, each photon's in
    /// the order it stored them.
    #[test]
    fn results_are_put_back_in_photon_order() {
        let ph = |x: f32| Photon::new(Vec3::splat(x), Rgb::WHITE, Vec3::Z, 1.0);
        // (photon's offset, what it stores: x of each photon)
        let tasks: [&[(u32, &[f32])]; 2] = [
            &[(5, &[5.0, 5.5]), (0, &[]), (3, &[3.0])],
            &[(1, &[1.0]), (4, &[]), (2, &[2.0, 2.25, 2.5])],
        ];
        let parts: Vec<(Traced, Vec<Span>)> = tasks
            .iter()
            .map(|task| {
                let (mut out, mut spans) = (Traced::default(), Vec::new());
                for &(offset, xs) in task.iter() {
                    for &x in xs {
                        out.photons.push(ph(x));
                        out.normals.push(Vec3::splat(x));
                        out.volume.push(ph(-x));
                    }
                    spans.push(Span::after(offset, &out));
                }
                (out, spans)
            })
            .collect();
        let mut all = Traced::default();
        all.photons.push(ph(-9.0));
        all.normals.push(Vec3::splat(-9.0));
        append_in_photon_order(&mut all, &parts);
        let want = [-9.0, 1.0, 2.0, 2.25, 2.5, 3.0, 5.0, 5.5];
        let got: Vec<f32> = all.photons.iter().map(|p| p.pos().x).collect();
        assert_eq!(got, want);
        let normals: Vec<f32> = all.normals.iter().map(|n| n.x).collect();
        assert_eq!(normals, want);
        let volume: Vec<f32> = all.volume.iter().map(|p| -p.pos().x).collect();
        assert_eq!(volume, &want[1..]);
    }
}
