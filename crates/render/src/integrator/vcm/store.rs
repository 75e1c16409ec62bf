//! One pass's light subpaths, stored for vertex merging and for the
//! connections of the camera samples they are paired with: traced in
//! parallel and deterministically (subpath `i` draws from a stream keyed
//! by the pass's seed and `i` alone; chunks are concatenated in order),
//! with a kd-tree over the vertices a merge can use.

use crate::integrator::bdpt::vertex::{Kind, Vertex};
use crate::integrator::bdpt::walk;
use crate::integrator::photon::map::{inclusive, KdTree};
use crate::integrator::RayCounts;
use crate::scene::Scene;
use lumis_math::{Sampler, SamplerKind, Vec3};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

const CHUNK: usize = 1024;
const LEAF: usize = 16;

/// The light subpaths of one pass.
#[derive(Debug, Default)]
pub struct LightPaths {
    vertices: Vec<Vertex>,
    /// Subpath `i` is `vertices[starts[i]..starts[i + 1]]`.
    starts: Vec<u32>,
    /// Over the mergeable vertices: their index in `vertices`.
    tree: KdTree,
    mergeable: Vec<u32>,
    /// For each vertex, the index of its subpath.
    path_of: Vec<u32>,
}

impl LightPaths {
    /// Traces `n` light subpaths of up to `max_verts` vertices; `None` if
    /// `cancel` was set meanwhile.
    pub fn trace(
        scene: &Scene,
        n: usize,
        max_verts: usize,
        seed: u64,
        cancel: &AtomicBool,
    ) -> Option<LightPaths> {
        let parts: Vec<(Vec<Vertex>, Vec<u32>)> = (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let (mut verts, mut lens, mut path) = (Vec::new(), Vec::new(), Vec::new());
                if cancel.load(Ordering::Relaxed) {
                    return (verts, lens);
                }
                let mut sampler = Sampler::new(SamplerKind::Independent, seed);
                let mut rays = RayCounts::default();
                for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                    sampler.start_stream(i as u64, 0);
                    walk::light_path(scene, &mut sampler, max_verts, &mut path, &mut rays);
                    verts.extend_from_slice(&path);
                    lens.push(path.len() as u32);
                }
                scene.count_rays(rays.total());
                (verts, lens)
            })
            .collect();
        if cancel.load(Ordering::Relaxed) {
            return None;
        }
        let mut lp = LightPaths {
            starts: Vec::with_capacity(n + 1),
            ..Default::default()
        };
        lp.starts.push(0);
        for (verts, lens) in parts {
            for len in lens {
                let start = *lp.starts.last().expect("starts at 0");
                lp.path_of
                    .extend((0..len).map(|_| lp.starts.len() as u32 - 1));
                lp.starts.push(start + len);
            }
            lp.vertices.extend(verts);
        }
        assert!(
            lp.vertices.len() < u32::MAX as usize,
            "too many light vertices"
        );
        // Merges use surface vertices past the light's own.
        lp.mergeable = (0..lp.vertices.len() as u32)
            .filter(|&i| {
                let v = &lp.vertices[i as usize];
                let first = lp.starts[lp.path_of[i as usize] as usize];
                i > first && v.kind == Kind::Surface && v.connectible()
            })
            .collect();
        lp.tree = KdTree::build(
            lp.mergeable.iter().map(|&i| lp.vertices[i as usize].p),
            LEAF,
        );
        Some(lp)
    }

    /// Light subpaths stored.
    pub fn len(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Light subpath `i` (empty beyond the last).
    pub fn path(&self, i: usize) -> &[Vertex] {
        match (self.starts.get(i), self.starts.get(i + 1)) {
            (Some(&a), Some(&b)) => &self.vertices[a as usize..b as usize],
            _ => &[],
        }
    }

    /// Calls `f` with the light subpath up to and including each mergeable
    /// vertex within `radius` of `p`.
    pub fn within(&self, p: Vec3, radius: f32, mut f: impl FnMut(&[Vertex])) {
        let mut bound = inclusive(radius * radius);
        self.tree
            .for_each_within(p.to_array(), &mut bound, |i, _, _| {
                let v = self.mergeable[i as usize] as usize;
                let a = self.starts[self.path_of[v] as usize] as usize;
                f(&self.vertices[a..=v]);
            });
    }

    pub fn memory_bytes(&self) -> usize {
        self.vertices.capacity() * std::mem::size_of::<Vertex>()
            + (self.starts.capacity() + self.mergeable.capacity() + self.path_of.capacity()) * 4
            + self.tree.memory_bytes()
    }
}
