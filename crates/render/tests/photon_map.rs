//! Photon map: encoding round trips, k-nearest and fixed-radius queries
//! against brute force, and irradiance estimates on a uniformly lit plane.

use lumis_math::sampling::{square_to_cosine_hemisphere, square_to_uniform_sphere};
use lumis_math::{Pcg32, Rgb, Vec2, Vec3};
use lumis_render::integrator::photon::map::{irradiance_knn, PhotonMap};
use lumis_render::integrator::photon::photon::Photon;
use lumis_render::integrator::photon::radiance::RadiancePhotons;
use std::f32::consts::FRAC_1_SQRT_2;

fn u2(rng: &mut Pcg32) -> Vec2 {
    Vec2::new(rng.next_f32(), rng.next_f32())
}

fn v3(rng: &mut Pcg32) -> Vec3 {
    Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32())
}

fn angle_deg(a: Vec3, b: Vec3) -> f64 {
    let (a, b) = (a.as_dvec3(), b.as_dvec3().normalize());
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

#[test]
fn photon_encoding_round_trips() {
    assert!(std::mem::size_of::<Photon>() <= 24);
    let mut rng = Pcg32::new(1, 0);
    let mut dirs = vec![Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z];
    dirs.push(Vec3::new(1.0, 1.0, 1.0).normalize());
    dirs.push(Vec3::new(-1.0, 1.0, -1.0).normalize());
    dirs.push(Vec3::new(1e-4, -1e-4, -1.0).normalize());
    dirs.push(Vec3::new(FRAC_1_SQRT_2, 0.0, -FRAC_1_SQRT_2));
    dirs.extend((0..100_000).map(|_| square_to_uniform_sphere(u2(&mut rng))));
    let mut worst_dir = 0.0f64;
    let mut worst_power = 0.0f64;
    for d in dirs {
        let power = Rgb::new(
            10f32.powf(rng.next_f32() * 12.0 - 6.0),
            10f32.powf(rng.next_f32() * 12.0 - 6.0),
            10f32.powf(rng.next_f32() * 12.0 - 6.0),
        );
        let le = 10f32.powf(rng.next_f32() * 12.0 - 6.0);
        let pos = (v3(&mut rng) - 0.5) * 1e3;
        let ph = Photon::new(pos, power, d, le);
        assert_eq!(ph.pos(), pos);
        let (p, e) = (ph.power().to_array(), power.to_array());
        for c in 0..3 {
            worst_power = worst_power.max(((p[c] - e[c]) / e[c]).abs() as f64);
        }
        assert!(((ph.le() - le) / le).abs() < 1e-3, "le {le} -> {}", ph.le());
        assert!((ph.dir().length() - 1.0).abs() < 1e-6);
        worst_dir = worst_dir.max(angle_deg(ph.dir(), d));
    }
    assert!(worst_power < 1e-3, "power relative error {worst_power}");
    assert!(worst_dir < 0.01, "direction error {worst_dir} degrees");
    let ph = Photon::new(Vec3::ZERO, Rgb::new(1.0, 0.0, 1e-3), Vec3::Z, f32::INFINITY);
    assert_eq!(ph.le(), f32::INFINITY);
    assert_eq!(ph.power().g, 0.0);
}

fn point_set(kind: usize, n: usize, rng: &mut Pcg32) -> Vec<Vec3> {
    let centers: Vec<Vec3> = (0..5).map(|_| v3(rng)).collect();
    (0..n)
        .map(|i| match kind {
            0 => v3(rng),
            1 => centers[i % 5] + (v3(rng) - 0.5) * 0.02,
            // duplicates: few distinct points, repeated
            2 => {
                let mut r = Pcg32::new((i % 7) as u64, 9);
                v3(&mut r)
            }
            _ => Vec3::new(rng.next_f32(), rng.next_f32(), 0.25),
        })
        .collect()
}

fn map_of(points: &[Vec3]) -> PhotonMap {
    let photons = points
        .iter()
        .map(|&p| Photon::new(p, Rgb::WHITE, Vec3::Z, 1.0))
        .collect();
    PhotonMap::build(photons, points.len() as u64)
}

/// Squared distance exactly as the tree computes it.
fn d2(p: Vec3, q: Vec3) -> f32 {
    let (dx, dy, dz) = (p.x - q.x, p.y - q.y, p.z - q.z);
    dx * dx + dy * dy + dz * dz
}

#[test]
fn queries_match_brute_force() {
    let mut rng = Pcg32::new(7, 3);
    let mut out = Vec::new();
    for &n in &[0usize, 1, 5, 13, 100, 1000, 20_000] {
        for kind in 0..4 {
            let points = point_set(kind, n, &mut rng);
            let map = map_of(&points);
            assert_eq!(map.len(), n);
            // Stored in the tree's order: check the map back, then use it.
            let mut seen = vec![false; n];
            for i in 0..n as u32 {
                let o = map.original_index(i) as usize;
                assert!(!seen[o] && points[o] == map.photon(i).pos());
                seen[o] = true;
            }
            let points: Vec<Vec3> = map.photons().iter().map(Photon::pos).collect();
            for _ in 0..200 {
                let pick = rng.next_f32();
                let q = if n > 0 && pick < 0.4 {
                    points[rng.next_below(n as u32) as usize]
                } else if n > 0 && pick < 0.7 {
                    // A point moved along one axis: queries just off a
                    // point set's surface (its plane, its clusters, its box).
                    let mut a = points[rng.next_below(n as u32) as usize].to_array();
                    a[rng.next_below(3) as usize] += 0.6 * rng.next_f32() - 0.3;
                    Vec3::from_array(a)
                } else {
                    v3(&mut rng) * 1.2 - 0.1
                };
                let mut all: Vec<(u32, f32)> = (0..n as u32)
                    .map(|i| (i, d2(points[i as usize], q)))
                    .collect();
                all.sort_by(|a, b| a.1.total_cmp(&b.1));
                let k = 1 + rng.next_below(100) as usize;
                let max_r = if rng.next_f32() < 0.3 {
                    10.0
                } else {
                    0.3 * rng.next_f32()
                };
                let r2 = map.knn(q, k, max_r, &mut out);
                let expect: Vec<f32> = all
                    .iter()
                    .map(|e| e.1)
                    .filter(|&d| d <= max_r * max_r)
                    .take(k)
                    .collect();
                let mut got: Vec<f32> = out.iter().map(|e| e.1).collect();
                got.sort_by(f32::total_cmp);
                assert_eq!(got, expect, "knn n {n} kind {kind} k {k} r {max_r}");
                for &(i, d) in &out {
                    assert_eq!(d, d2(points[i as usize], q));
                }
                let mut ids: Vec<u32> = out.iter().map(|e| e.0).collect();
                ids.sort_unstable();
                ids.dedup();
                assert_eq!(ids.len(), out.len(), "duplicate indices");
                if out.len() == k {
                    assert_eq!(r2, *expect.last().unwrap());
                } else {
                    assert_eq!(r2, max_r * max_r);
                }
                let radius = 0.2 * rng.next_f32();
                map.within(q, radius, &mut out);
                let mut got: Vec<u32> = out.iter().map(|e| e.0).collect();
                got.sort_unstable();
                let mut expect: Vec<u32> = all
                    .iter()
                    .filter(|e| e.1 <= radius * radius)
                    .map(|e| e.0)
                    .collect();
                expect.sort_unstable();
                assert_eq!(got, expect, "within n {n} kind {kind} r {radius}");
            }
        }
    }
}

#[test]
fn empty_map_and_large_k() {
    let map = PhotonMap::build(Vec::new(), 10);
    assert!(map.is_empty() && map.emitted() == 10);
    let mut out = vec![(1, 1.0)];
    assert_eq!(map.knn(Vec3::ZERO, 5, 2.0, &mut out), 4.0);
    assert!(out.is_empty());
    map.within(Vec3::ZERO, 1e9, &mut out);
    assert!(out.is_empty());
    let (e, r2) = irradiance_knn(&map, Vec3::ZERO, Vec3::Z, 5, 1.0, &mut out);
    assert!(e.is_black() && r2 == 1.0);
    let rp = RadiancePhotons::build(&map, &[], 4, 50, 1.0);
    assert_eq!(rp.len(), 0);
    assert!(rp.irradiance(Vec3::ZERO, Vec3::Z, 1.0).is_none());

    let mut rng = Pcg32::new(3, 3);
    let points = point_set(0, 30, &mut rng);
    let map = map_of(&points);
    assert_eq!(map.knn(Vec3::ZERO, 100, 5.0, &mut out), 25.0);
    assert_eq!(out.len(), 30);
    assert_eq!(map.knn(Vec3::ZERO, 0, 5.0, &mut out), 25.0);
    assert!(out.is_empty());
}

const N: usize = 200_000;
const K: usize = 50;

/// Photons uniform on the unit square at z = 0 lit from above with total
/// power `phi` (area 1: E = phi), and optionally a back-facing plane 1e-4
/// below lit from underneath with ten times the power. Returns photons and normals.
fn lit_planes(phi: Rgb, back: bool) -> (PhotonMap, Vec<Vec3>) {
    let mut rng = Pcg32::new(11, 5);
    let mut photons = Vec::new();
    let mut normals = Vec::new();
    for i in 0..N * (1 + back as usize) {
        let front = i < N;
        let (z, s) = if front { (0.0, 1.0) } else { (-1e-4, -1.0) };
        let p = Vec3::new(rng.next_f32(), rng.next_f32(), z);
        let d = square_to_cosine_hemisphere(u2(&mut rng)) * Vec3::new(1.0, 1.0, s);
        let power = if front {
            phi / N as f32
        } else {
            phi * 10.0 / N as f32
        };
        photons.push(Photon::new(p, power, d, 1.0));
        normals.push(Vec3::new(0.0, 0.0, s));
    }
    (PhotonMap::build(photons, N as u64), normals)
}

/// Query points on a grid well inside the square (more than r from its edges).
fn queries() -> Vec<Vec3> {
    (0..400)
        .map(|i| {
            Vec3::new(
                0.1 + 0.04 * (i % 20) as f32,
                0.1 + 0.04 * (i / 20) as f32,
                0.0,
            )
        })
        .collect()
}

/// Mean over the queries of `E / expected`; each within 6 sd, the mean within
/// 4 sd of the known bias K / (K - 1) of `k / (pi r_K^2)`. `k_eff`: photons
/// counted on average (K / 2 when half of the K nearest face away).
fn check_estimates(ratios: &[Rgb], k_eff: f32) {
    let sd = 1.0 / (k_eff - 2.0).sqrt();
    let mut mean = Rgb::BLACK;
    for r in ratios {
        assert!((r.g - 1.0).abs() < 6.0 * sd, "ratio {r:?}");
        assert!(
            (r.r - r.g).abs() < 1e-2 && (r.b - r.g).abs() < 1e-2,
            "colour {r:?}"
        );
        mean += *r / ratios.len() as f32;
    }
    let bias = K as f32 / (K as f32 - 1.0);
    let tol = 4.0 * sd / (ratios.len() as f32).sqrt();
    assert!(
        (mean.g - bias).abs() < tol,
        "mean ratio {mean:?}, bias {bias}, tol {tol}"
    );
}

#[test]
fn irradiance_of_uniformly_lit_plane() {
    let phi = Rgb::new(3.0, 1.5, 0.75);
    let mut scratch = Vec::new();
    for back in [false, true] {
        let (map, normals) = lit_planes(phi, back);
        let ratios: Vec<Rgb> = queries()
            .iter()
            .map(|&q| irradiance_knn(&map, q, Vec3::Z, K, 0.1, &mut scratch).0 / phi)
            .collect();
        // With the back plane, about half of the k nearest face away.
        check_estimates(&ratios, if back { K as f32 / 2.0 } else { K as f32 });

        let rp = RadiancePhotons::build(&map, &normals, 4, K, 0.1);
        assert_eq!(rp.len(), map.len().div_ceil(4));
        assert!(rp.memory_bytes() > 0);
        let mut ratios = Vec::new();
        for &q in &queries() {
            let e = rp
                .irradiance(q, Vec3::Z, 0.05)
                .expect("a radiance photon nearby");
            ratios.push(e / phi);
            assert!(rp.irradiance(q, Vec3::X, 0.05).is_none());
            assert!(rp.irradiance(q + Vec3::Z * 0.2, Vec3::Z, 0.05).is_none());
            if back {
                let e = rp.irradiance(q, -Vec3::Z, 0.05).unwrap() / (phi * 10.0);
                assert!(
                    (e.g - 1.0).abs() < 6.0 / (K as f32 / 2.0 - 2.0).sqrt(),
                    "back {e:?}"
                );
            }
        }
        // Lookups are of single estimates, each made from k photons of one side.
        check_estimates(&ratios, if back { K as f32 / 2.0 } else { K as f32 });
    }
}

#[test]
fn radiance_photons_are_deterministic() {
    let (map, normals) = lit_planes(Rgb::WHITE, true);
    let a = RadiancePhotons::build(&map, &normals, 3, 20, 0.1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let b = pool.install(|| RadiancePhotons::build(&map, &normals, 3, 20, 0.1));
    for q in queries() {
        for n in [Vec3::Z, -Vec3::Z] {
            let (ea, eb) = (a.irradiance(q, n, 0.05), b.irradiance(q, n, 0.05));
            assert_eq!(ea.map(|e| e.to_array()), eb.map(|e| e.to_array()));
        }
    }
}
