//! Photon tracing: parallel, deterministic for a given seed (photon `i`
//! draws its random numbers from a stream keyed by `i` alone, and chunks are
//! concatenated in order).

use super::aim::{aimed_emission, Aims, Targets};
use super::connect::{to_camera, Connection};
use super::photon::Photon;
use super::polar::PolarWindows;
use crate::bsdf::TransportMode;
use crate::geometry::ray::spawn_ray;
use crate::geometry::Ray;
use crate::integrator::volpath::{advance, flight_stream, Flight};
use crate::material::Material;
use crate::media::LightMedium;
use crate::scene::Scene;
use lumis_math::rng::{hash, Pcg32};
use lumis_math::{Rgb, Sampler, SamplerKind, Vec2, Vec3};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// Every photon hit on a non-delta surface.
    Global,
    /// Only paths `L S+` ending on a non-delta surface (one or more perfectly
    /// specular bounces, no other bounce); paths end there.
    Caustic,
}

#[derive(Default)]
pub struct Traced {
    pub photons: Vec<Photon>,
    /// Surface normal (facing the photon's side) where each photon was stored.
    pub normals: Vec<Vec3>,
    /// Photons stored where they scattered in a medium (`Global`: every
    /// such event; `Caustic`: the first after a purely specular path).
    pub volume: Vec<Photon>,
    /// Caustic photons connected to the camera (`connect.rs`).
    pub connections: Vec<Connection>,
}

const CHUNK: u64 = 4096;

/// Traces `n_emit` photons; gives up (`None`) soon after `cancel` is set:
/// chunks not yet started are skipped. Caustic photons are aimed by
/// `aims.aim` and skipped by `aims.starts` when those are given.
/// `connect`: caustic photons are also connected to the camera, whose film
/// they may reach within that margin (the filter's radius, pixels).
///
/// Where `aims.starts` bounds the shapes a caustic path can start at and
/// the scene's geometry does not fit in a core's cache, the caustic
/// photons are traced in the order of where they meet those shapes
/// (`order.rs`), and their results put back in photon order.
#[allow(clippy::too_many_arguments)]
pub fn trace_photons(
    scene: &Scene,
    n_emit: u64,
    kind: MapKind,
    seed: u64,
    max_depth: u32,
    aims: &Aims,
    connect: Option<Vec2>,
    cancel: &AtomicBool,
) -> Option<Traced> {
    if n_emit == 0 || scene.light_sampler.is_empty() {
        return Some(Traced::default());
    }
    let (targets, starts) = match kind {
        MapKind::Caustic => (aims.aim.as_ref(), aims.starts.as_ref()),
        MapKind::Global => (None, None),
    };
    let windows = starts.map(|s| PolarWindows::new(scene, s));
    let job = Job {
        scene,
        n_emit,
        kind,
        seed,
        max_depth,
        targets,
        starts,
        windows: windows.as_ref(),
        connect,
    };
    if let (MapKind::Caustic, Some(starts)) = (kind, starts) {
        if scene.geometry_memory_bytes() > super::order::SORT_ABOVE_BYTES {
            return super::order::trace_by_first_hit(&job, starts, cancel);
        }
    }
    let chunks = n_emit.div_ceil(CHUNK);
    let parts: Vec<Traced> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut out = Traced::default();
            if cancel.load(Ordering::Relaxed) {
                return out;
            }
            let mut sampler = job.sampler();
            let mut rays = 0u64;
            for i in c * CHUNK..((c + 1) * CHUNK).min(n_emit) {
                job.trace(i, &mut sampler, &mut out, &mut rays);
            }
            job.count(rays);
            out
        })
        .collect();
    if cancel.load(Ordering::Relaxed) {
        return None;
    }
    let total: usize = parts.iter().map(|p| p.photons.len()).sum();
    let mut all = Traced {
        photons: Vec::with_capacity(total),
        normals: Vec::with_capacity(total),
        volume: Vec::new(),
        connections: Vec::new(),
    };
    for p in parts {
        all.photons.extend(p.photons);
        all.normals.extend(p.normals);
        all.volume.extend(p.volume);
        all.connections.extend(p.connections);
    }
    Some(all)
}

/// What the photons of one [`trace_photons`] call share. Photon `i`'s
/// results depend on `i` and these alone, whatever order they are traced in.
pub(super) struct Job<'a> {
    pub scene: &'a Scene,
    pub n_emit: u64,
    pub kind: MapKind,
    pub seed: u64,
    pub max_depth: u32,
    pub targets: Option<&'a Targets>,
    pub starts: Option<&'a Targets>,
    /// Light-wide polar-angle tests of caustic photons (with `starts`).
    pub windows: Option<&'a PolarWindows>,
    pub connect: Option<Vec2>,
}

impl Job<'_> {
    pub fn sampler(&self) -> Sampler {
        Sampler::new(SamplerKind::Independent, self.seed)
    }

    /// Photon `i`'s first ray, if it is traced at all (`sampler` is left
    /// part way through its stream).
    pub fn first_ray(&self, i: u64, sampler: &mut Sampler) -> Option<Ray> {
        sampler.start_stream(i, 0);
        self.emit(sampler).map(|e| e.ray)
    }

    /// Traces photon `i`, adding what it stores to `out`.
    pub fn trace(&self, i: u64, sampler: &mut Sampler, out: &mut Traced, rays: &mut u64) {
        sampler.start_stream(i, 0);
        let seed = self.seed;
        // Its stream is made only for a photon that is traced.
        let connect = self.connect.map(|margin| {
            move || Connect {
                margin,
                rng: Pcg32::new(hash(&[seed, i, 0xc0_11ec7]), 0),
            }
        });
        let Some(e) = self.emit(sampler) else {
            return;
        };
        let (scene, kind_depth) = (self.scene, (self.kind, self.max_depth));
        trace_from(scene, e, kind_depth, connect, sampler, out, rays);
    }

    /// The emission of the photon whose stream `sampler` starts, or None for
    /// one that is not traced (no light, zero power, or a caustic photon that
    /// `starts` drops).
    fn emit(&self, sampler: &mut Sampler) -> Option<Emission> {
        let (scene, n_emit, targets, starts) = (self.scene, self.n_emit, self.targets, self.starts);
        let (li, pmf) = scene.light_sampler.sample(sampler.get_1d())?;
        let light = &scene.lights[li as usize];
        let (u1, u2) = (sampler.get_2d(), sampler.get_2d());
        // Aimed caustic photons (area, point, spot lights), else ordinary emission.
        let aimed =
            targets.and_then(|t| aimed_emission(scene, t, light, pmf, u1, sampler.get_1d(), u2));
        // A caustic photon ends unstored where its first hit has no specular
        // part, so one whose first ray misses every shape that has one is
        // dropped as soon as its ray is known (most are, where those shapes
        // are small), before its flux. (`starts` is given for caustic photons
        // in scenes without media only.)
        let dropped = |ray: &Ray| starts.is_some_and(|t| !t.may_hit(ray));
        let (ray, flux, le_rgb) = match aimed {
            Some(Some(e)) if dropped(&e.0) => return None,
            Some(Some(e)) => e,
            Some(None) => return None,
            None => {
                let cull = self.windows.zip(starts).map(|(w, s)| w.cull(li, s));
                let le = light.sample_le_culled(&scene.shapes, u1, u2, cull.as_ref())?;
                if dropped(&le.ray) {
                    return None;
                }
                (le.ray, le.flux_weight() / pmf, le.le)
            }
        };
        let power: Rgb = flux / n_emit as f32;
        if !power.is_finite() || power.is_black() {
            return None;
        }
        // Emitted luminance at the origin; infinite for delta lights (the seed's L_e).
        let le_lum = if light.is_delta() {
            f32::INFINITY
        } else {
            le_rgb.luminance()
        };
        Some(Emission {
            li,
            ray,
            power,
            le_lum,
        })
    }

    /// Adds `rays` photon rays to the scene's counters.
    pub fn count(&self, rays: u64) {
        self.scene.count_rays(rays);
        self.scene
            .counters
            .photon_rays
            .fetch_add(rays, Ordering::Relaxed);
    }
}

/// A photon's connections to the camera: the film margin, and a stream of
/// its own, so the photon's path (and the maps) are those without them.
struct Connect {
    margin: Vec2,
    rng: Pcg32,
}

/// A photon as it leaves its light: the light, the first ray, the power
/// and the emitted luminance at the origin (infinite for delta lights).
struct Emission {
    li: u32,
    ray: Ray,
    power: Rgb,
    le_lum: f32,
}

/// Traces an emitted photon on (the rest of its stream in `sampler`).
fn trace_from(
    scene: &Scene,
    e: Emission,
    (kind, max_depth): (MapKind, u32),
    connect: Option<impl FnOnce() -> Connect>,
    sampler: &mut Sampler,
    out: &mut Traced,
    rays: &mut u64,
) {
    let Emission {
        li,
        mut ray,
        mut power,
        le_lum,
    } = e;
    let mut connect = connect.map(|make| make());
    let mut specular_only = true;
    // Media: the medium the light emits into, and a stream for free flights.
    let mut medium = match scene.light_media.get(li as usize) {
        None | Some(LightMedium::In(None)) => None,
        Some(LightMedium::In(m)) => *m,
        // The side of the light's own surface the photon leaves on: found
        // by a probe back towards it.
        Some(LightMedium::Between(mi)) => {
            let back = Ray {
                o: ray.o,
                d: -ray.d,
                tmax: 1e-2,
            };
            match scene.intersect(&back) {
                Some(h) => mi.towards(ray.d, h.geom.ng),
                None => mi.outside,
            }
        }
    };
    let mut rng = scene.has_media().then(|| flight_stream(sampler));
    'bounce: for depth in 0..=max_depth {
        *rays += 1;
        // A caustic photon ends unstored where its first hit has no
        // specular part: there its hit's geometry is not needed.
        let mut hit = if kind == MapKind::Caustic && depth == 0 && !scene.has_media() {
            match scene.intersect_unless(&ray, Material::never_delta) {
                Some(None) => return,
                found => found.flatten(),
            }
        } else {
            scene.intersect(&ray)
        };
        if let Some(rng) = rng.as_mut() {
            // Free flights, and pure boundaries crossed, up to the next
            // surface that scatters or a scattering event in a medium.
            let f = advance(
                scene,
                &mut medium,
                &mut ray,
                &mut hit,
                rng,
                &mut power,
                None,
                rays,
            );
            match f {
                Flight::Absorbed => return,
                Flight::Scattered(p) => {
                    let wo = -ray.d.normalize();
                    match kind {
                        MapKind::Global => out.volume.push(Photon::new(p, power, wo, le_lum)),
                        MapKind::Caustic => {
                            if depth > 0 && specular_only {
                                out.volume.push(Photon::new(p, power, wo, le_lum));
                            }
                            return;
                        }
                    }
                    let Some(m) = medium else {
                        return;
                    };
                    let Some(ps) = scene.media[m as usize].phase.sample(wo, sampler.get_2d())
                    else {
                        return;
                    };
                    specular_only = false;
                    ray = Ray::new(p, ps.wi);
                    continue 'bounce;
                }
                Flight::Passed => {}
            }
        }
        let Some(hit) = hit else {
            return;
        };
        let bsdf = scene.bsdf(&hit, -ray.d);
        let wo = -ray.d;
        if !bsdf.is_delta() {
            let n = if hit.geom.ng.dot(wo) < 0.0 {
                -hit.geom.ng
            } else {
                hit.geom.ng
            };
            match kind {
                MapKind::Global => {
                    out.photons.push(Photon::new(hit.geom.p, power, wo, le_lum));
                    out.normals.push(n);
                }
                MapKind::Caustic => {
                    if depth > 0 && specular_only {
                        out.photons.push(Photon::new(hit.geom.p, power, wo, le_lum));
                        out.normals.push(n);
                        if let Some(c) = connect.as_mut() {
                            let pl = (power, le_lum);
                            let m = c.margin;
                            let conn = to_camera(scene, &hit, &bsdf, wo, pl, m, &mut c.rng, rays);
                            out.connections.extend(conn);
                        }
                    }
                    // A delta lobe (smooth coat) may still carry the caustic on.
                    if !bsdf.has_delta_lobe() {
                        return;
                    }
                }
            }
        }
        let uc = sampler.get_1d();
        let u = sampler.get_2d();
        let Some(bs) = bsdf.sample(wo, uc, u, TransportMode::Importance) else {
            return;
        };
        let weight = bs.weight(hit.geom.ns);
        // Russian roulette with survival = the bounce's transmittance, so the
        // photon's power keeps its luminance (the seed's gamma).
        let survive = weight.luminance().min(1.0);
        if !(survive > 0.0) || sampler.get_1d() >= survive {
            return;
        }
        power *= weight / survive;
        if !bs.delta {
            if kind == MapKind::Caustic {
                return;
            }
            specular_only = false;
        }
        if let Some(mi) = scene.medium_interface(&hit) {
            medium = mi.towards(bs.wi, hit.geom.ng);
        }
        ray = spawn_ray(hit.geom.p, hit.geom.ng, bs.wi);
    }
}
