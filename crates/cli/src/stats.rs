//! `--stats`: what pbrt users expect at the end of a render — rays by kind,
//! photons stored per map, memory by category, time by phase.

use lumis_render::integrator::{RenderOutcome, RenderSettings};
use lumis_render::load::LoadedScene;
use std::sync::atomic::Ordering;
use std::time::Duration;

/// Wall time of each phase.
pub use lumis_render::session::Phases;

fn mrays(n: u64) -> String {
    n.to_string()
}

fn kib(n: usize) -> String {
    format!("{:.1} KiB", n as f64 / 1024.0)
}

pub fn print(l: &LoadedScene, out: &RenderOutcome, ph: &Phases) {
    let r = &out.ray_counts;
    let photon_rays = l.scene.counters.photon_rays.load(Ordering::Relaxed);
    eprintln!("Statistics");
    eprintln!(
        "  rays         camera {}, indirect {}, shadow {}, gather {}, photon {}; total {}",
        mrays(r.camera),
        mrays(r.indirect),
        mrays(r.shadow),
        mrays(r.gather),
        mrays(photon_rays),
        mrays(r.total() + photon_rays)
    );
    let p = l.options.integrator.photon();
    let ps = out.photon_stats.as_ref();
    if let (Some(ps), Some(p)) = (ps, p) {
        let (global, caustic) = ps.emitted(p);
        eprintln!(
            "  photons      global map {} stored of {} emitted, caustic map {} stored of {} emitted",
            ps.global_stored, global, ps.caustic_stored, caustic
        );
    }
    let shapes = l.scene.shapes.memory_bytes();
    let bvh = l.scene.geometry_memory_bytes().saturating_sub(shapes);
    let film = out.film.memory_bytes();
    let maps = ps.map_or(0, |s| s.memory_bytes);
    eprintln!(
        "  memory       BVH {}, meshes and shapes {}, film {}, photon maps {}",
        kib(bvh),
        kib(shapes),
        kib(film),
        kib(maps)
    );
    let photon_time = ps.map_or(Duration::ZERO, |s| {
        s.trace_time + s.build_time + s.radiance_time
    });
    eprintln!(
        "  time         parse {:.3} s, build {:.3} s, photon pass {:.3} s, rendering {:.3} s, writing {:.3} s",
        ph.parse.as_secs_f64(),
        ph.build.as_secs_f64(),
        photon_time.as_secs_f64(),
        out.elapsed.saturating_sub(photon_time).as_secs_f64(),
        ph.write.as_secs_f64()
    );
}

/// `-v`: parse and build times, the scene's size and the render settings.
pub fn print_setup(l: &LoadedScene, settings: &RenderSettings, ph: &Phases) {
    let o = &l.options;
    let sc = &l.scene;
    let tris: usize = sc.shapes.meshes.iter().map(|m| m.indices.len() / 3).sum();
    eprintln!(
        "lumis: parsed in {:.3} s; built in {:.3} s: {} triangles in {} meshes, {} spheres, {} disks, {} lights, {:.1} MiB of geometry and BVH",
        ph.parse.as_secs_f64(),
        ph.build.as_secs_f64(),
        tris,
        sc.shapes.meshes.len(),
        sc.shapes.spheres.len(),
        sc.shapes.disks.len(),
        sc.lights.len(),
        sc.geometry_memory_bytes() as f64 / (1u64 << 20) as f64
    );
    eprintln!(
        "lumis: {} {}x{} (crop {}x{}), {} spp, seed {}, sampler {:?}, maxdepth {}, threads {}",
        o.integrator.name(),
        o.resolution.0,
        o.resolution.1,
        o.crop.width(),
        o.crop.height(),
        if settings.spp == 0 {
            "time-limited".to_string()
        } else {
            settings.spp.to_string()
        },
        settings.seed,
        settings.sampler,
        o.integrator.max_depth(),
        if settings.threads == 0 {
            rayon::current_num_threads()
        } else {
            settings.threads
        },
    );
}
