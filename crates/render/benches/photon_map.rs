//! Photon map benchmark: 1M photons uniform in a unit cube, and clustered on
//! the walls of a box plus two tilted panels (non-uniform density). Build
//! and queries single-thread; radiance-photon precompute with rayon.
//!
//! `cargo bench -p lumis-render --bench photon_map -- --warm-up-time 1 --measurement-time 5`
//! Set `LUMIS_BENCH_PHOTONS` to change the photon count. Query benches run
//! `QUERIES` queries per iteration: time / QUERIES is the time per query.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use lumis_math::sampling::square_to_cosine_hemisphere;
use lumis_math::{Frame, Pcg32, Rgb, Vec2, Vec3, PI};
use lumis_render::integrator::photon::map::{irradiance_knn, PhotonMap};
use lumis_render::integrator::photon::photon::Photon;
use lumis_render::integrator::photon::radiance::RadiancePhotons;
use std::time::Instant;

const QUERIES: usize = 10_000;
const K: usize = 50;

fn n_photons() -> usize {
    std::env::var("LUMIS_BENCH_PHOTONS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000)
}

fn u2(rng: &mut Pcg32) -> Vec2 {
    Vec2::new(rng.next_f32(), rng.next_f32())
}

/// Surfaces as (corner, edge u, edge v, relative photon density).
fn surfaces() -> Vec<(Vec3, Vec3, Vec3, f32)> {
    let (o, x, y, z) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z);
    let tilt = Vec3::new(0.0, 0.3, 0.3);
    vec![
        (o, x, z, 4.0), // floor, brightest
        (y, z, x, 1.0), // ceiling
        (o, z, y, 1.0),
        (x, y, z, 1.0),
        (z, y, x, 1.0),
        (o, x, y, 0.5),
        (Vec3::new(0.2, 0.1, 0.2), x * 0.3, tilt, 2.0),
        (Vec3::new(0.5, 0.2, 0.6), z * 0.3, tilt, 2.0),
    ]
}

/// Photons and their surface normals; second value: surface area in total.
fn scene(kind: &str, n: usize, seed: u64) -> (Vec<Photon>, Vec<Vec3>, f32) {
    let mut rng = Pcg32::new(seed, 1);
    let surf = surfaces();
    let total: f32 = surf.iter().map(|s| s.3).sum();
    let area: f32 = surf.iter().map(|s| s.1.cross(s.2).length()).sum();
    let mut photons = Vec::with_capacity(n);
    let mut normals = Vec::with_capacity(n);
    for _ in 0..n {
        let (p, nrm) = if kind == "cube" {
            let p = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            (p, Vec3::Z)
        } else {
            let mut t = rng.next_f32() * total;
            let s = surf.iter().find(|s| {
                t -= s.3;
                t < 0.0
            });
            let (c, a, b, _) = *s.unwrap_or(&surf[0]);
            let p = c + a * rng.next_f32() + b * rng.next_f32();
            (p, a.cross(b).normalize())
        };
        let d = Frame::from_normal(nrm).to_world(square_to_cosine_hemisphere(u2(&mut rng)));
        photons.push(Photon::new(p, Rgb::splat(1.0 / n as f32), d, 1.0));
        normals.push(nrm);
    }
    (photons, normals, area)
}

fn bench(c: &mut Criterion) {
    let n = n_photons();
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for kind in ["cube", "surfaces"] {
        let (photons, normals, area) = scene(kind, n, 1);
        let (queries, qnormals, _) = scene(kind, QUERIES, 2);
        let queries: Vec<Vec3> = queries.iter().map(Photon::pos).collect();
        // Radius holding about K photons on average.
        let radius = if kind == "cube" {
            (3.0 * K as f32 / (4.0 * PI * n as f32)).cbrt()
        } else {
            (K as f32 * area / (PI * n as f32)).sqrt()
        };
        let t0 = Instant::now();
        let map = single.install(|| PhotonMap::build(photons.clone(), n as u64));
        let mut out = Vec::new();
        let found: usize = queries
            .iter()
            .map(|&q| {
                map.within(q, radius, &mut out);
                out.len()
            })
            .sum();
        eprintln!(
            "{kind}: {n} photons, first build {:.3} s single-thread, {:.1} MB; radius {radius:.4} holds {:.1} photons on average",
            t0.elapsed().as_secs_f64(),
            map.memory_bytes() as f64 / 1e6,
            found as f64 / QUERIES as f64
        );

        let mut g = c.benchmark_group(format!("photon_map_{kind}"));
        g.sample_size(10);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function("build_1t", |b| {
            b.iter(|| single.install(|| PhotonMap::build(black_box(photons.clone()), n as u64)))
        });
        g.bench_function("build_rayon", |b| {
            b.iter(|| PhotonMap::build(black_box(photons.clone()), n as u64))
        });
        g.throughput(Throughput::Elements(QUERIES as u64));
        g.bench_function("knn50", |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for &q in black_box(&queries) {
                    acc += map.knn(q, K, 1.0, &mut out);
                }
                acc
            })
        });
        g.bench_function("within", |b| {
            b.iter(|| {
                let mut acc = 0;
                for &q in black_box(&queries) {
                    map.within(q, radius, &mut out);
                    acc += out.len();
                }
                acc
            })
        });
        g.bench_function("irradiance_knn50", |b| {
            b.iter(|| {
                let mut acc = Rgb::BLACK;
                for (&q, &nq) in black_box(&queries).iter().zip(&qnormals) {
                    acc += irradiance_knn(&map, q, nq, K, 1.0, &mut out).0;
                }
                acc
            })
        });
        g.throughput(Throughput::Elements(n.div_ceil(4) as u64));
        g.bench_function("radiance_build_rayon", |b| {
            b.iter(|| RadiancePhotons::build(&map, &normals, 4, K, 4.0 * radius))
        });
        let rp = RadiancePhotons::build(&map, &normals, 4, K, 4.0 * radius);
        let hits = queries
            .iter()
            .zip(&qnormals)
            .filter(|(&q, &nq)| rp.irradiance(q, nq, 2.0 * radius).is_some())
            .count();
        eprintln!(
            "{kind}: {} radiance photons, {:.1} MB; {:.1}% of lookups found one",
            rp.len(),
            rp.memory_bytes() as f64 / 1e6,
            100.0 * hits as f64 / QUERIES as f64
        );
        g.throughput(Throughput::Elements(QUERIES as u64));
        g.bench_function("radiance_lookup", |b| {
            b.iter(|| {
                let mut acc = Rgb::BLACK;
                for (&q, &nq) in black_box(&queries).iter().zip(&qnormals) {
                    acc += rp.irradiance(q, nq, 2.0 * radius).unwrap_or_default();
                }
                acc
            })
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
