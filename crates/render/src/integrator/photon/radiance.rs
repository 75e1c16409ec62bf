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

use super::disc_grid::DiscGrid;
use super::map::{dist2, inclusive, irradiance_knn, irradiance_within, KdTree, PhotonMap};
use super::radius_field::RadiusField;
use lumis_math::{Rgb, Vec3};
use rayon::prelude::*;
use std::sync::{Arc, Mutex};

/// Points per kd-tree leaf at most: measured best for nearest-one lookups.
const LEAF: usize = 16;

/// Christensen's normal agreement threshold for a lookup.
const NORMAL_DOT: f32 = 0.9;

/// A lookup grid serves iterations until their discs shrink below this
/// fraction of its own in area; then the next iteration builds another
/// (with `a` = 1/2, at iterations 1, 3, 9, 30...: 1.05x faster than a
/// grid per iteration on the default scene, whose lists grow stale less
/// than their builds cost).
const GRID_KEEP: f32 = 0.5;

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
    /// The last lookup grid built and the `scale2` it was built for.
    grid: Mutex<Option<(f32, Option<Arc<DiscGrid>>)>>,
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
            grid: Mutex::new(None),
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
        let grid = self.grid.lock().unwrap_or_else(|e| e.into_inner());
        let grid = grid.as_ref().and_then(|g| g.1.as_ref());
        self.tree.memory_bytes()
            + (self.pos.capacity() + self.normals.capacity()) * 12
            + self.r0_2.capacity() * 4
            + grid.map_or(0, |g| g.memory_bytes())
    }

    /// A lookup grid for discs `scale2` times the initial ones: the last
    /// one built while these discs are at least [`GRID_KEEP`] of its own,
    /// else a new one. Which grid answers never changes a lookup's result.
    fn grid(&self, scale2: f32) -> Option<Arc<DiscGrid>> {
        let mut last = self.grid.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((s, g)) = last.as_ref() {
            if scale2 <= *s && scale2 >= GRID_KEEP * s {
                return g.clone();
            }
        }
        *last = None;
        let g = DiscGrid::build(&self.pos, &self.r0_2, scale2).map(Arc::new);
        *last = Some((scale2, g.clone()));
        g
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
    /// Progressive iterations: the lookup's candidates per cell (exact;
    /// None where a radius is not finite, and the kd-tree answers).
    grid: Option<Arc<DiscGrid>>,
    /// Progressive iterations: what the grid's lookup reads of a point, in
    /// one cache line.
    records: Vec<Record>,
}

/// A point's normal, squared disc radius in this iteration and irradiance.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
struct Record {
    n: Vec3,
    r2: f32,
    e: Rgb,
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
            grid: None,
            records: Vec::new(),
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
        let grid = points.grid(scale2);
        let records = (0..points.len())
            .map(|i| Record {
                n: points.normals[i],
                r2: points.r0_2[i] * scale2,
                e: irradiance[i],
            })
            .collect();
        RadiancePhotons {
            points,
            irradiance,
            scale2: Some(scale2),
            grid,
            records,
        }
    }

    /// [`RadiancePhotons::fixed`] read through the kd-tree only (tests).
    #[cfg(test)]
    pub(crate) fn without_grid(mut self) -> RadiancePhotons {
        self.grid = None;
        self
    }

    /// Irradiance of the nearest radiance photon within `max_radius` of `p`
    /// whose normal agrees with unit `n` (dot > 0.9) and, in progressive
    /// iterations, within its own disc's radius, or None. Exitant radiance
    /// of a diffuse surface is then `E * albedo / pi`.
    pub fn irradiance(&self, p: Vec3, n: Vec3, max_radius: f32) -> Option<Rgb> {
        if !(max_radius >= 0.0) {
            return None;
        }
        let mut bound = inclusive(max_radius * max_radius);
        if let Some(g) = &self.grid {
            let best = g.nearest(p, bound, |i, d2| {
                let r = &self.records[i as usize];
                d2 <= r.r2 && r.n.dot(n) > NORMAL_DOT
            });
            return best.map(|i| self.records[i as usize].e);
        }
        let normals = &self.points.normals;
        let q = p.to_array();
        let mut best = None;
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
        self.points.memory_bytes()
            + self.irradiance.capacity() * std::mem::size_of::<Rgb>()
            + self.records.capacity() * std::mem::size_of::<Record>()
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::photon::photon::Photon;
    use lumis_math::Pcg32;

    /// Photons on the floor and two walls of a unit box meeting at edges
    /// (where normals disagree), denser in one corner.
    fn box_photons(n: usize, rng: &mut Pcg32) -> (Vec<Photon>, Vec<Vec3>) {
        let (mut ph, mut normals) = (Vec::new(), Vec::new());
        for i in 0..n {
            let (a, b) = (rng.next_f32(), rng.next_f32());
            let (a, b) = if i % 3 == 0 {
                (a * 0.2, b * 0.2)
            } else {
                (a, b)
            };
            let (p, nrm) = match i % 3 {
                0 => (Vec3::new(a, 0.0, b), Vec3::Y),
                1 => (Vec3::new(0.0, a, b), Vec3::X),
                _ => (Vec3::new(a, b, 1.0), -Vec3::Z),
            };
            let power = Rgb::new(rng.next_f32(), 1.0, 0.5);
            ph.push(Photon::new(p, power, -nrm, 1.0));
            normals.push(nrm);
        }
        (ph, normals)
    }

    #[test]
    fn grid_lookups_are_the_kd_trees() {
        let mut rng = Pcg32::new(3, 1);
        let (ph, normals) = box_photons(20000, &mut rng);
        let map = PhotonMap::build(ph, 20000);
        let field = RadiusField::from_map(&map, 30, 0.08, false);
        let points = Arc::new(Points::from_map(&map, &normals, 4).with_radii(&field));
        let (mut found, mut total) = (0, 0);
        // Shrinking discs (the first grid serves two of these, then new
        // ones), then larger ones again (as after a reset).
        for scale2 in [1.0, 0.7, 0.45, 0.3, 0.1, 0.6] {
            let rp = RadiancePhotons::fixed(&map, points.clone(), scale2);
            let kd = RadiancePhotons::fixed(&map, points.clone(), scale2).without_grid();
            assert!(rp.grid.is_some());
            let max = 0.08 * scale2.sqrt();
            for k in 0..20000 {
                let q = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
                // Onto a face, or just off it, or anywhere in the box.
                let (q, n) = match k % 4 {
                    0 => (Vec3::new(q.x, 1e-4 * q.y, q.z), Vec3::Y),
                    1 => (Vec3::new(0.02 * q.x, q.y, q.z), Vec3::X),
                    2 => (Vec3::new(q.x, q.y, 1.0), -Vec3::Z),
                    _ => (q, Vec3::Y),
                };
                let r = if k % 5 == 0 { 0.01 } else { max };
                let got = rp.irradiance(q, n, r).map(|e| [e.r, e.g, e.b]);
                let want = kd.irradiance(q, n, r).map(|e| [e.r, e.g, e.b]);
                assert_eq!(got, want, "scale2 {scale2}, query {k} at {q:?}");
                found += want.is_some() as usize;
                total += 1;
            }
        }
        assert!(
            found > total / 4 && found < total,
            "{found} of {total} found"
        );
    }
}
