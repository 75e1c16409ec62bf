//! What each integrator does during a render, behind the driver's
//! [`Pass`] interface: work before each pass (photon tracing), the
//! radiance of one camera sample, bookkeeping after each pass, and its own
//! state for checkpoints.

use super::driver::{Pass, PassReport, SampleCx, Start};
use super::photon::run::PhotonRun;
use super::vcm::VcmRun;
use super::{bdpt, direct, lighttracer, path, Integrator};
use crate::geometry::Ray;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler, Vec2};
use std::sync::atomic::AtomicBool;
use std::time::Duration;

/// An integrator prepared for one render of one scene.
pub enum Run<'a> {
    Path {
        scene: &'a Scene,
        max_depth: u32,
    },
    Direct {
        scene: &'a Scene,
        max_depth: u32,
    },
    Photon(Box<PhotonRun<'a>>),
    /// `scale`: the film's pixels over the rendered (crop) pixels.
    LightTracer {
        scene: &'a Scene,
        max_depth: u32,
        scale: f32,
    },
    /// `scale` as for the light tracer (its `t = 1` strategies splat).
    Bdpt {
        scene: &'a Scene,
        settings: &'a bdpt::BdptSettings,
        scale: f32,
    },
    Vcm(Box<VcmRun<'a>>),
}

impl<'a> Run<'a> {
    /// `saved` is the state of an earlier run of the same render (from
    /// [`Pass::save`]); `None` starts afresh.
    pub fn new(
        integrator: &'a Integrator,
        scene: &'a Scene,
        start: &Start,
        saved: Option<&[u8]>,
    ) -> Run<'a> {
        match integrator {
            Integrator::Path { max_depth } => Run::Path {
                scene,
                max_depth: *max_depth,
            },
            Integrator::Direct { max_depth } => Run::Direct {
                scene,
                max_depth: *max_depth,
            },
            Integrator::Photon(s) => Run::Photon(Box::new(PhotonRun::new(scene, s, start, saved))),
            Integrator::LightTracer { max_depth } => Run::LightTracer {
                scene,
                max_depth: *max_depth,
                scale: splat_scale(scene, start),
            },
            Integrator::Bdpt(settings) => Run::Bdpt {
                scene,
                settings,
                scale: splat_scale(scene, start),
            },
            Integrator::Vcm(s) => Run::Vcm(Box::new(VcmRun::new(
                scene,
                s,
                start,
                splat_scale(scene, start),
                saved,
            ))),
        }
    }

    /// The state [`Pass::save`] would give after the passes before pass
    /// `pass` (`spp_done` samples per pixel) of a render started afresh:
    /// what a partial render starting there continues from. Every
    /// integrator's state follows from the pass count alone when no time
    /// budget steers it.
    pub fn state_at(integrator: &Integrator, start: &Start, pass: u32, spp_done: u32) -> Vec<u8> {
        match integrator {
            Integrator::Photon(s) => PhotonRun::state_at(s, start, spp_done),
            Integrator::Vcm(_) => VcmRun::state_at(pass),
            _ => Vec::new(),
        }
    }

    /// Photon pass figures, for the `photon` integrator.
    pub fn photon_stats(&self) -> Option<super::photon::PhotonStats> {
        match self {
            Run::Photon(p) => p.stats(),
            _ => None,
        }
    }
}

/// Splats of light reaching the camera carry the importance of the whole
/// film: a crop's share of the paths is made up by the film's pixels over
/// the crop's.
fn splat_scale(scene: &Scene, start: &Start) -> f32 {
    let (w, h) = scene.camera.resolution;
    let crop = start.crop.area().max(1) as f64;
    (w as f64 * h as f64 / crop) as f32
}

impl Pass for Run<'_> {
    fn before_pass(&mut self, cancel: &AtomicBool) -> bool {
        match self {
            Run::Photon(p) => p.before_pass(cancel),
            Run::Vcm(v) => v.before_pass(cancel),
            _ => true,
        }
    }

    #[inline]
    fn li(&self, ray: Ray, sampler: &mut Sampler, cx: &mut SampleCx) -> Rgb {
        match self {
            Run::Path { scene, max_depth } => path::li(scene, ray, sampler, *max_depth, cx.rays),
            Run::Direct { scene, max_depth } => {
                direct::li(scene, ray, sampler, *max_depth, cx.rays)
            }
            Run::Photon(p) => p.li(ray, sampler, cx.rays),
            Run::LightTracer {
                scene,
                max_depth,
                scale,
            } => {
                lighttracer::trace(scene, sampler, *max_depth, *scale, cx);
                Rgb::BLACK
            }
            Run::Bdpt {
                scene,
                settings,
                scale,
            } => bdpt::li(scene, ray, sampler, settings, *scale, cx),
            Run::Vcm(v) => v.li(ray, sampler, cx),
        }
    }

    fn pass_splats(&self) -> &[(Vec2, Rgb)] {
        match self {
            Run::Photon(p) => p.pass_splats(),
            _ => &[],
        }
    }

    fn next_cost(&self, r: &PassReport, pass_time: Duration) -> Option<Duration> {
        match self {
            Run::Photon(p) => p.next_cost(r, pass_time),
            Run::Vcm(v) => v.next_cost(r, pass_time),
            _ => Some(pass_time),
        }
    }

    fn after_pass(&mut self, r: &PassReport) {
        match self {
            Run::Photon(p) => p.after_pass(r),
            Run::Vcm(v) => v.after_pass(),
            _ => {}
        }
    }

    fn save(&self) -> Vec<u8> {
        match self {
            Run::Photon(p) => p.save(),
            Run::Vcm(v) => v.save(),
            _ => Vec::new(),
        }
    }
}
