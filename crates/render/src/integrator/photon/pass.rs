//! One photon pass: photons traced from the lights into a global and a
//! caustic map, their kd-trees, and the radiance photons over the global
//! map; with the query radii of a progressive iteration, if any.

use super::connect::Connection;
use super::map::PhotonMap;
use super::radiance::{self, RadiancePhotons};
use super::radius_field::RadiusField;
use super::{aim, trace, PhotonSettings};
use crate::scene::Scene;
use lumis_math::{Rgb, Vec2, Vec3};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Timing and counts of the photon passes, for the summary and benchmarks.
#[derive(Clone, Debug, Default)]
pub struct PhotonStats {
    pub global_stored: usize,
    pub caustic_stored: usize,
    pub trace_time: Duration,
    pub build_time: Duration,
    pub radiance_time: Duration,
    pub memory_bytes: usize,
    /// Of `memory_bytes`, what progressive iterations keep beside the maps
    /// (their peak): the radiance photons' lookup grid and the radius
    /// fields (the caustic one with its own grid), built once per render.
    pub grid_bytes: usize,
    /// Progressive iterations begun (0 without the progressive mode); the
    /// counts and times are then sums over them and the memory their peak.
    pub iterations: u32,
    /// Progressive: the caustic radius of the latest iteration.
    pub caustic_radius: f32,
    /// Progressive: photons emitted per iteration (global, caustic).
    pub iteration_photons: (u64, u64),
    /// Progressive: the time rule chose `iteration_photons` (`budget.rs`).
    pub counts_chosen: bool,
    /// Progressive: iterations of the whole render (over all runs of a
    /// resumed one) begun so far; `iterations` counts this run's photon
    /// passes.
    pub render_iterations: u64,
}

impl PhotonStats {
    /// Adds one progressive iteration's photon pass: counts and times
    /// summed, memory the peak, the radius the latest.
    pub fn add_iteration(&mut self, st: &PhotonStats) {
        self.global_stored += st.global_stored;
        self.caustic_stored += st.caustic_stored;
        self.trace_time += st.trace_time;
        self.build_time += st.build_time;
        self.radiance_time += st.radiance_time;
        self.memory_bytes = self.memory_bytes.max(st.memory_bytes);
        self.grid_bytes = self.grid_bytes.max(st.grid_bytes);
        self.iterations += 1;
        self.caustic_radius = st.caustic_radius;
    }

    /// Photons emitted (global, caustic) by the photon passes these stats
    /// count: the settings' counts for one map, the iterations' counts
    /// (which the time rule may have chosen) times this run's iterations
    /// for the progressive mode.
    pub fn emitted(&self, s: &PhotonSettings) -> (u64, u64) {
        if self.iterations == 0 {
            return (s.global_photons, s.caustic_photons);
        }
        let n = self.iterations as u64;
        (self.iteration_photons.0 * n, self.iteration_photons.1 * n)
    }
}

/// Everything the camera pass needs from the photon pass.
pub struct PhotonMaps {
    pub global: PhotonMap,
    pub caustic: PhotonMap,
    /// Photons scattered in media (empty without media): every event, and
    /// the first after a purely specular path (volumetric caustics).
    pub volume_global: PhotonMap,
    pub volume_caustic: PhotonMap,
    pub radiance: Option<RadiancePhotons>,
    /// Total emitted power `Phi` (luminance) of all lights.
    pub phi: f32,
    pub max_radius: f32,
    /// Set when caustic photons were aimed: q_1 then uses per-photon fluxes.
    pub targets: Option<aim::Targets>,
    /// The fixed radii of the caustic and global estimates (progressive
    /// iterations); `None`: the `nearest` photons within a largest radius.
    pub radii: Option<Radii>,
    /// The caustic photons connected to the camera (`connect_caustics`),
    /// and, once weighed, their raster positions and radiance: one estimate
    /// of the caustics seen directly per sample per pixel.
    pub connections: Vec<Connection>,
    pub splats: Vec<(Vec2, Rgb)>,
    pub stats: PhotonStats,
}

/// The query radii of one progressive iteration: each point's `r_0`
/// scaled by the iteration's `scale2` (fixed before the iteration).
#[derive(Clone, Debug)]
pub struct Radii {
    pub caustic: Arc<RadiusField>,
    pub global: Arc<RadiusField>,
    pub scale2: f32,
    /// Where the global estimate is precomputed (radiance photons).
    pub global_points: Arc<radiance::Points>,
}

impl Radii {
    /// Squared radius of the caustic estimate at `p`.
    #[inline]
    pub fn caustic_r2(&self, p: Vec3) -> f32 {
        self.caustic.r2_at(p) * self.scale2
    }

    /// [`caustic_r2`](Self::caustic_r2) and, from the same search of the
    /// field, the share of the irradiance at `p` that the gather rays carry
    /// of the caustics in this iteration (`RadiusField::at`).
    #[inline]
    pub fn caustic_at(&self, p: Vec3) -> (f32, f32) {
        let (r2, share) = self.caustic.at(p, self.scale2);
        (r2 * self.scale2, share)
    }

    /// Squared radius of the global estimate at `p`.
    #[inline]
    pub fn global_r2(&self, p: Vec3) -> f32 {
        self.global.r2_at(p) * self.scale2
    }

    /// The largest global radius of this iteration.
    pub fn global_max(&self) -> f32 {
        self.global.max_radius() * self.scale2.sqrt()
    }
}

/// One global photon in this many becomes a radiance photon.
pub const RADIANCE_STRIDE: usize = 4;

/// The global map's largest radius relative to the caustic map's.
pub const GLOBAL_RADIUS_SCALE: f32 = 5.0;

impl PhotonMaps {
    /// Traces and builds the maps, radiance photons from the `nearest`
    /// photons; gives up (`None`) soon after `cancel` is set, so an
    /// interrupt during a long photon pass ends the render at once.
    /// `connect`: caustic photons are connected to the camera, whose film
    /// they may reach within that margin (pixels); weighed by the run.
    pub fn build(
        scene: &Scene,
        s: &PhotonSettings,
        seed: u64,
        connect: Option<Vec2>,
        aims: &aim::Aims,
        cancel: &AtomicBool,
    ) -> Option<PhotonMaps> {
        let (mut maps, normals) = Self::trace(scene, s, seed, connect, aims, cancel)?;
        maps.finish(s, &normals, None);
        Some(maps)
    }

    /// Traces the photons and builds the maps' trees; [`PhotonMaps::finish`]
    /// then builds the radiance photons (`normals`: the global photons'
    /// surface normals).
    pub fn trace(
        scene: &Scene,
        s: &PhotonSettings,
        seed: u64,
        connect: Option<Vec2>,
        aims: &aim::Aims,
        cancel: &AtomicBool,
    ) -> Option<(PhotonMaps, Vec<Vec3>)> {
        let phi: f32 = scene
            .lights
            .iter()
            .map(|l| l.power(&scene.shapes).luminance())
            .sum();
        let max_radius = if s.max_radius > 0.0 {
            s.max_radius
        } else {
            0.02 * scene.bounds.bounding_sphere().1.max(1e-6)
        };
        let t0 = Instant::now();
        let g = trace::trace_photons(
            scene,
            s.global_photons,
            trace::MapKind::Global,
            seed,
            s.max_depth,
            aims,
            None,
            cancel,
        )?;
        let c = trace::trace_photons(
            scene,
            s.caustic_photons,
            trace::MapKind::Caustic,
            seed ^ 0x5eed,
            s.max_depth,
            aims,
            connect,
            cancel,
        )?;
        let trace_time = t0.elapsed();
        let t1 = Instant::now();
        let global = PhotonMap::build(g.photons, s.global_photons);
        let caustic = PhotonMap::build(c.photons, s.caustic_photons);
        let volume_global = PhotonMap::build(g.volume, s.global_photons);
        let volume_caustic = PhotonMap::build(c.volume, s.caustic_photons);
        let stats = PhotonStats {
            global_stored: global.len(),
            caustic_stored: caustic.len(),
            trace_time,
            build_time: t1.elapsed(),
            ..PhotonStats::default()
        };
        let maps = PhotonMaps {
            global,
            caustic,
            volume_global,
            volume_caustic,
            radiance: None,
            phi,
            max_radius,
            targets: aims.aim.clone(),
            radii: None,
            connections: c.connections,
            splats: Vec::new(),
            stats,
        };
        Some((maps, g.normals))
    }

    /// Sets the query radii (`None`: nearest photons) and builds the
    /// radiance photons accordingly, if the settings ask for them.
    pub fn finish(&mut self, s: &PhotonSettings, normals: &[Vec3], radii: Option<Radii>) {
        let t2 = Instant::now();
        self.radiance = match &radii {
            _ if !s.radiance_photons || self.global.is_empty() => None,
            Some(r) => Some(RadiancePhotons::fixed(
                &self.global,
                r.global_points.clone(),
                r.scale2,
            )),
            None => Some(RadiancePhotons::build(
                &self.global,
                normals,
                RADIANCE_STRIDE,
                s.nearest,
                self.max_radius * 2.0,
            )),
        };
        let st = &mut self.stats;
        st.radiance_time = t2.elapsed();
        st.memory_bytes = self.global.memory_bytes()
            + self.caustic.memory_bytes()
            + self.volume_global.memory_bytes()
            + self.volume_caustic.memory_bytes()
            + self.radiance.as_ref().map_or(0, |r| r.memory_bytes());
        let fields = radii
            .as_ref()
            .map_or(0, |r| r.caustic.memory_bytes() + r.global.memory_bytes());
        st.memory_bytes += fields;
        st.grid_bytes = self.radiance.as_ref().map_or(0, |r| r.grid_bytes()) + fields;
        st.caustic_radius = radii
            .as_ref()
            .map_or(0.0, |r| (r.caustic.median_r2() * r.scale2).sqrt());
        self.radii = radii;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn emitted_counts_the_iterations_photons() {
        let s = PhotonSettings::default();
        let mut st = PhotonStats::default();
        assert_eq!(st.emitted(&s), (s.global_photons, s.caustic_photons));
        st.iteration_photons = (6400, 32000);
        let pass = PhotonStats::default();
        for _ in 0..3 {
            st.add_iteration(&pass);
        }
        assert_eq!(st.emitted(&s), (19200, 96000));
    }
}
