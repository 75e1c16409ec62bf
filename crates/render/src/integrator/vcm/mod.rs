//! Vertex connection and merging (Georgiev, Krivánek, Davidovič and
//! Slusallek 2012): bidirectional path tracing whose strategies also
//! include *merging* a camera vertex with every light vertex within a
//! radius `r`, a photon-map estimate, all weighted by the power heuristic
//! (`bdpt/mis.rs`, where a merge at a vertex has the density of the
//! connection that ends there times `eta = pi r^2 N`, `N` the light
//! subpaths per pass).
//!
//! Each pass traces one light subpath per camera sample of the whole film
//! (`store.rs`): camera sample `k` of the pass connects to subpath `k` as
//! in `bdpt`, and merges at each of its non-delta vertices with the
//! vertices of all of them. A crop renders its pixels with the whole
//! film's light subpaths, so that its estimate (radius, `eta`, weights) is
//! the full render's; only the subpaths paired with its samples splat.
//! The radius shrinks from pass to pass as Knaus and Zwicker's sequence `r_{i+1}^2 = r_i^2 (i + a) / (i + 1)` (`shrink` = `a`, 0.75 as
//! in the paper), so the merges' bias and variance both vanish: the
//! estimate is consistent. Only one pass's light subpaths are ever held.
//!
//! Merging is what renders light focused by mirrors and glass seen again
//! through mirrors and glass (`L S+ D S+ E` from a point light), which no
//! connection can make; where connections are good (diffuse light paths,
//! caustics seen directly) the weights hand the path to them.

mod merge;
pub mod store;

use super::bdpt::{self, BdptSettings};
use super::driver::{PassReport, SampleCx, Start};
use super::photon::progressive::{iteration_seed, next_radius2};
use crate::geometry::Ray;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler, Vec2, PI};
use lumis_scene::ParamSpec;
use std::cell::RefCell;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};
use store::LightPaths;

#[derive(Clone, Debug, PartialEq)]
pub struct VcmSettings {
    pub max_depth: u32,
    /// The first pass's merging radius in scene units (0: one pixel's
    /// footprint at the median distance the camera sees, `merge.rs`).
    pub initial_radius: f32,
    /// `a` of the radius sequence, in (0, 1].
    pub shrink: f32,
}

impl VcmSettings {
    pub fn new(max_depth: u32) -> VcmSettings {
        VcmSettings {
            max_depth,
            initial_radius: 0.0,
            shrink: 0.75,
        }
    }
}

/// The parameters of `Integrator "vcm"` besides `maxdepth`. `photon`'s
/// progressive mode has the same two (one flag each, see the CLI's tables).
pub const PARAMS: &[ParamSpec] = &[
    ParamSpec {
        ty: "float",
        name: "initialradius",
        words: "initial-radius",
        value: "R",
        help: "merging radius of the first pass in scene units (0: one pixel's footprint at the median distance the camera sees)",
    },
    ParamSpec {
        ty: "float",
        name: "shrink",
        words: "shrink",
        value: "A",
        help: "radius sequence r_{i+1}^2 = r_i^2 (i + A) / (i + 1) over passes, 0 < A <= 1 (default 0.75)",
    },
];

thread_local! {
    static CAMERA: RefCell<Vec<bdpt::vertex::Vertex>> = const { RefCell::new(Vec::new()) };
}

/// `vcm` prepared for one render: the pass's light subpaths and radius.
pub struct VcmRun<'a> {
    scene: &'a Scene,
    bdpt: BdptSettings,
    shrink: f64,
    seed: u64,
    /// The film's full resolution.
    film: (u32, u32),
    per_pass: u32,
    /// `t = 1` splats' scale (as `bdpt`'s).
    scale: f32,
    /// Passes done (over all runs of a resumed render), and the squared
    /// radius of the next.
    iteration: u64,
    r2: f64,
    paths: LightPaths,
    radius: f32,
    eta: f32,
    trace_time: Duration,
}

impl<'a> VcmRun<'a> {
    pub fn new(
        scene: &'a Scene,
        st: &VcmSettings,
        start: &Start,
        scale: f32,
        saved: Option<&[u8]>,
    ) -> VcmRun<'a> {
        let iteration = saved
            .and_then(|b| b.try_into().ok())
            .map_or(0, u64::from_le_bytes);
        let r1 = if st.initial_radius > 0.0 {
            st.initial_radius
        } else {
            merge::footprint_radius(scene)
        };
        let shrink = st.shrink as f64;
        let r2 = (0..iteration).fold((r1 as f64).powi(2), |r2, j| next_radius2(r2, j, shrink));
        VcmRun {
            scene,
            bdpt: BdptSettings::new(st.max_depth),
            shrink,
            seed: start.seed,
            film: scene.camera.resolution,
            per_pass: start.spp_per_pass.max(1),
            scale,
            iteration,
            r2,
            paths: LightPaths::default(),
            radius: 0.0,
            eta: 0.0,
            trace_time: Duration::ZERO,
        }
    }

    /// Traces the pass's light subpaths.
    pub fn before_pass(&mut self, cancel: &AtomicBool) -> bool {
        let t0 = Instant::now();
        let n = self.film.0 as usize * self.film.1 as usize * self.per_pass as usize;
        let seed = iteration_seed(self.seed ^ VCM_STREAMS, self.iteration);
        let max_verts = self.bdpt.max_depth as usize + 1;
        let Some(paths) = LightPaths::trace(self.scene, n, max_verts, seed, cancel) else {
            return false;
        };
        self.paths = paths;
        self.radius = self.r2.sqrt() as f32;
        self.eta = PI * self.radius * self.radius * n as f32;
        self.trace_time = t0.elapsed();
        true
    }

    /// Camera sample `cx.index` of pixel `cx.pixel`: connections to its own
    /// light subpath and merges with all.
    pub fn li(&self, ray: Ray, sampler: &mut Sampler, cx: &mut SampleCx) -> Rgb {
        let (x, y) = cx.pixel;
        let pixel = y as usize * self.film.0 as usize + x as usize;
        let k = pixel * self.per_pass as usize + (cx.index % self.per_pass) as usize;
        let light = self.paths.path(k);
        CAMERA.with(|cell| {
            let camera = &mut *cell.borrow_mut();
            let margin: Vec2 = cx.filter.radius;
            let max_verts = self.bdpt.max_depth as usize + 2;
            let escape = bdpt::walk::camera_path(
                self.scene, ray, margin, sampler, max_verts, camera, cx.rays,
            );
            let c = bdpt::Connect {
                scene: self.scene,
                st: &self.bdpt,
                eta: self.eta,
                margin,
                light,
                camera,
            };
            let l = c.all(escape, sampler, self.scale, cx);
            l + merge::all(self, camera, margin)
        })
    }

    /// The next pass's cost: its light subpaths' and its samples'.
    pub fn next_cost(&self, _r: &PassReport, pass_time: Duration) -> Option<Duration> {
        Some(pass_time + self.trace_time)
    }

    pub fn after_pass(&mut self) {
        self.r2 = next_radius2(self.r2, self.iteration, self.shrink);
        self.iteration += 1;
        self.paths = LightPaths::default();
    }

    pub fn save(&self) -> Vec<u8> {
        Self::state_at(self.iteration as u32)
    }

    /// The saved state after `passes` passes: their count.
    pub fn state_at(passes: u32) -> Vec<u8> {
        (passes as u64).to_le_bytes().to_vec()
    }
}

/// Keeps the light subpaths' streams apart from `photon`'s for one seed.
const VCM_STREAMS: u64 = 0x7663_6d5f_6c69_6768;
