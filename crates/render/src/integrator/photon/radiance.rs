//! Precomputed radiance photons (Christensen 2000, "Faster photon map global
//! illumination"): irradiance estimated once at a subset of the photon
//! positions, then read by a single nearest-neighbour lookup per final-gather
//! ray instead of a k-nearest density estimate.
//!
//! In progressive iterations the points stay those of the first iteration
//! ([`Points`], shared) and each iteration estimates irradiance there from
//! its own photons, each point over its own fixed disc. Which point a
//! lookup reads then depends on the first iteration's photons only, not on
//! the photons of the estimate it reads: were the points the iteration's
//! own photons, the nearest one to a lookup would sit beside a gap in them
//! (no nearer point), and the disc around it would miss those photons, a
//! bias of about one photon per disc that grows as the discs shrink.

use super::map::{dist2, inclusive, irradiance_knn, irradiance_within, KdTree, PhotonMap};
use super::radius_field::RadiusField;
use lumis_math::{Rgb, Vec3};
use rayon::prelude::*;
use std::sync::Arc;

/// Points per kd-tree leaf at most: measured best for nearest-one lookups.
const LEAF: usize = 16;

/// Christensen's normal agreement threshold for a lookup.
const NORMAL_DOT: f32 = 0.9;

/// Where radiance photons are: positions and surface normals in the
/// kd-tree's leaf order (a search result is an index into both).
#[derive(Debug)]
pub struct Points {
    tree: KdTree,
    pos: Vec<Vec3>,
    normals: Vec<Vec3>,
    /// Progressive iterations: each point's initial squared disc radius
    /// (the global radius field's there; read once per render, not once
    /// per iteration). Empty otherwise.
    r0_2: Vec<f32>,
}

impl Points {
    /// Every `stride`-th photon of `map` (`normals[i]` is the surface
    /// normal where photon `i` of the `Vec` given to [`PhotonMap::build`]
    /// was stored).
    pub fn from_map(map: &PhotonMap, normals: &[Vec3], stride: usize) -> Points {
        assert_eq!(normals.len(), map.len(), "one normal per photon");
        let idx: Vec<u32> = (0..map.len() as u32).step_by(stride.max(1)).collect();
        let mut tree = KdTree::build(idx.iter().map(|&i| map.photon(i).pos()), LEAF);
        let order = tree.reindex_to_leaf_order();
        let at = |j: u32| idx[j as usize];
        Points {
            tree,
            pos: order.iter().map(|&j| map.photon(at(j)).pos()).collect(),
            normals: order
                .iter()
                .map(|&j| normals[map.original_index(at(j)) as usize].normalize_or_zero())
                .collect(),
            r0_2: Vec::new(),
        }
    }

    /// [`Points::from_map`] with each point's initial squared disc radius
    /// read from the global radius field.
    pub fn with_radii(mut self, field: &RadiusField) -> Points {
        self.r0_2 = self.pos.iter().map(|&p| field.r2_at(p)).collect();
        self
    }

    pub fn len(&self) -> usize {
        self.pos.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    pub fn memory_bytes(&self) -> usize {
        self.tree.memory_bytes()
            + (self.pos.capacity() + self.normals.capacity()) * 12
            + self.r0_2.capacity() * 4
    }
}

/// Irradiance at [`Points`].
#[derive(Debug)]
pub struct RadiancePhotons {
    points: Arc<Points>,
    irradiance: Vec<Rgb>,
    /// Progressive iterations: the iteration's `scale2`; each point's
    /// squared disc radius, `r0_2 scale2`, also bounds the distance at
    /// which it may be read (None otherwise).
    scale2: Option<f32>,
}

impl RadiancePhotons {
    /// Irradiance at every `stride`-th photon of `map` from the `k` nearest
    /// photons within `max_radius` (itself included) arriving on the
    /// normal's side. Parallel and deterministic.
    pub fn build(
        map: &PhotonMap,
        normals: &[Vec3],
        stride: usize,
        k: usize,
        max_radius: f32,
    ) -> RadiancePhotons {
        let points = Arc::new(Points::from_map(map, normals, stride));
        let irradiance = par_map(&points, |_, p, n, scratch| {
            irradiance_knn(map, p, n, k, max_radius, scratch).0
        });
        RadiancePhotons {
            points,
            irradiance,
            scale2: None,
        }
    }

    /// Irradiance at `points` (made [`Points::with_radii`]) from every
    /// photon of `map` within the iteration's global radius there
    /// (progressive iterations): `r0_2 scale2` at each point, what
    /// `Radii::global_r2` gives there.
    pub fn fixed(map: &PhotonMap, points: Arc<Points>, scale2: f32) -> RadiancePhotons {
        assert_eq!(points.r0_2.len(), points.len(), "points made with_radii");
        let irradiance = par_map(&points, |i, p, n, scratch| {
            irradiance_within(map, p, n, (points.r0_2[i] * scale2).sqrt(), scratch)
        });
        RadiancePhotons {
            points,
            irradiance,
            scale2: Some(scale2),
        }
    }

    /// Irradiance of the nearest radiance photon within `max_radius` of `p`
    /// whose normal agrees with unit `n` (dot > 0.9) and, in progressive
    /// iterations, within its own disc's radius, or None. Exitant radiance
    /// of a diffuse surface is then `E * albedo / pi`.
    pub fn irradiance(&self, p: Vec3, n: Vec3, max_radius: f32) -> Option<Rgb> {
        if !(max_radius >= 0.0) {
            return None;
        }
        let q = p.to_array();
        let mut bound = inclusive(max_radius * max_radius);
        let mut best = None;
        let normals = &self.points.normals;
        self.points.tree.search(q, &mut bound, |pts, bound| {
            for pt in pts {
                let d2 = dist2(pt, q);
                if d2 < *bound {
                    let i = pt[3].to_bits() as usize;
                    let inside = self.scale2.is_none_or(|s| d2 <= self.points.r0_2[i] * s);
                    if inside && normals[i].dot(n) > NORMAL_DOT {
                        *bound = d2;
                        best = Some(i);
                    }
                }
            }
        });
        best.map(|i| self.irradiance[i])
    }

    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Bytes of this iteration's values and of the points they share.
    pub fn memory_bytes(&self) -> usize {
        self.points.memory_bytes() + self.irradiance.capacity() * std::mem::size_of::<Rgb>()
    }
}

/// `f(index, position, normal, scratch)` at every point, in parallel, in order.
fn par_map(
    points: &Points,
    f: impl Fn(usize, Vec3, Vec3, &mut Vec<(u32, f32)>) -> Rgb + Sync,
) -> Vec<Rgb> {
    let mut out = Vec::with_capacity(points.len());
    (0..points.len())
        .into_par_iter()
        .with_min_len(256)
        .map_init(Vec::new, |scratch, i| {
            f(i, points.pos[i], points.normals[i], scratch)
        })
        .collect_into_vec(&mut out);
    out
}
