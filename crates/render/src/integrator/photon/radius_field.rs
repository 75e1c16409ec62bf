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

use super::disc_grid::DiscGrid;
use super::map::{inclusive, KdTree, PhotonMap};
use super::progressive::Progressive;
use super::radiance::Points;
use super::{PhotonMaps, PhotonSettings, GLOBAL_RADIUS_SCALE, RADIANCE_STRIDE};
use lumis_math::{Vec3, PI};
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
    /// At each sample (leaf order; empty: not measured), the share of the
    /// irradiance that caustics the gather rays can find bring, and the
    /// factor `c` of their weight `w_2 = 1 / (1 + c scale2)` in an
    /// iteration whose discs are `scale2` times the first's ([`Shares`]).
    share: Vec<(f32, f32)>,
    /// The largest radius: where no sample lies within it, and the cap.
    max_radius: f32,
    /// The samples' nearest lookup (None: the tree's).
    grid: Option<DiscGrid>,
}

impl RadiusField {
    /// The same radius everywhere.
    pub fn constant(radius: f32) -> RadiusField {
        RadiusField {
            tree: KdTree::build(std::iter::empty(), LEAF),
            r2: Vec::new(),
            share: Vec::new(),
            max_radius: radius,
            grid: None,
        }
    }

    /// Squared `k`-nearest radii (at most `max_radius`, at least their
    /// median) at up to 32768 of `map`'s photons. Parallel and
    /// deterministic. `by_flux`: the median weights each photon by its flux
    /// (aimed photons, whose fluxes differ: the median unaimed photons,
    /// all of equal flux, would give).
    pub fn from_map(map: &PhotonMap, k: usize, max_radius: f32, by_flux: bool) -> RadiusField {
        RadiusField::with_shares(map, k, max_radius, by_flux, None)
    }

    /// [`from_map`](Self::from_map), and where `shares` is given, what
    /// [`at`](Self::at) reads at each sample ([`Shares`]).
    pub fn with_shares(
        map: &PhotonMap,
        k: usize,
        max_radius: f32,
        by_flux: bool,
        shares: Option<Shares>,
    ) -> RadiusField {
        let n = map.len();
        if n == 0 {
            return RadiusField::constant(max_radius);
        }
        let stride = n.div_ceil(SAMPLES);
        let idx: Vec<u32> = (0..n as u32).step_by(stride).collect();
        let measured: Vec<(f32, (f32, f32))> = idx
            .par_iter()
            .with_min_len(64)
            .map_init(Vec::new, |found, &i| {
                let p = map.photon(i).pos();
                let r2 = map.knn(p, k, max_radius, found);
                let share = shares.as_ref().map_or((0.0, 0.0), |sh| {
                    let (flux, k_mean) = sh.gatherable(map, found);
                    let r2g = sh.global.knn(p, k, sh.global_max, found);
                    (
                        caustic_share(flux / r2, total_flux(sh.global, found) / r2g),
                        k_mean,
                    )
                });
                (r2, share)
            })
            .collect();
        let (r2, share): (Vec<f32>, Vec<(f32, f32)>) = measured.into_iter().unzip();
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
        // `c` of `w_2` over the first iteration's disc, `pi r_0^2`.
        let share: Vec<(f32, f32)> = share
            .iter()
            .zip(&r2)
            .map(|(&(sc, k_mean), &r2)| (sc, k_mean * PI * r2))
            .collect();
        let mut tree = KdTree::build(idx.iter().map(|&i| map.photon(i).pos()), LEAF);
        let order = tree.reindex_to_leaf_order();
        RadiusField {
            grid: None,
            tree,
            r2: order.iter().map(|&j| r2[j as usize]).collect(),
            share: match shares {
                Some(_) => order.iter().map(|&j| share[j as usize]).collect(),
                None => Vec::new(),
            },
            max_radius,
        }
    }

    /// The field with its samples listed on a hashed grid for
    /// [`r2_at`](Self::r2_at) and [`at`](Self::at) (the caustic field, read
    /// at every camera path's shading point): each sample is a ball of
    /// radius `max_radius`, so the nearest ball holding a point is the
    /// nearest sample within `max_radius` (`disc_grid.rs`; the same sample
    /// as the tree's but where two lie at exactly the same distance).
    pub fn with_grid(mut self) -> RadiusField {
        let pos = self.tree.positions();
        let balls = vec![self.max_radius * self.max_radius; pos.len()];
        self.grid = DiscGrid::build(&pos, &balls, 1.0, usize::MAX);
        self
    }

    /// `r_0(p)^2`: the nearest sample's within `max_radius`, else
    /// `max_radius^2`.
    pub fn r2_at(&self, p: Vec3) -> f32 {
        self.nearest(p)
            .map_or(self.max_radius * self.max_radius, |i| self.r2[i])
    }

    /// [`r2_at`](Self::r2_at) and, from the same sample, the share of the
    /// irradiance at `p` that the gather rays carry of the caustics in an
    /// iteration whose discs are `scale2` times the first's (0 where no
    /// sample lies within `max_radius`, or shares were not measured).
    pub fn at(&self, p: Vec3, scale2: f32) -> (f32, f32) {
        match self.nearest(p) {
            None => (self.max_radius * self.max_radius, 0.0),
            Some(i) => {
                let share = self
                    .share
                    .get(i)
                    .map_or(0.0, |&(share, c)| share / (1.0 + c * scale2));
                (self.r2[i], share)
            }
        }
    }

    /// The nearest sample within `max_radius`, in leaf order.
    fn nearest(&self, p: Vec3) -> Option<usize> {
        let mut bound = inclusive(self.max_radius * self.max_radius);
        if let Some(g) = &self.grid {
            return g.nearest(p, bound, |_, _| true).map(|i| i as usize);
        }
        let mut best = None;
        self.tree
            .for_each_within(p.to_array(), &mut bound, |i, d2, bound| {
                *bound = d2;
                best = Some(i as usize);
            });
        best
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
        self.tree.memory_bytes()
            + self.r2.capacity() * 4
            + self.share.capacity() * 8
            + self.grid.as_ref().map_or(0, DiscGrid::memory_bytes)
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
        let global_max = maps.max_radius * GLOBAL_RADIUS_SCALE;
        // The gather rays' share of the light, measured where they are
        // boosted by it: with the first iteration's `DeltaA` and `alpha`
        // (the disc shrinks later, so `w_2` grows).
        let alpha = (p.iteration_spp.max(1) as f32) * s.gather_gain;
        let n_over_phi = match aimed {
            false => maps.caustic.emitted() as f32 / maps.phi,
            true => 1.0,
        };
        let shares = (s.gather_boost > 1.0).then_some(Shares {
            global: &maps.global,
            global_max,
            q_ratio: n_over_phi * PI / (alpha * s.gather_rays.max(1) as f32),
            aimed,
        });
        let caustic = match (p.initial_radius > 0.0, aimed) {
            (true, _) => RadiusField::constant(p.initial_radius),
            (false, false) => {
                RadiusField::with_shares(&maps.caustic, s.nearest, maps.max_radius, false, shares)
                    .with_grid()
            }
            (false, true) => {
                let k = flux_equivalent_k(&maps.caustic, s.nearest, maps.phi);
                RadiusField::with_shares(&maps.caustic, k, maps.max_radius, true, shares)
                    .with_grid()
            }
        };
        let global = RadiusField::from_map(&maps.global, s.nearest, global_max, false);
        let points = Points::from_map(&maps.global, normals, RADIANCE_STRIDE).with_radii(&global);
        RadiusFields {
            caustic: Arc::new(caustic),
            global: Arc::new(global),
            global_points: Arc::new(points),
        }
    }
}

/// The summed power (luminance) of the photons `found`.
fn total_flux(map: &PhotonMap, found: &[(u32, f32)]) -> f32 {
    found
        .iter()
        .map(|&(i, _)| map.photon(i).power().luminance())
        .sum()
}

/// What the gather rays' share of the light at a point is measured with:
/// the same iteration's global map (read within `global_max`), and the
/// seed's weights. At a diffuse point a caustic photon's `q_1 / q_2 = N L_e
/// DeltaA pi / (Phi alpha m_2)` (the cosines cancel), so the gather rays'
/// weight of its path is `w_2 = 1 / (1 + q_ratio L_e DeltaA)` with
/// `q_ratio = N pi / (Phi alpha m_2)` (aimed photons: `N / Phi` is each
/// photon's own `1 / power`, as in their `q_1`). `w_2` is near 1 for a
/// large dim light seen through glass, 0 for a small bright one and for a
/// delta light (whose `L_e` is infinite), and grows as the discs shrink.
/// A sample keeps the caustic irradiance of lights that are not delta
/// lights over the global irradiance, and `c = q_ratio L_e pi r_0^2`
/// (flux-weighted over its photons).
pub struct Shares<'a> {
    pub global: &'a PhotonMap,
    pub global_max: f32,
    pub q_ratio: f32,
    pub aimed: bool,
}

impl Shares<'_> {
    /// The summed power (luminance) of the caustic photons `found` that
    /// are not from delta lights, and the flux-weighted mean of their
    /// `q_ratio L_e`.
    fn gatherable(&self, map: &PhotonMap, found: &[(u32, f32)]) -> (f32, f32) {
        let (mut flux, mut k_sum) = (0.0f32, 0.0f32);
        for &(i, _) in found {
            let ph = map.photon(i);
            let power = ph.power().luminance();
            if !ph.le().is_finite() || !(power > 0.0) {
                continue;
            }
            let q_ratio = match self.aimed {
                false => self.q_ratio,
                true => self.q_ratio / power,
            };
            flux += power;
            k_sum += power * q_ratio * ph.le();
        }
        (flux, if flux > 0.0 { k_sum / flux } else { 0.0 })
    }
}

/// `caustic / total` irradiance (both over their discs' areas, up to the
/// same factor `pi`) in `[0, 1]`: 1 where the global map saw nothing.
fn caustic_share(caustic: f32, total: f32) -> f32 {
    match (caustic > 0.0, total > 0.0) {
        (false, _) => 0.0,
        (true, false) => 1.0,
        (true, true) => (caustic / total).min(1.0),
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

    /// The grid's nearest sample is the tree's: random photons in clusters
    /// of different densities (no two at the same distance from a query),
    /// queries near them, on the largest radius's edge and far away.
    #[test]
    fn the_grid_finds_the_trees_sample() {
        let mut rng = lumis_math::Pcg32::new(5, 0);
        let mut rnd = || rng.next_f32();
        let mut v = Vec::new();
        for (c, spread, n) in [(0.0, 1.0, 3000), (3.0, 0.05, 500), (-2.0, 4.0, 200)] {
            for _ in 0..n {
                let p = Vec3::new(c + spread * rnd(), c + spread * rnd(), 0.1 * rnd());
                v.push(Photon::new(p, Rgb::WHITE, Vec3::Z, 1.0));
            }
        }
        // Alone (no other within the largest radius), so a query near the
        // largest radius from one has no nearer sample.
        let alone: Vec<Vec3> = (0..50)
            .map(|k| Vec3::new(10.0 + k as f32, 10.0, 0.0))
            .collect();
        v.extend(
            alone
                .iter()
                .map(|&p| Photon::new(p, Rgb::WHITE, Vec3::Z, 1.0)),
        );
        let len = v.len() as u64;
        let map = PhotonMap::build(v, len);
        let tree = RadiusField::from_map(&map, 9, 0.3, false);
        let grid = RadiusField::from_map(&map, 9, 0.3, false).with_grid();
        assert!(grid.grid.is_some() && tree.grid.is_none());
        let (mut found, mut none) = (0, 0);
        for i in 0..20_000 {
            let q = match i % 3 {
                0 => Vec3::new(6.0 * rnd() - 2.5, 6.0 * rnd() - 2.5, 0.4 * rnd() - 0.2),
                // Just inside or outside the largest radius of a photon.
                1 => {
                    let p = match i % 2 {
                        0 => map.photon(i % map.len() as u32).pos(),
                        _ => alone[i as usize % alone.len()],
                    };
                    let d = Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
                    p + d * 0.3 * (0.999 + 0.002 * rnd())
                }
                _ => map.photon(i % map.len() as u32).pos() + 0.01 * Vec3::splat(rnd()),
            };
            let want = tree.nearest(q);
            assert_eq!(grid.nearest(q), want, "at {q}");
            assert_eq!(grid.at(q, 0.5), tree.at(q, 0.5));
            if want.is_some() {
                found += 1;
            } else {
                none += 1;
            }
        }
        assert!(found > 5000 && none > 2000, "{found} {none}");
    }

    #[test]
    fn shares_weigh_caustics_by_the_gather_rays_weight() {
        assert_eq!(caustic_share(0.0, 1.0), 0.0);
        assert_eq!(caustic_share(1.0, 0.0), 1.0);
        assert_eq!(caustic_share(1.0, 4.0), 0.25);
        assert_eq!(caustic_share(8.0, 4.0), 1.0);
        // Caustic and global photons on the same lattice, the caustic ones
        // with twice the power: a caustic share of 1 (clamped); with
        // `q_ratio L_e = 1 / (pi r_0^2)` (`c = 1`), `w_2 = 1 / 2` in the
        // first iteration and 1 / 1.1 at a tenth of its disc.
        let k = 9;
        let lattice = |power: f32, le: f32| {
            let mut v = Vec::new();
            for i in 0..20 {
                for j in 0..20 {
                    let p = Vec3::new(i as f32 * 0.01, j as f32 * 0.01, 0.0);
                    v.push(Photon::new(p, Rgb::splat(power), Vec3::Z, le));
                }
            }
            PhotonMap::build(v, 400)
        };
        let global = lattice(1.0, 1.0);
        let r0_2 = 2e-4; // 9 nearest on the lattice, as above
        let shares = |le: f32| Shares {
            global: &global,
            global_max: 1.0,
            q_ratio: 1.0 / (PI * r0_2 * le),
            aimed: false,
        };
        let caustic = lattice(2.0, 3.0);
        let f = RadiusField::with_shares(&caustic, k, 1.0, false, Some(shares(3.0)));
        let at = Vec3::new(0.1, 0.1, 0.0);
        assert!((f.at(at, 1.0).1 - 0.5).abs() < 1e-3, "{}", f.at(at, 1.0).1);
        assert!((f.at(at, 0.1).1 - 1.0 / 1.1).abs() < 1e-3);
        // Far from every sample, or without shares: none.
        assert_eq!(f.at(Vec3::new(5.0, 0.0, 0.0), 1.0).1, 0.0);
        assert_eq!(
            RadiusField::from_map(&caustic, k, 1.0, false).at(at, 1.0).1,
            0.0
        );
        // A delta light's photons (infinite `L_e`): the gather rays cannot
        // find them.
        let delta = lattice(2.0, f32::INFINITY);
        let f = RadiusField::with_shares(&delta, k, 1.0, false, Some(shares(3.0)));
        assert_eq!(f.at(at, 0.01).1, 0.0);
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
