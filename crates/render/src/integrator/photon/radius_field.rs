//! The progressive mode's initial radii, one per point of the scene: the
//! squared distance to the `k`-th nearest photon, measured at a sample of
//! the first iteration's stored photons, never less than its median over
//! them, and read at any point from the nearest sample. Iteration `i` uses
//! `r_i(x)^2 = r_0(x)^2 prod_{j<i} (j + a) / (j + 1)`, so every point's
//! radius follows Knaus and Zwicker's sequence and the estimate stays
//! consistent everywhere. Aimed caustic photons are counted by flux (the
//! radii an unaimed map would give; `flux_equivalent_k`).
//!
//! One radius for the whole scene (the median) is too small where photons
//! are sparse: the photon estimate's variance grows there and, under the
//! seed's weights, `q_1` (proportional to the disc's area) hands those
//! caustics to the gather rays, which see small lights only as fireflies
//! (measured: speckles over the default scene's walls, from the gold
//! sphere's caustic). The k-nearest radius alone is smaller than the median
//! where photons are dense, and there the median measured better: on the
//! diffuse caustic test scene at 64 iterations, per-pixel MSE 2.96e-2 with
//! the k-nearest radius, 1.81e-2 with it floored at the median, 1.63e-2
//! with the median everywhere (`tests/photon_progressive.rs`'s scene and
//! settings, 4 seeds).
//!
//! The field is fixed after the first iteration; only that iteration's
//! estimate shares photons with the radii it uses (as any k-nearest
//! estimate does), which affects one iteration out of many.

use super::map::{dist2, inclusive, KdTree, PhotonMap};
use super::progressive::Progressive;
use super::radiance::Points;
use super::{PhotonMaps, PhotonSettings, GLOBAL_RADIUS_SCALE, RADIANCE_STRIDE};
use lumis_math::Vec3;
use rayon::prelude::*;
use std::sync::Arc;

/// Photons sampled for the field at most (evenly strided).
const SAMPLES: usize = 32_768;
const LEAF: usize = 16;

#[derive(Debug)]
pub struct RadiusField {
    tree: KdTree,
    /// Squared radius of each sample, in the tree's leaf order.
    r2: Vec<f32>,
    /// The largest radius: where no sample lies within it, and the cap.
    max_radius: f32,
}

impl RadiusField {
    /// The same radius everywhere.
    pub fn constant(radius: f32) -> RadiusField {
        RadiusField {
            tree: KdTree::build(std::iter::empty(), LEAF),
            r2: Vec::new(),
            max_radius: radius,
        }
    }

    /// Squared `k`-nearest radii (at most `max_radius`, at least their
    /// median) at up to 32768 of `map`'s photons. Parallel and
    /// deterministic. `by_flux`: the median weights each photon by its flux
    /// (aimed photons, whose fluxes differ: the median unaimed photons,
    /// all of equal flux, would give).
    pub fn from_map(map: &PhotonMap, k: usize, max_radius: f32, by_flux: bool) -> RadiusField {
        let n = map.len();
        if n == 0 {
            return RadiusField::constant(max_radius);
        }
        let stride = n.div_ceil(SAMPLES);
        let idx: Vec<u32> = (0..n as u32).step_by(stride).collect();
        let r2: Vec<f32> = idx
            .par_iter()
            .with_min_len(64)
            .map_init(Vec::new, |found, &i| {
                map.knn(map.photon(i).pos(), k, max_radius, found)
            })
            .collect();
        let floor = match by_flux {
            false => {
                let mut sorted = r2.clone();
                sorted.sort_by(f32::total_cmp);
                sorted[sorted.len() / 2]
            }
            true => {
                let flux = |i: u32| map.photon(i).power().luminance() as f64;
                let mut sorted: Vec<(f32, f64)> =
                    r2.iter().zip(&idx).map(|(&r, &i)| (r, flux(i))).collect();
                sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
                let half = 0.5 * sorted.iter().map(|x| x.1).sum::<f64>();
                let mut acc = 0.0;
                let at = sorted.iter().position(|x| {
                    acc += x.1;
                    acc >= half
                });
                sorted[at.unwrap_or(sorted.len() - 1)].0
            }
        };
        let r2: Vec<f32> = r2.into_iter().map(|r| r.max(floor)).collect();
        let mut tree = KdTree::build(idx.iter().map(|&i| map.photon(i).pos()), LEAF);
        let order = tree.reindex_to_leaf_order();
        RadiusField {
            tree,
            r2: order.iter().map(|&j| r2[j as usize]).collect(),
            max_radius,
        }
    }

    /// `r_0(p)^2`: the nearest sample's within `max_radius`, else
    /// `max_radius^2`.
    pub fn r2_at(&self, p: Vec3) -> f32 {
        let q = p.to_array();
        let mut bound = inclusive(self.max_radius * self.max_radius);
        let mut best = None;
        self.tree.search(q, &mut bound, |pts, bound| {
            for pt in pts {
                let d2 = dist2(pt, q);
                if d2 < *bound {
                    *bound = d2;
                    best = Some(pt[3].to_bits() as usize);
                }
            }
        });
        best.map_or(self.max_radius * self.max_radius, |i| self.r2[i])
    }

    /// The largest radius.
    pub fn max_radius(&self) -> f32 {
        self.max_radius
    }

    /// The median squared radius over the samples (`max_radius^2` without).
    pub fn median_r2(&self) -> f32 {
        let mut v = self.r2.clone();
        if v.is_empty() {
            return self.max_radius * self.max_radius;
        }
        v.sort_by(f32::total_cmp);
        v[v.len() / 2]
    }

    pub fn memory_bytes(&self) -> usize {
        self.tree.memory_bytes() + self.r2.capacity() * 4
    }
}

/// The initial radii of the caustic and global estimates, point by point.
pub struct RadiusFields {
    pub caustic: Arc<RadiusField>,
    pub global: Arc<RadiusField>,
    /// Where the global estimate is precomputed in every iteration.
    pub global_points: Arc<Points>,
}

impl RadiusFields {
    /// From iteration 0's maps: the `nearest`-th photon's distance, up to
    /// the single map's largest radii (the caustic estimate's, and the
    /// global lookup's); a given `initialradius` sets the caustic one.
    pub fn new(
        maps: &PhotonMaps,
        normals: &[Vec3],
        s: &PhotonSettings,
        p: &Progressive,
    ) -> RadiusFields {
        let aimed = maps.targets.is_some();
        let caustic = match (p.initial_radius > 0.0, aimed) {
            (true, _) => RadiusField::constant(p.initial_radius),
            (false, false) => {
                RadiusField::from_map(&maps.caustic, s.nearest, maps.max_radius, false)
            }
            (false, true) => {
                let k = flux_equivalent_k(&maps.caustic, s.nearest, maps.phi);
                RadiusField::from_map(&maps.caustic, k, maps.max_radius, true)
            }
        };
        let global_max = maps.max_radius * GLOBAL_RADIUS_SCALE;
        RadiusFields {
            caustic: Arc::new(caustic),
            global: Arc::new(RadiusField::from_map(
                &maps.global,
                s.nearest,
                global_max,
                false,
            )),
            global_points: Arc::new(Points::from_map(&maps.global, normals, RADIANCE_STRIDE)),
        }
    }
}

/// Aimed caustic photons carry less flux each than unaimed ones, whose
/// luminance is `Phi / N` (Russian roulette keeps it): the count of aimed
/// photons carrying on average the flux of `k` unaimed ones, at most `16 k`.
/// The initial radii are then those an unaimed map would give, and aiming
/// lowers the estimate's variance instead of its radius (measured on the
/// large-light caustic scene, where aiming stores 5.5 times the photons:
/// with the radii of `k` aimed photons the error did not fall).
fn flux_equivalent_k(map: &PhotonMap, k: usize, phi: f32) -> usize {
    let n = map.len();
    if n == 0 || map.emitted() == 0 {
        return k;
    }
    let sum: f64 = (0..n as u32)
        .map(|i| map.photon(i).power().luminance() as f64)
        .sum();
    let unaimed = phi as f64 / map.emitted() as f64;
    let ratio = unaimed / (sum / n as f64);
    if !ratio.is_finite() || ratio <= 1.0 {
        return k;
    }
    ((k as f64 * ratio).round() as usize).min(16 * k)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::photon::photon::Photon;
    use lumis_math::Rgb;

    /// Photons on the plane z = 0: a dense square [0,1]^2 (spacing 0.01), a
    /// sparse one [10,11]^2 (spacing 0.1) and a small denser one at 20
    /// (spacing 0.001, fewer photons than the dense square).
    fn three_densities() -> PhotonMap {
        let mut v = Vec::new();
        for (origin, step, n) in [(0.0, 0.01, 100), (10.0, 0.1, 10), (20.0, 0.001, 20)] {
            for i in 0..n {
                for j in 0..n {
                    let p = Vec3::new(origin + i as f32 * step, origin + j as f32 * step, 0.0);
                    v.push(Photon::new(p, Rgb::WHITE, Vec3::Z, 1.0));
                }
            }
        }
        let len = v.len() as u64;
        PhotonMap::build(v, len)
    }

    #[test]
    fn radii_follow_the_photon_density() {
        let f = RadiusField::from_map(&three_densities(), 9, 5.0, false);
        // 9 nearest on a square lattice: the 8 neighbours and itself, the
        // farthest diagonal: r^2 = 2 step^2.
        let dense = f.r2_at(Vec3::new(0.5, 0.5, 0.0));
        let sparse = f.r2_at(Vec3::new(10.5, 10.5, 0.0));
        assert!((dense - 2e-4).abs() < 1e-6, "{dense}");
        assert!((sparse - 2e-2).abs() < 1e-4, "{sparse}");
        // Denser than the median: the median (the dense square's) instead.
        let denser = f.r2_at(Vec3::new(20.01, 20.01, 0.0));
        assert!((denser - 2e-4).abs() < 1e-6, "{denser}");
        assert!((f.median_r2() - 2e-4).abs() < 1e-6);
        // Far from every photon: the largest radius.
        assert_eq!(f.r2_at(Vec3::new(100.0, 0.0, 0.0)), 25.0);
        assert_eq!(RadiusField::constant(0.5).r2_at(Vec3::ZERO), 0.25);
    }

    #[test]
    fn aimed_photons_are_counted_by_flux() {
        // 400 photons of power 0.25 from 100 emitted with Phi = 100: an
        // unaimed photon would carry Phi / N = 1, the flux of four of these.
        let v = (0..400)
            .map(|i| {
                Photon::new(
                    Vec3::new(i as f32, 0.0, 0.0),
                    Rgb::splat(0.25),
                    Vec3::Z,
                    1.0,
                )
            })
            .collect();
        let map = PhotonMap::build(v, 100);
        assert_eq!(flux_equivalent_k(&map, 10, 100.0), 40);
        // Photons carrying more than unaimed ones would: k itself; the cap.
        assert_eq!(flux_equivalent_k(&map, 10, 10.0), 10);
        assert_eq!(flux_equivalent_k(&map, 10, 1.0e4), 160);
    }

    #[test]
    fn the_flux_weighted_median_follows_the_flux() {
        // A dense square of dim photons and a sparse one carrying ten times
        // their total flux: by count the floor is the dense square's radius,
        // by flux the sparse one's.
        let mut v = Vec::new();
        for (origin, step, n, power) in [(0.0, 0.01, 100, 1.0), (10.0, 0.1, 10, 1000.0)] {
            for i in 0..n {
                for j in 0..n {
                    let p = Vec3::new(origin + i as f32 * step, origin + j as f32 * step, 0.0);
                    v.push(Photon::new(p, Rgb::splat(power), Vec3::Z, 1.0));
                }
            }
        }
        let map = PhotonMap::build(v, 10_100);
        let dense = Vec3::new(0.5, 0.5, 0.0);
        let by_count = RadiusField::from_map(&map, 9, 5.0, false);
        let by_flux = RadiusField::from_map(&map, 9, 5.0, true);
        assert!((by_count.r2_at(dense) - 2e-4).abs() < 1e-6);
        assert!(
            (by_flux.r2_at(dense) - 2e-2).abs() < 1e-4,
            "{}",
            by_flux.r2_at(dense)
        );
    }
}
