//! `--stats`: what pbrt users expect at the end of a render — rays by kind,
//! photons stored per map, memory by category, time by phase.

use lumis_render::film::Pixel;
use lumis_render::integrator::RenderOutcome;
use lumis_render::load::LoadedScene;
use std::sync::atomic::Ordering;
use std::time::Duration;

/// Wall time of each phase.
#[derive(Default, Debug)]
pub struct Phases {
    pub parse: Duration,
    pub build: Duration,
    pub write: Duration,
}

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
    let p = &l.options.integrator.photon;
    let ps = out.photon_stats.as_ref();
    if let Some(ps) = ps {
        eprintln!(
            "  photons      global map {} stored of {} emitted, caustic map {} stored of {} emitted",
            ps.global_stored, p.global_photons, ps.caustic_stored, p.caustic_photons
        );
    }
    let shapes = l.scene.shapes.memory_bytes();
    let bvh = l.scene.geometry_memory_bytes().saturating_sub(shapes);
    let film = out.film.pixels.len() * std::mem::size_of::<Pixel>();
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
