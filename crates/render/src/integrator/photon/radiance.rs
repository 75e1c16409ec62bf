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
use super::map::{inclusive, irradiance_knn, irradiance_within, KdTree, PhotonMap};
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
/// (five grids over the default scene's first 256 iterations). Level with
/// a grid per iteration in single-thread profiles of the default scene
/// (the lookup 11.0% against 11.6% of the render, one profile each), for
/// a fraction of the builds.
const GRID_KEEP: f32 = 0.5;

/// Where radiance photons are: positions and surface normals in the
/// kd-tree's leaf order (a search result is an index into both).
#[derive(Debug)]
pub struct Points {
    tree: KdTree,
    pos: Vec<Vec3>,
    /// Each point's unit normal and, in `[3]`, in progressive iterations,
    /// its initial squared disc radius (the global radius field's there;
    /// read once per render, not once per iteration): what a lookup reads
    /// of a candidate, side by side.
    normal_r0_2: Vec<[f32; 4]>,
    /// The radii are set ([`Points::with_radii`]).
    has_radii: bool,
    /// The lookup grids built: the last and the `scale2` it was built for.
    grid: Mutex<GridCache>,
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
            normal_r0_2: order
                .iter()
                .map(|&j| {
                    let n = normals[map.original_index(at(j)) as usize].normalize_or_zero();
                    [n.x, n.y, n.z, 0.0]
                })
                .collect(),
            has_radii: false,
            grid: Mutex::new(GridCache::default()),
        }
    }

    /// [`Points::from_map`] with each point's initial squared disc radius
    /// read from the global radius field.
    pub fn with_radii(mut self, field: &RadiusField) -> Points {
        for (m, &p) in self.normal_r0_2.iter_mut().zip(&self.pos) {
            m[3] = field.r2_at(p);
        }
        self.has_radii = true;
        self
    }

    pub fn len(&self) -> usize {
        self.pos.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    /// Bytes of the points, not counting a lookup grid.
    pub fn memory_bytes(&self) -> usize {
        self.tree.memory_bytes() + self.pos.capacity() * 12 + self.normal_r0_2.capacity() * 16
    }

    /// A lookup grid for discs `scale2` times the initial ones: the last
    /// one built while these discs are at least [`GRID_KEEP`] of its own,
    /// else a new one. Which grid answers never changes a lookup's result.
    /// Its cells are at most twice the first grid's (plus a floor): the
    /// grid's memory stays that of the first however long the render.
    fn grid(&self, scale2: f32) -> Option<Arc<DiscGrid>> {
        let mut cache = self.grid.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((s, g)) = cache.last.as_ref() {
            if scale2 <= *s && scale2 >= GRID_KEEP * s {
                return g.clone();
            }
        }
        cache.last = None;
        let r0_2: Vec<f32> = self.normal_r0_2.iter().map(|m| m[3]).collect();
        let max_cells = cache.first_cells.map_or(usize::MAX, |c| 2 * c + 4096);
        let g = DiscGrid::build(&self.pos, &r0_2, scale2, max_cells).map(Arc::new);
        if let Some(g) = &g {
            cache.first_cells.get_or_insert(g.cells());
        }
        cache.last = Some((scale2, g.clone()));
        g
    }
}

/// [`Points`]' lookup grids: the last built, and how many cells the first
/// one used.
#[derive(Debug, Default)]
struct GridCache {
    last: Option<(f32, Option<Arc<DiscGrid>>)>,
    first_cells: Option<usize>,
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
        }
    }

    /// Irradiance at `points` (made [`Points::with_radii`]) from every
    /// photon of `map` within the iteration's global radius there
    /// (progressive iterations): `r0_2 scale2` at each point, what
    /// `Radii::global_r2` gives there.
    pub fn fixed(map: &PhotonMap, points: Arc<Points>, scale2: f32) -> RadiancePhotons {
        assert!(points.has_radii, "points made with_radii");
        let irradiance = par_map(&points, |i, p, n, scratch| {
            irradiance_within(
                map,
                p,
                n,
                (points.normal_r0_2[i][3] * scale2).sqrt(),
                scratch,
            )
        });
        let grid = points.grid(scale2);
        RadiancePhotons {
            points,
            irradiance,
            scale2: Some(scale2),
            grid,
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
        let meta = &self.points.normal_r0_2;
        // Inside the point's own disc (progressive iterations) and facing
        // the same way.
        let readable = |m: &[f32; 4], d2: f32| {
            self.scale2.is_none_or(|s| d2 <= m[3] * s)
                && Vec3::new(m[0], m[1], m[2]).dot(n) > NORMAL_DOT
        };
        if let Some(g) = &self.grid {
            let best = g.nearest(p, bound, |i, d2| readable(&meta[i as usize], d2));
            return best.map(|i| self.irradiance[i as usize]);
        }
        let mut best = None;
        self.points
            .tree
            .for_each_within(p.to_array(), &mut bound, |i, d2, bound| {
                if readable(&meta[i as usize], d2) {
                    *bound = d2;
                    best = Some(i as usize);
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

    /// Bytes of this iteration's values, of the points they share and of
    /// the lookup grid.
    pub fn memory_bytes(&self) -> usize {
        self.points.memory_bytes()
            + self.irradiance.capacity() * std::mem::size_of::<Rgb>()
            + self.grid_bytes()
    }

    /// Bytes of the lookup grid alone (0 without one).
    pub fn grid_bytes(&self) -> usize {
        self.grid.as_ref().map_or(0, |g| g.memory_bytes())
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
            let m = &points.normal_r0_2[i];
            f(i, points.pos[i], Vec3::new(m[0], m[1], m[2]), scratch)
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
