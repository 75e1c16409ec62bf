//! `lumis bench`: the figures the README quotes, measured on this machine.
//! Medians of repeated runs; single-thread where a per-thread rate is quoted.

use crate::args::BenchArgs;
use crate::measure::{peak_memory_mib, single_thread, time_it};
use anyhow::Result;
use lumis_math::Vec3;
use lumis_render::accel::bench::{bumpy_sphere, inward_rays, mesh_bounds, random_rays, MeshAccel};
use lumis_render::integrator::photon::aim::Aims;
use lumis_render::integrator::photon::map::PhotonMap;
use lumis_render::integrator::photon::PhotonMaps;
use lumis_render::integrator::{render, RenderOutcome};
use lumis_render::load::{load_text, LoadedScene, Overrides, DEFAULT_SCENE};
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// A whole render on all threads, seed 0, no progress display.
fn render_all(l: &LoadedScene, spp: u32) -> RenderOutcome {
    let settings = l.options.render_settings(spp, 0, 0);
    render(
        &l.scene,
        &l.options.integrator,
        &settings,
        &|_| {},
        &AtomicBool::new(false),
    )
}

pub fn run(a: BenchArgs) -> Result<()> {
    let reps = if a.quick { 3 } else { 7 };
    let tris = if a.quick { 100_000 } else { 1_000_000 };
    let threads = rayon::current_num_threads();
    outln!(
        "lumis bench ({} threads available; medians of {reps} runs)",
        threads
    );

    // Ray tracing.
    let mesh = bumpy_sphere(tris, 1);
    let accel = MeshAccel::new(&mesh);
    let b = mesh_bounds(&mesh);
    let n_rays = 100_000;
    let (random, inward) = (random_rays(&b, n_rays, 1), inward_rays(&b, n_rays, 2));
    // Shadow rays: finite lengths, so both blocked and unblocked rays occur.
    let shadow: Vec<_> = random
        .iter()
        .enumerate()
        .map(|(i, r)| lumis_render::geometry::Ray {
            tmax: 0.05 + 2.0 * (i % 97) as f32 / 97.0,
            ..*r
        })
        .collect();
    let rate = |rays: &[lumis_render::geometry::Ray], any: bool| {
        let s = single_thread(|| {
            time_it(reps, || {
                for r in rays {
                    if any {
                        std::hint::black_box(accel.any(r));
                    } else {
                        std::hint::black_box(accel.closest(r));
                    }
                }
            })
        });
        rays.len() as f64 / s / 1e6
    };
    let (r_random, r_inward, r_any) = (
        rate(&random, false),
        rate(&inward, false),
        rate(&shadow, true),
    );
    let memory = accel.memory_bytes();
    drop(accel);
    let build = time_it(reps, || {
        std::hint::black_box(MeshAccel::new(&mesh));
    });
    outln!(
        "| BVH build, {} triangles ({threads} threads) | {:.0} ms |",
        mesh.triangle_count(),
        build * 1e3
    );
    outln!(
        "| BVH memory (nodes + leaf-ordered triangles) | {:.1} MiB |",
        memory as f64 / (1u64 << 20) as f64
    );
    outln!("| closest hit, random rays, 1 thread | {r_random:.2} Mrays/s |");
    outln!("| closest hit, rays aimed inward, 1 thread | {r_inward:.2} Mrays/s |");
    outln!("| any hit, random shadow rays, 1 thread | {r_any:.2} Mrays/s |");
    #[cfg(feature = "embree")]
    embree_rates(
        &mesh,
        reps,
        [(&random, r_random), (&inward, r_inward), (&shadow, r_any)],
    );

    // Path tracing the default scene.
    let res = if a.quick { 128 } else { 512 };
    let mut ov = Overrides::default();
    ov.resolution(res, res).integrator("path");
    let l = load_text(DEFAULT_SCENE, "<default>", Path::new("."), &ov)
        .map_err(|d| anyhow::anyhow!("{d}"))?;
    let spp = 4;
    let out = render_all(&l, spp);
    let secs = out.elapsed.as_secs_f64();
    outln!(
        "| path, default scene {res}x{res}, {spp} spp ({threads} threads) | {:.2} Msamples/s, {:.2} Mrays/s, {:.2} s |",
        (res * res * spp) as f64 / secs / 1e6,
        out.rays as f64 / secs / 1e6,
        secs
    );

    // Photon mapping on the default scene.
    let mut ov = Overrides::default();
    ov.integrator("photon");
    if a.quick {
        ov.resolution(128, 128);
    }
    let l = load_text(DEFAULT_SCENE, "<default>", Path::new("."), &ov)
        .map_err(|d| anyhow::anyhow!("{d}"))?;
    let ps = l.options.integrator.photon().expect("photon");
    let never = std::sync::atomic::AtomicBool::new(false);
    let aims = Aims::new(&l.scene, ps.aim_caustics);
    let maps = PhotonMaps::build(&l.scene, ps, 0, None, &aims, &never).expect("not cancelled");
    let emitted = (ps.global_photons + ps.caustic_photons) as f64;
    let st = &maps.stats;
    outln!(
        "| photon tracing, default scene ({threads} threads) | {:.2} M photons emitted/s ({} global + {} caustic stored) |",
        emitted / st.trace_time.as_secs_f64() / 1e6,
        st.global_stored,
        st.caustic_stored
    );
    outln!(
        "| photon map build (global + caustic) | {:.0} ms |",
        st.build_time.as_secs_f64() * 1e3
    );
    outln!(
        "| radiance photons precompute | {:.0} ms |",
        st.radiance_time.as_secs_f64() * 1e3
    );
    outln!(
        "| photon maps memory | {:.1} MiB |",
        st.memory_bytes as f64 / (1u64 << 20) as f64
    );

    // k-NN queries among 1M photons (uniform in a unit cube), k = 50, 1 thread.
    let n = if a.quick { 100_000 } else { 1_000_000 };
    let mut rng = lumis_math::Pcg32::new(3, 3);
    let photons: Vec<_> = (0..n)
        .map(|_| {
            let p = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            lumis_render::integrator::photon::photon::Photon::new(
                p,
                lumis_math::Rgb::splat(1e-6),
                Vec3::Z,
                1.0,
            )
        })
        .collect();
    let map_build = time_it(reps, || {
        std::hint::black_box(PhotonMap::build(photons.clone(), n as u64));
    });
    let map = PhotonMap::build(photons, n as u64);
    let queries: Vec<Vec3> = (0..20_000)
        .map(|_| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()))
        .collect();
    let knn = single_thread(|| {
        let mut out = Vec::new();
        time_it(reps, || {
            for q in &queries {
                std::hint::black_box(map.knn(*q, 50, 1.0, &mut out));
            }
        })
    });
    outln!(
        "| photon map build, {n} photons | {:.0} ms |",
        map_build * 1e3
    );
    outln!(
        "| k-NN query, k = 50 among {n} photons, 1 thread | {:.2} µs/query ({:.0} k queries/s) |",
        knn / queries.len() as f64 * 1e6,
        queries.len() as f64 / knn / 1e3
    );
    drop(map);

    let out = render_all(&l, l.options.spp);
    let (w, h) = (out.film.width(), out.film.height());
    outln!(
        "| photon, default scene as shipped: {w}x{h}, {} spp ({threads} threads) | {:.1} s (incl. photon pass) |",
        out.spp,
        out.elapsed.as_secs_f64()
    );
    if let Some(m) = peak_memory_mib() {
        outln!("| peak memory of this run (VmHWM) | {m:.0} MiB |");
    }
    Ok(())
}

/// The same rays through Embree 3 (feature `embree`), with the ratio to the
/// built-in BVH's rates (`lumis / Embree`; above 1: lumis is faster).
#[cfg(feature = "embree")]
fn embree_rates(
    mesh: &lumis_render::geometry::TriangleMesh,
    reps: usize,
    sets: [(&[lumis_render::geometry::Ray], f64); 3],
) {
    use lumis_render::accel::embree::EmbreeMesh;
    let build = time_it(reps, || {
        std::hint::black_box(EmbreeMesh::new(mesh));
    });
    let em = EmbreeMesh::new(mesh);
    outln!("| Embree 3 build, same mesh | {:.0} ms |", build * 1e3);
    let labels = [
        "closest hit, random rays",
        "closest hit, rays aimed inward",
        "any hit, random shadow rays",
    ];
    for (k, (rays, lumis_rate)) in sets.into_iter().enumerate() {
        let any = k == 2;
        let s = single_thread(|| {
            time_it(reps, || {
                for r in rays {
                    if any {
                        std::hint::black_box(em.any(r));
                    } else {
                        std::hint::black_box(em.closest(r));
                    }
                }
            })
        });
        let rate = rays.len() as f64 / s / 1e6;
        outln!(
            "| Embree 3 {}, 1 thread | {rate:.2} Mrays/s (lumis/Embree {:.2}) |",
            labels[k],
            lumis_rate / rate
        );
    }
}
