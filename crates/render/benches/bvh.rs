//! BVH benchmark on a ~1M-triangle bumpy sphere (single-thread traversal).
//!
//! `cargo bench -p lumis-render --bench bvh -- --warm-up-time 1 --measurement-time 5`
//! Set `LUMIS_BENCH_TRIS` to change the mesh size.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use lumis_render::accel::bench::{bumpy_sphere, inward_rays, mesh_bounds, random_rays, MeshAccel};
use lumis_render::accel::Bvh;
use lumis_render::geometry::{Aabb, Ray};
use std::time::Instant;

const N_RAYS: usize = 100_000;

fn n_tris() -> usize {
    std::env::var("LUMIS_BENCH_TRIS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000)
}

fn bench(c: &mut Criterion) {
    let mesh = bumpy_sphere(n_tris(), 7);
    let bounds = mesh_bounds(&mesh);
    let t0 = Instant::now();
    let accel = MeshAccel::new(&mesh);
    eprintln!(
        "bumpy sphere: {} triangles, first build {:.3} s ({} rayon threads), BVH {} nodes, {:.1} MB (+ leaf-ordered vertices: {:.1} MB total)",
        mesh.triangle_count(),
        t0.elapsed().as_secs_f64(),
        rayon::current_num_threads(),
        accel.bvh.nodes.len(),
        accel.bvh.memory_bytes() as f64 / 1e6,
        accel.memory_bytes() as f64 / 1e6,
    );
    let random = random_rays(&bounds, N_RAYS, 1);
    let inward = inward_rays(&bounds, N_RAYS, 2);
    for (name, rays) in [("random", &random), ("inward", &inward)] {
        let hits = rays.iter().filter(|r| accel.closest(r).is_some()).count();
        eprintln!(
            "{name}: {:.1}% of rays hit",
            100.0 * hits as f64 / rays.len() as f64
        );
    }

    let mut g = c.benchmark_group("bvh");
    g.sample_size(10);
    g.throughput(Throughput::Elements(mesh.triangle_count() as u64));
    g.bench_function("build_1M_parallel", |b| {
        let boxes: Vec<Aabb> = (0..mesh.triangle_count() as u32)
            .map(|t| mesh.bounds(t))
            .collect();
        b.iter(|| Bvh::build(black_box(&boxes)))
    });
    g.throughput(Throughput::Elements(N_RAYS as u64));
    let closest = |rays: &[Ray]| {
        let mut acc = 0.0f32;
        for r in rays {
            if let Some((t, _)) = accel.closest(r) {
                acc += t;
            }
        }
        acc
    };
    g.bench_function("closest_random", |b| b.iter(|| closest(black_box(&random))));
    g.bench_function("closest_inward", |b| b.iter(|| closest(black_box(&inward))));
    // Any-hit with a finite tmax so both occluded and unoccluded rays occur.
    let shadow: Vec<Ray> = random
        .iter()
        .enumerate()
        .map(|(i, r)| Ray {
            tmax: 0.05 + 2.0 * (i % 97) as f32 / 97.0,
            ..*r
        })
        .collect();
    g.bench_function("any_random", |b| {
        b.iter(|| black_box(&shadow).iter().filter(|r| accel.any(r)).count())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
