//! `lumis bench --scaling`: how cost grows with scene size and photon count,
//! and what the second thread buys. Prints Markdown tables and writes
//! log-log SVG plots (with fitted slopes) into a folder.

use crate::args::BenchArgs;
use crate::measure::{peak_memory_mib, single_thread, time_it};
use anyhow::{Context, Result};
use lumis_math::SamplerKind;
use lumis_math::{Rgb, Transform, Vec3};
use lumis_render::accel::bench::{bumpy_sphere, MeshAccel};
use lumis_render::camera::Camera;
use lumis_render::film::{Filter, PixelBounds};
use lumis_render::geometry::TriangleMesh;
use lumis_render::integrator::photon::map::PhotonMap;
use lumis_render::integrator::photon::photon::Photon;
use lumis_render::integrator::{render, Integrator, RenderOutcome, RenderSettings};
use lumis_render::light::{Light, UniformInfiniteLight};
use lumis_render::load::{load_text, Overrides, DEFAULT_SCENE};
use lumis_render::scene::Scene;
use lumis_render::study::fit::log_log;
use lumis_render::study::plot::{svg_xy, Series, COLOURS};
use std::path::Path;
use std::sync::atomic::AtomicBool;

const MIB: f64 = (1u64 << 20) as f64;

pub fn run(a: &BenchArgs) -> Result<()> {
    let dir = a
        .plots
        .clone()
        .unwrap_or_else(|| "lumis-bench-scaling".into());
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    let threads = rayon::current_num_threads();
    outln!("lumis bench --scaling ({threads} threads available)");
    triangles(a.quick, threads, &dir)?;
    photons(a.quick, &dir)?;
    speedup(a.quick)?;
    if let Some(m) = peak_memory_mib() {
        outln!("\npeak memory of this run (VmHWM): {m:.0} MiB");
    }
    outln!("plots in {}", dir.display());
    Ok(())
}

/// A diffuse bumpy sphere of `n` triangles under a uniform sky, seen from 3
/// units away: a scene whose cost is the mesh.
fn mesh_scene(mesh: TriangleMesh, res: u32) -> Scene {
    let sky = Light::Infinite(UniformInfiniteLight {
        l: Rgb::splat(1.0),
        scene_center: Vec3::ZERO,
        scene_radius: 1.0,
    });
    let at = Transform::new(lumis_math::Mat4::from_translation(Vec3::new(
        0.0, 0.0, -3.0,
    )))
    .expect("a translation inverts");
    Scene::grey_mesh(
        mesh,
        vec![sky],
        Camera::perspective(at, (res, res), 45.0, 0.0, 1.0),
    )
}

fn render_path(scene: &Scene, res: u32, spp: u32, threads: usize) -> RenderOutcome {
    let settings = RenderSettings {
        spp,
        seed: 1,
        threads,
        time_limit: None,
        sampler: SamplerKind::Sobol,
        filter: Filter::boxf(lumis_math::Vec2::splat(0.5)),
        crop: PixelBounds {
            x0: 0,
            x1: res,
            y0: 0,
            y1: res,
        },
        spp_per_pass: 1,
        clamp: None,
        inject_nan: None,
        passes: None,
    };
    let path = Integrator::Path { max_depth: 5 };
    render(scene, &path, &settings, &|_| {}, &AtomicBool::new(false))
}

/// One series of a plot, a point per size, with its log-log slope.
fn series(name: &str, k: usize, points: &[(f64, f64)]) -> Series {
    Series {
        name: name.to_string(),
        colour: COLOURS[k % COLOURS.len()],
        groups: points.iter().map(|&p| vec![p]).collect(),
        fit: log_log(points),
    }
}

fn write_plot(dir: &Path, file: &str, svg: String) -> Result<()> {
    let p = dir.join(file);
    std::fs::write(&p, svg).with_context(|| format!("writing {}", p.display()))
}

fn slope(points: &[(f64, f64)]) -> String {
    log_log(points).map_or("-".into(), |l| format!("{:.2}", l.slope))
}

/// BVH build, Embree build, memory and a path render against triangles.
fn triangles(quick: bool, threads: usize, dir: &Path) -> Result<()> {
    let sizes: &[usize] = if quick {
        &[10_000, 100_000, 1_000_000]
    } else {
        &[10_000, 100_000, 1_000_000, 10_000_000]
    };
    let (res, spp) = if quick { (256, 4) } else { (512, 8) };
    outln!(
        "\n| triangles | BVH build ({threads} threads) | Embree 3 build | BVH + mesh memory | path {res}x{res} {spp} spp ({threads} threads) | Mrays/s |"
    );
    outln!("| --- | --- | --- | --- | --- | --- |");
    let (mut build, mut embree, mut memory, mut render_s) = (vec![], vec![], vec![], vec![]);
    for &n in sizes {
        let mesh = bumpy_sphere(n, 1);
        let tris = mesh.triangle_count() as f64;
        let reps = if n >= 5_000_000 { 1 } else { 3 };
        let b = time_it(reps, || {
            std::hint::black_box(MeshAccel::new(&mesh));
        });
        let e = embree_build(&mesh, reps);
        let scene = mesh_scene(mesh, res);
        let mem = scene.geometry_memory_bytes() as f64 / MIB;
        let out = render_path(&scene, res, spp, 0);
        let secs = out.elapsed.as_secs_f64();
        outln!(
            "| {} | {:.3} s | {} | {mem:.1} MiB | {secs:.2} s | {:.2} |",
            tris as u64,
            b,
            e.map_or("-".into(), |e| format!("{e:.3} s")),
            out.rays as f64 / secs / 1e6
        );
        build.push((tris, b));
        if let Some(e) = e {
            embree.push((tris, e));
        }
        memory.push((tris, mem));
        render_s.push((tris, secs));
    }
    outln!(
        "\nlog-log slopes: BVH build {}, Embree build {}, memory {}, render {}",
        slope(&build),
        slope(&embree),
        slope(&memory),
        slope(&render_s)
    );
    let mut time_series = vec![series("lumis BVH build", 0, &build)];
    if !embree.is_empty() {
        time_series.push(series("Embree 3 build", 1, &embree));
    }
    time_series.push(series(&format!("path {res}x{res} {spp} spp"), 2, &render_s));
    let title = "Cost against triangles (bumpy sphere)";
    write_plot(
        dir,
        "scaling-triangles.svg",
        svg_xy(title, "triangles (log)", "seconds", &time_series),
    )?;
    write_plot(
        dir,
        "scaling-memory.svg",
        svg_xy(
            "Memory against triangles",
            "triangles (log)",
            "MiB (BVH + mesh)",
            &[series("BVH + mesh", 0, &memory)],
        ),
    )
}

#[cfg(feature = "embree")]
fn embree_build(mesh: &TriangleMesh, reps: usize) -> Option<f64> {
    use lumis_render::accel::embree::EmbreeMesh;
    Some(time_it(reps, || {
        std::hint::black_box(EmbreeMesh::new(mesh));
    }))
}

#[cfg(not(feature = "embree"))]
fn embree_build(_: &TriangleMesh, _: usize) -> Option<f64> {
    None
}

/// Photon-map build and k-NN queries against the photon count.
fn photons(quick: bool, dir: &Path) -> Result<()> {
    let sizes: &[usize] = if quick {
        &[100_000, 300_000, 1_000_000, 3_000_000]
    } else {
        &[
            100_000, 300_000, 1_000_000, 3_000_000, 10_000_000, 30_000_000,
        ]
    };
    outln!("\n| photons | map build (all threads) | k-NN, k = 50, 1 thread | map memory |");
    outln!("| --- | --- | --- | --- |");
    let (mut build, mut query) = (vec![], vec![]);
    let mut rng = lumis_math::Pcg32::new(3, 3);
    let queries: Vec<Vec3> = (0..20_000)
        .map(|_| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()))
        .collect();
    for &n in sizes {
        let photons: Vec<Photon> = (0..n)
            .map(|_| {
                let p = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
                Photon::new(p, Rgb::splat(1e-6), Vec3::Z, 1.0)
            })
            .collect();
        let reps = if n >= 10_000_000 { 1 } else { 3 };
        let b = time_it(reps, || {
            std::hint::black_box(PhotonMap::build(photons.clone(), n as u64));
        });
        let map = PhotonMap::build(photons, n as u64);
        let q = single_thread(|| {
            let mut out = Vec::new();
            time_it(3, || {
                for p in &queries {
                    std::hint::black_box(map.knn(*p, 50, 1.0, &mut out));
                }
            })
        }) / queries.len() as f64;
        outln!(
            "| {n} | {:.3} s | {:.2} µs | {:.1} MiB |",
            b,
            q * 1e6,
            map.memory_bytes() as f64 / MIB
        );
        build.push((n as f64, b));
        query.push((n as f64, q * 1e6));
    }
    outln!(
        "\nlog-log slopes: build {}, query {}",
        slope(&build),
        slope(&query)
    );
    write_plot(
        dir,
        "scaling-photons.svg",
        svg_xy(
            "Photon map against photon count",
            "photons (log)",
            "build s, query µs",
            &[
                series("build (s)", 0, &build),
                series("k-NN query (µs)", 1, &query),
            ],
        ),
    )
}

/// Wall time of the default scene with `path` and with `photon` on one
/// thread and on all.
fn speedup(quick: bool) -> Result<()> {
    let threads = rayon::current_num_threads();
    outln!("\n| default scene | 1 thread | {threads} threads | speedup |");
    outln!("| --- | --- | --- | --- |");
    let res = if quick { 128 } else { 256 };
    for (integrator, spp) in [("path", 8), ("photon", 8)] {
        let mut ov = Overrides::default();
        ov.resolution(res, res).integrator(integrator);
        let l = load_text(DEFAULT_SCENE, "<default>", Path::new("."), &ov)
            .map_err(|d| anyhow::anyhow!("{d}"))?;
        let time = |t: usize| {
            let settings = l.options.render_settings(spp, 0, t);
            let never = AtomicBool::new(false);
            let out = render(&l.scene, &l.options.integrator, &settings, &|_| {}, &never);
            out.elapsed.as_secs_f64()
        };
        let (one, all) = (time(1), time(threads));
        outln!(
            "| {integrator} {res}x{res}, {spp} spp | {one:.2} s | {all:.2} s | {:.2}x |",
            one / all
        );
    }
    Ok(())
}
