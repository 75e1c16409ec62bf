//! What each integrator does during a render, behind the driver's
//! [`Pass`] interface: work before each pass (photon tracing), the
//! radiance of one camera sample, bookkeeping after each pass, and its own
//! state for checkpoints.

use super::driver::{Pass, PassReport, SampleCx, Start};
use super::photon::run::PhotonRun;
use super::{direct, path, Integrator};
use crate::geometry::Ray;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler};
use std::sync::atomic::AtomicBool;
use std::time::Duration;

/// An integrator prepared for one render of one scene.
pub enum Run<'a> {
    Path { scene: &'a Scene, max_depth: u32 },
    Direct { scene: &'a Scene, max_depth: u32 },
    Photon(Box<PhotonRun<'a>>),
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

impl Pass for Run<'_> {
    fn before_pass(&mut self, cancel: &AtomicBool) -> bool {
        match self {
            Run::Photon(p) => p.before_pass(cancel),
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
        }
    }

    fn next_cost(&self, r: &PassReport, pass_time: Duration) -> Option<Duration> {
        match self {
            Run::Photon(p) => p.next_cost(r, pass_time),
            _ => Some(pass_time),
        }
    }

    fn after_pass(&mut self, r: &PassReport) {
        if let Run::Photon(p) = self {
            p.after_pass(r);
        }
    }

    fn save(&self) -> Vec<u8> {
        match self {
            Run::Photon(p) => p.save(),
            _ => Vec::new(),
        }
    }
}
