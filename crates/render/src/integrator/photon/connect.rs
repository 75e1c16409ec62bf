//! Caustic photons connected to the camera: the light tracer's strategy as
//! a third caustic technique beside the seed's two (`connectcaustics`).
//!
//! Where the camera sees a caustic directly (`L S+ x E`, `x` the camera
//! ray's first hit), a caustic photon stored at `x` also reaches the lens
//! in one shadow ray: an unbiased estimate, sharp however small the light,
//! and the one that wins where a light tracer sees a caustic (bdpt, whose
//! `t = 1` strategy this is, is 6-160 times better there than the photon
//! density estimate). Such paths are weighed by the balance heuristic over
//! three techniques ([`mis3`]): the photon density estimate (`q_1`), the
//! gather rays (`q_2`) and the connections, with
//! `q_3 = N L_e cos(theta) / (Phi S J)`: per camera sample, the `N / S`
//! photon paths of the iteration (shared by its `S` samples per pixel, as
//! `q_1`'s `alpha` counts them), at the density `J` (pixels per unit area
//! at `x`) a camera sample's hit has there. So `q_3 / q_1 = alpha /
//! (S DeltaA J)`: connections take over where the photon disc covers less
//! than a pixel, and the gather rays keep what they find well (a large
//! light seen through glass).
//!
//! Both sides evaluate the same weights of the same path: the camera side
//! at its hit ([`inv_density`] there), the connections once the
//! iteration's radii are known ([`weigh`]). `J` is measured from the lens
//! centre whatever the lens, a function of `x` alone, so the weights sum to
//! one for every path; the lens point of a connection is sampled as the
//! light tracer samples it.

use super::gather::PhotonCtx;
use super::weights::{mis3, q1};
use crate::accel::Hit;
use crate::bsdf::{SurfaceBsdf, TransportMode};
use crate::geometry::ray::spawn_ray_to;
use crate::scene::Scene;
use lumis_math::{Pcg32, Rgb, Vec2, Vec3, PI};

/// A caustic photon's connection to the camera, before its weight.
#[derive(Clone, Copy, Debug)]
pub struct Connection {
    /// Where it lands on the film (raster, pixels, y down), and the
    /// radiance it brings there at weight 1.
    pub raster: Vec2,
    pub l: Rgb,
    /// The photon's point and geometric normal, what its `q_1` needs
    /// (emitted luminance, `cos(theta)` of its direction on the shading
    /// normal, its power's luminance), and the density a gather ray from
    /// the camera's direction has of the photon's (`q_2` per gather ray:
    /// their count depends on `p`, [`PhotonCtx::gather_rays`]).
    pub p: Vec3,
    pub ng: Vec3,
    pub le: f32,
    pub cos: f32,
    pub power: f32,
    pub p2: f32,
}

/// `1 / J`: the area at `p` (normal `ng`) per pixel of the film that a
/// camera sample's hit there spreads over, seen from the lens centre; 0
/// where `p` is outside the film's reach.
pub fn inv_density(scene: &Scene, p: Vec3, ng: Vec3, margin: Vec2) -> f32 {
    let Some(c) = scene.camera.sample_wi(p, Vec2::splat(0.5), margin) else {
        return 0.0;
    };
    let (w, h) = scene.camera.resolution;
    let j = w as f32 * h as f32 * c.we * c.wi.dot(ng).abs() / c.pdf;
    if j > 0.0 && j.is_finite() {
        1.0 / j
    } else {
        0.0
    }
}

/// The camera connection of a caustic photon of power `power` arriving at
/// `hit` from `wo`: `power f |cos| W_e / pdf` times the film's pixels (the
/// photon set is one estimate of the image, as its powers sum to the
/// emitted flux, while `W_e` integrates to one over the film), if nothing
/// blocks it.
#[allow(clippy::too_many_arguments)]
pub fn to_camera(
    scene: &Scene,
    hit: &Hit,
    bsdf: &SurfaceBsdf,
    wo: Vec3,
    (power, le): (Rgb, f32),
    margin: Vec2,
    rng: &mut Pcg32,
    rays: &mut u64,
) -> Option<Connection> {
    let u = Vec2::new(rng.next_f32(), rng.next_f32());
    let cam = scene.camera.sample_wi(hit.geom.p, u, margin)?;
    let f = bsdf.eval(wo, cam.wi, TransportMode::Importance);
    let (w, h) = scene.camera.resolution;
    let pixels = w as f32 * h as f32;
    let l = power * f * (cam.wi.dot(hit.geom.ns).abs() * cam.we / cam.pdf * pixels);
    if l.is_black() || !l.is_finite() {
        return None;
    }
    *rays += 1;
    if scene.occluded(&spawn_ray_to(hit.geom.p, hit.geom.ng, cam.p_lens)) {
        return None;
    }
    // `q_2` as the camera side computes it: the BSDF seen from the camera.
    let seen = scene.bsdf(hit, cam.wi);
    let pdf = seen.pdf(cam.wi, wo, TransportMode::Radiance);
    Some(Connection {
        raster: cam.p_raster,
        l,
        p: hit.geom.p,
        ng: hit.geom.ng,
        le,
        cos: wo.dot(hit.geom.ns),
        power: power.luminance(),
        p2: pdf,
    })
}

/// `q_1` of a caustic photon path at a first camera hit over `measure`
/// (`DeltaA`, or `1 / J` for `q_3`) and `alpha`: with aimed photons each
/// photon's own power stands for `Phi / N`.
pub fn photon_q(ctx: &PhotonCtx, le: f32, cos: f32, measure: f32, power: f32, alpha: f32) -> f32 {
    if ctx.maps.targets.is_some() {
        q1(1.0, le, cos, measure, power, alpha)
    } else {
        let n = ctx.maps.caustic.emitted() as f64;
        q1(n, le, cos, measure, ctx.maps.phi, alpha)
    }
}

/// The three weights of a caustic path at a first camera hit whose
/// `q_1` over `delta_a` with effective `alpha` and `q_2` are known, given
/// `inv_j` there and `q3_of(measure, alpha)`, `q_1`'s formula.
pub fn weights(
    ctx: &PhotonCtx,
    (q_1, q_2): (f32, f32),
    (delta_a, alpha): (f32, f32),
    inv_j: f32,
    q3_of: impl Fn(f32, f32) -> f32,
) -> [f32; 3] {
    // The connections are a light-side technique, like the map: the gather
    // rays' gain counts against both.
    let s = ctx.alpha_first.max(1.0) * ctx.s.gather_gain;
    let q_3 = q3_of(inv_j, s);
    let r3 = (inv_j / s) / (delta_a / alpha);
    mis3(q_1, q_2, q_3, r3, ctx.s.heuristic)
}

/// The connections of an iteration, each weighted by its `w_3`, once its
/// radii are known.
pub fn weigh(ctx: &PhotonCtx, conns: &[Connection], margin: Vec2) -> Vec<(Vec2, Rgb)> {
    let Some(radii) = ctx.maps.radii.as_ref() else {
        return Vec::new();
    };
    let scene = ctx.scene;
    conns
        .iter()
        .filter_map(|c| {
            let (r2, share) = radii.caustic_at(c.p);
            let delta_a = PI * r2;
            let alpha = ctx
                .alpha(true, || {
                    scene.textures.footprint.pixel_area(c.p, c.ng) * ctx.pixel_spread
                })
                .effective(delta_a);
            let inv_j = inv_density(scene, c.p, c.ng, margin);
            let q_1 = photon_q(ctx, c.le, c.cos, delta_a, c.power, alpha);
            let q3 = |m: f32, s: f32| photon_q(ctx, c.le, c.cos, m, c.power, s);
            let q_2 = super::weights::q2(ctx.gather_rays(share), c.p2);
            let w = weights(ctx, (q_1, q_2), (delta_a, alpha), inv_j, q3)[2];
            (w > 0.0).then_some((c.raster, c.l * w))
        })
        .collect()
}
