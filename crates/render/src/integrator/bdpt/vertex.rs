//! Path vertices of bidirectional path tracing and the densities the MIS
//! weights compare: every vertex keeps the area density with which its own
//! subpath sampled it (`pdf_fwd`) and with which the other direction would
//! have (`pdf_rev`), as in Veach's thesis and pbrt-v4.

use crate::bsdf::{SurfaceBsdf, TransportMode};
use crate::light::Light;
use crate::scene::Scene;
use lumis_math::{Rgb, Vec2, Vec3};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// The lens point.
    Camera,
    /// A point on light `u32` (the light subpath's first vertex, or the
    /// one a light sample connects to).
    Light(u32),
    /// A scattering point; `light` if it is on an area light.
    Surface,
}

#[derive(Clone, Copy, Debug)]
pub struct Vertex {
    pub kind: Kind,
    pub p: Vec3,
    /// Geometric normal (zero at a point: pinhole, point and spot lights).
    pub ng: Vec3,
    /// Shading normal (surfaces; `ng` elsewhere).
    pub ns: Vec3,
    /// Throughput of the subpath up to and including this vertex.
    pub beta: Rgb,
    /// Area densities (solid angle for directions at infinity never occur:
    /// infinite and distant lights take part through light sampling and
    /// escaped rays only, see `mod.rs`).
    pub pdf_fwd: f32,
    pub pdf_rev: f32,
    /// The BSDF sampled here was a delta lobe, or the light is a delta light.
    pub delta: bool,
    /// Surfaces: the BSDF (for the outgoing direction `wo`), the emitter on
    /// the surface and its surface parameters.
    pub bsdf: Option<SurfaceBsdf>,
    pub wo: Vec3,
    pub light: Option<u32>,
    pub uv: Vec2,
}

impl Vertex {
    /// The lens point (no normal: densities towards it are never needed).
    pub fn camera(p: Vec3) -> Vertex {
        Vertex {
            kind: Kind::Camera,
            p,
            ng: Vec3::ZERO,
            ns: Vec3::ZERO,
            beta: Rgb::WHITE,
            pdf_fwd: 0.0,
            pdf_rev: 0.0,
            delta: false,
            bsdf: None,
            wo: Vec3::ZERO,
            light: None,
            uv: Vec2::ZERO,
        }
    }

    /// A point on light `li`, for the MIS weights only (a connection to a
    /// light samples its own point: `s = 1`), so no throughput. Its `delta`
    /// stays false: a point light can be connected to; that no path can
    /// hit it is the MIS weights' concern.
    pub fn light(li: u32, p: Vec3, n: Vec3, pdf_fwd: f32) -> Vertex {
        Vertex {
            kind: Kind::Light(li),
            p,
            ng: n,
            ns: n,
            beta: Rgb::BLACK,
            pdf_fwd,
            pdf_rev: 0.0,
            delta: false,
            bsdf: None,
            wo: Vec3::ZERO,
            light: Some(li),
            uv: Vec2::ZERO,
        }
    }

    /// Can a connection end here (a non-delta BSDF, a camera or a light)?
    pub fn connectible(&self) -> bool {
        match self.kind {
            Kind::Surface => self.bsdf.is_some_and(|b| !b.is_delta()),
            _ => true,
        }
    }

    /// The BSDF value here for the pair (`wo`, the direction the subpath
    /// arrived from; `wi`); black at cameras and lights.
    pub fn f(&self, wi: Vec3, mode: TransportMode) -> Rgb {
        match &self.bsdf {
            Some(b) => b.eval(self.wo, wi, mode),
            None => Rgb::BLACK,
        }
    }

    /// `|cos|` of `w` at this vertex (1 at a point).
    pub fn cos(&self, w: Vec3) -> f32 {
        if self.ns == Vec3::ZERO {
            1.0
        } else {
            self.ns.dot(w).abs()
        }
    }
}

/// A solid-angle density at `from` turned into an area density at `to`.
pub fn to_area(pdf: f32, from: Vec3, to: &Vertex) -> f32 {
    let d = to.p - from;
    let d2 = d.length_squared();
    if !(d2 > 0.0) {
        return 0.0;
    }
    let cos = if to.ng == Vec3::ZERO {
        1.0
    } else {
        to.ng.dot(d).abs() / d2.sqrt()
    };
    pdf * cos / d2
}

/// Area density at `next` of continuing a path from `cur`, which it
/// reached from `prev` (`None` at a subpath's first vertex), in transport
/// direction `mode` (radiance: towards the light).
pub fn pdf(
    scene: &Scene,
    margin: Vec2,
    prev: Option<&Vertex>,
    cur: &Vertex,
    next: &Vertex,
    mode: TransportMode,
) -> f32 {
    let w = (next.p - cur.p).normalize_or_zero();
    let dir = match cur.kind {
        Kind::Camera => scene.camera.pdf_dir(cur.p, w, margin),
        Kind::Light(li) => scene.lights[li as usize].pdf_le_dir(cur.ng, w),
        Kind::Surface => {
            let (Some(b), Some(prev)) = (&cur.bsdf, prev) else {
                return 0.0;
            };
            let wp = (prev.p - cur.p).normalize_or_zero();
            b.pdf(wp, w, mode)
        }
    };
    to_area(dir, cur.p, next)
}

/// Area density with which a light subpath starts at `v` (a point on a
/// light): the light's choice times its position density.
pub fn light_origin_pdf(scene: &Scene, li: u32, p: Vec3) -> f32 {
    let pmf = scene.light_sampler.pmf(li);
    match &scene.lights[li as usize] {
        Light::Area(a) => pmf * a.pdf_pos(&scene.shapes, p),
        _ => pmf,
    }
}
