//! Precomputed radiance photons (Christensen 2000, "Faster photon map global
//! illumination"): irradiance estimated once at a subset of the photon
//! positions, then read by a single nearest-neighbour lookup per final-gather
//! ray instead of a k-nearest density estimate.

use super::map::{dist2, inclusive, irradiance_knn, KdTree, PhotonMap};
use lumis_math::{Rgb, Vec3};
use rayon::prelude::*;

/// Points per kd-tree leaf at most: measured best for nearest-one lookups.
const LEAF: usize = 16;

/// Christensen's normal agreement threshold for a lookup.
const NORMAL_DOT: f32 = 0.9;

/// Radiance photons in their kd-tree's leaf order (a result index is the
/// position in `normals` / `irradiance`).
#[derive(Debug)]
pub struct RadiancePhotons {
    tree: KdTree,
    normals: Vec<Vec3>,
    irradiance: Vec<Rgb>,
}

impl RadiancePhotons {
    /// Irradiance at every `stride`-th photon of `map` (`normals[i]` is the
    /// surface normal where photon `i` of the `Vec` given to
    /// [`PhotonMap::build`] was stored) from the `k` nearest
    /// photons within `max_radius` arriving on the normal's side. Parallel and
    /// deterministic.
    pub fn build(
        map: &PhotonMap,
        normals: &[Vec3],
        stride: usize,
        k: usize,
        max_radius: f32,
    ) -> RadiancePhotons {
        assert_eq!(normals.len(), map.len(), "one normal per photon");
        let stride = stride.max(1);
        let count = map.len().div_ceil(stride);
        let mut estimates: Vec<(Vec3, Vec3, Rgb)> = Vec::with_capacity(count);
        (0..count)
            .into_par_iter()
            .with_min_len(256)
            .map_init(Vec::new, |scratch, j| {
                let i = j * stride;
                let p = map.photon(i as u32).pos();
                let n = normals[map.original_index(i as u32) as usize].normalize_or_zero();
                let (e, _) = irradiance_knn(map, p, n, k, max_radius, scratch);
                (p, n, e)
            })
            .collect_into_vec(&mut estimates);
        let mut tree = KdTree::build(estimates.iter().map(|e| e.0), LEAF);
        let order = tree.reindex_to_leaf_order();
        let normals = order.iter().map(|&i| estimates[i as usize].1).collect();
        let irradiance = order.iter().map(|&i| estimates[i as usize].2).collect();
        RadiancePhotons {
            tree,
            normals,
            irradiance,
        }
    }

    /// Irradiance of the nearest radiance photon within `max_radius` of `p`
    /// whose normal agrees with unit `n` (dot > 0.9), or None. Exitant
    /// radiance of a diffuse surface is then `E * albedo / pi`.
    pub fn irradiance(&self, p: Vec3, n: Vec3, max_radius: f32) -> Option<Rgb> {
        if !(max_radius >= 0.0) {
            return None;
        }
        let q = p.to_array();
        let mut bound = inclusive(max_radius * max_radius);
        let mut best = None;
        self.tree.search(q, &mut bound, |pts, bound| {
            for pt in pts {
                let d2 = dist2(pt, q);
                if d2 < *bound {
                    let i = pt[3].to_bits() as usize;
                    if self.normals[i].dot(n) > NORMAL_DOT {
                        *bound = d2;
                        best = Some(i);
                    }
                }
            }
        });
        best.map(|i| self.irradiance[i])
    }

    pub fn len(&self) -> usize {
        self.normals.len()
    }

    pub fn is_empty(&self) -> bool {
        self.normals.is_empty()
    }

    pub fn memory_bytes(&self) -> usize {
        self.tree.memory_bytes()
            + self.normals.capacity() * std::mem::size_of::<Vec3>()
            + self.irradiance.capacity() * std::mem::size_of::<Rgb>()
    }
}
