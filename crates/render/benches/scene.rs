//! `Scene::intersect` / `Scene::occluded` (the interface integrators use) on a
//! bumpy sphere, single thread: the cost of the scene layer over the raw BVH,
//! and a fixed point for comparing backends and the instancing fast path.
//!
//! `cargo bench -p lumis-render --bench scene -- --warm-up-time 1 --measurement-time 5`
//! Set `LUMIS_BENCH_TRIS` to change the mesh size (default 1M).

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use lumis_math::Transform;
use lumis_render::accel::bench::{bumpy_sphere, inward_rays, mesh_bounds, random_rays};
use lumis_render::camera::Camera;
use lumis_render::geometry::Ray;
use lumis_render::scene::Scene;

const N_RAYS: usize = 100_000;

fn bench(c: &mut Criterion) {
    let n = std::env::var("LUMIS_BENCH_TRIS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let mesh = bumpy_sphere(n, 7);
    let bounds = mesh_bounds(&mesh);
    let scene = Scene::grey_mesh(
        mesh,
        vec![],
        Camera::perspective(Transform::IDENTITY, (4, 4), 60.0, 0.0, 1.0),
    );
    let random = random_rays(&bounds, N_RAYS, 1);
    let inward = inward_rays(&bounds, N_RAYS, 2);
    let shadow: Vec<Ray> = random
        .iter()
        .enumerate()
        .map(|(i, r)| Ray {
            tmax: 0.05 + 2.0 * (i % 97) as f32 / 97.0,
            ..*r
        })
        .collect();
    let mut g = c.benchmark_group("scene");
    g.sample_size(10);
    g.throughput(Throughput::Elements(N_RAYS as u64));
    let closest = |rays: &[Ray]| {
        rays.iter()
            .filter_map(|r| scene.intersect(r))
            .map(|h| h.t)
            .sum::<f32>()
    };
    g.bench_function("intersect_random", |b| {
        b.iter(|| closest(black_box(&random)))
    });
    g.bench_function("intersect_inward", |b| {
        b.iter(|| closest(black_box(&inward)))
    });
    g.bench_function("occluded_random", |b| {
        b.iter(|| {
            black_box(&shadow)
                .iter()
                .filter(|r| scene.occluded(r))
                .count()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
