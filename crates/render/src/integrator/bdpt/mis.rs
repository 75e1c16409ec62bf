//! The MIS weight of one connection strategy `(s, t)`: Veach's power
//! heuristic over every strategy that could have made the same path,
//! from the ratios of the densities each vertex has when sampled from the
//! other side (pbrt-v4's `MISWeight`, with squared ratios). Delta vertices
//! cannot be connected, and a delta light cannot be hit: those strategies
//! are left out.
//!
//! With vertex merging (`vcm`, `eta > 0`: Georgiev et al. 2012) every
//! non-delta surface vertex is also where a merge could have made the path:
//! its density is the connection's with the vertex on the camera side,
//! times the light side's density of the vertex, times
//! `eta = pi r^2 N` (the merging disc and the light paths per pass).

use super::vertex::{light_origin_pdf, pdf, to_area, Kind, Vertex};
use crate::bsdf::TransportMode;
use crate::scene::Scene;
use lumis_math::Vec2;

/// The weight of the path joining `light[..s]` and `camera[..t]`;
/// `sampled` replaces `light[0]` (`s == 1`: a light sample) or `camera[0]`
/// (`t == 1`: a camera sample). `eta`: vertex merging's `pi r^2 N` (0:
/// no merging, bdpt).
#[allow(clippy::too_many_arguments)]
pub fn weight(
    scene: &Scene,
    margin: Vec2,
    light: &[Vertex],
    camera: &[Vertex],
    s: usize,
    t: usize,
    sampled: Option<&Vertex>,
    eta: f32,
) -> f32 {
    if s + t == 2 {
        return 1.0;
    }
    let (more_light, fewer_light, _) = sums(scene, margin, light, camera, s, t, sampled, eta);
    1.0 / (1.0 + more_light + fewer_light)
}

/// The weight of the merge of the light subpath `light` (its last vertex
/// the one merged) with the camera subpath `camera` at its last vertex.
pub fn merge_weight(
    scene: &Scene,
    margin: Vec2,
    light: &[Vertex],
    camera: &[Vertex],
    eta: f32,
) -> f32 {
    // The path as the connection of `light` without its last vertex to
    // `camera`: the merge is that connection's strategy with the light
    // side also sampling the camera's last vertex.
    let (s, t) = (light.len() - 1, camera.len());
    let (more_light, fewer_light, pt_rev) = sums(scene, margin, light, camera, s, t, None, eta);
    let connects = light[s - 1].connectible() as u32 as f32;
    let own = remap(pt_rev) * eta;
    own * own / (connects + more_light + fewer_light)
}

/// The power-heuristic sums over the strategies with more and with fewer
/// light vertices than `(s, t)` of their densities over its own, and the
/// light side's density of the camera subpath's last vertex.
#[allow(clippy::too_many_arguments)]
fn sums(
    scene: &Scene,
    margin: Vec2,
    light: &[Vertex],
    camera: &[Vertex],
    s: usize,
    t: usize,
    sampled: Option<&Vertex>,
    eta: f32,
) -> (f32, f32, f32) {
    let lv = |i: usize| -> &Vertex {
        match sampled {
            Some(v) if s == 1 && i == 0 => v,
            _ => &light[i],
        }
    };
    let cv = |i: usize| -> &Vertex {
        match sampled {
            Some(v) if t == 1 && i == 0 => v,
            _ => &camera[i],
        }
    };
    let pt = cv(t - 1);
    let qs = (s > 0).then(|| lv(s - 1));
    let pt_minus = (t > 1).then(|| cv(t - 2));
    let qs_minus = (s > 1).then(|| lv(s - 2));
    // The reverse densities of the four vertices around the connection.
    let pt_rev = match qs {
        Some(qs) => pdf(scene, margin, qs_minus, qs, pt, TransportMode::Importance),
        None => match pt.light {
            Some(li) => light_origin_pdf(scene, li, pt.p),
            None => 0.0,
        },
    };
    let pt_minus_rev = pt_minus.map(|ptm| match (qs, pt.light) {
        (Some(qs), _) => pdf(scene, margin, Some(qs), pt, ptm, TransportMode::Importance),
        (None, Some(li)) => {
            let w = (ptm.p - pt.p).normalize_or_zero();
            to_area(scene.lights[li as usize].pdf_le_dir(pt.ng, w), pt.p, ptm)
        }
        (None, None) => 0.0,
    });
    let qs_rev = qs.map(|qs| pdf(scene, margin, pt_minus, pt, qs, TransportMode::Radiance));
    let qs_minus_rev = qs_minus
        .zip(qs)
        .map(|(qsm, qs)| pdf(scene, margin, Some(pt), qs, qsm, TransportMode::Radiance));
    // Strategies with more light vertices: camera vertices t-1 .. 1 made
    // by the light side instead.
    let camera_rev = |i: usize| match i {
        _ if i == t - 1 => pt_rev,
        _ if i + 2 == t => pt_minus_rev.unwrap_or(0.0),
        _ => cv(i).pdf_rev,
    };
    let more_light = side_sum(
        1..t,
        |i| remap(camera_rev(i)) / remap(cv(i).pdf_fwd),
        |i| (i == t - 1 || !cv(i).delta) && !cv(i - 1).delta,
        // A merge at camera vertex i needs a light vertex before it.
        |i| match s + t - 1 - i >= 1 && mergeable(cv(i), i == t - 1) {
            true => remap(camera_rev(i)) * eta,
            false => 0.0,
        },
        eta,
    );
    // Strategies with fewer light vertices: light vertices s-1 .. 0 made
    // by the camera side instead.
    let light_rev = |i: usize| match i {
        _ if i + 1 == s => qs_rev.unwrap_or(0.0),
        _ if i + 2 == s => qs_minus_rev.unwrap_or(0.0),
        _ => lv(i).pdf_rev,
    };
    let fewer_light = side_sum(
        0..s,
        |i| remap(light_rev(i)) / remap(lv(i).pdf_fwd),
        |i| {
            let before = match i {
                0 => is_delta_light(scene, lv(0)),
                _ => lv(i - 1).delta,
            };
            // The connection's own light vertex `s - 1` may be a delta
            // surface when a merge asks (it ends no connection then).
            let ends = match i + 1 == s {
                true => lv(i).connectible(),
                false => !lv(i).delta,
            };
            ends && !before
        },
        // No merge at the light's own vertex.
        |i| match i >= 1 && mergeable(lv(i), i + 1 == s) {
            true => remap(light_rev(i)) * eta,
            false => 0.0,
        },
        eta,
    );
    (more_light, fewer_light, pt_rev)
}

/// A density of 0 (a vertex after a delta bounce, whose density is a
/// Dirac's) as 1: the same convention for every strategy keeps the weights
/// summing to one (pbrt-v4's `remap0`).
fn remap(f: f32) -> f32 {
    if f != 0.0 {
        f
    } else {
        1.0
    }
}

/// Can a merge happen at `v` (a surface with a non-delta BSDF, reached or
/// left by a non-delta lobe unless it ends its subpath)?
fn mergeable(v: &Vertex, end: bool) -> bool {
    v.kind == Kind::Surface && v.connectible() && (end || !v.delta)
}

/// The sum, over the strategies that hand the vertices of `range` (from
/// its end down) one by one to the other subpath, of their densities over
/// the current one's, squared (the power heuristic): `ratio(i)` is vertex
/// `i`'s reverse over forward density, `counts(i)` whether that strategy
/// can exist (no delta vertex at its connection). With merging (`eta >
/// 0`), `merge(i)` is the density ratio of the merge at vertex `i` before
/// its own reverse density enters (`rev_i * eta`, 0 where none can be).
fn side_sum(
    range: std::ops::Range<usize>,
    ratio: impl Fn(usize) -> f32,
    counts: impl Fn(usize) -> bool,
    merge: impl Fn(usize) -> f32,
    eta: f32,
) -> f32 {
    let (mut ri, mut sum) = (1.0f32, 0.0f32);
    for i in range.rev() {
        if eta > 0.0 {
            let m = merge(i);
            sum += ri * m * m;
        }
        let r = ratio(i);
        ri *= r * r;
        if counts(i) {
            sum += ri;
        }
    }
    sum
}

/// A point light (point, spot, goniometric): no camera path can hit it.
fn is_delta_light(scene: &Scene, v: &Vertex) -> bool {
    match v.kind {
        Kind::Light(li) => scene.lights[li as usize].is_delta(),
        _ => false,
    }
}
