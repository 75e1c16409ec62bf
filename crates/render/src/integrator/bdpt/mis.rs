//! The MIS weight of one connection strategy `(s, t)`: Veach's power
//! heuristic over every strategy that could have made the same path,
//! from the ratios of the densities each vertex has when sampled from the
//! other side (pbrt-v4's `MISWeight`, with squared ratios). Delta vertices
//! cannot be connected, and a delta light cannot be hit: those strategies
//! are left out.

use super::vertex::{light_dir_pdf, light_origin_pdf, pdf, to_area, Kind, Vertex};
use crate::bsdf::TransportMode;
use crate::scene::Scene;
use lumis_math::Vec2;

/// The weight of the path joining `light[..s]` and `camera[..t]`;
/// `sampled` replaces `light[0]` (`s == 1`: a light sample) or `camera[0]`
/// (`t == 1`: a camera sample).
pub fn weight(
    scene: &Scene,
    margin: Vec2,
    light: &[Vertex],
    camera: &[Vertex],
    s: usize,
    t: usize,
    sampled: Option<&Vertex>,
) -> f32 {
    if s + t == 2 {
        return 1.0;
    }
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
            to_area(light_dir_pdf(scene, li, pt.ng, w), pt.p, ptm)
        }
        (None, None) => 0.0,
    });
    let qs_rev = qs.map(|qs| pdf(scene, margin, pt_minus, pt, qs, TransportMode::Radiance));
    let qs_minus_rev = qs_minus
        .zip(qs)
        .map(|(qsm, qs)| pdf(scene, margin, Some(pt), qs, qsm, TransportMode::Radiance));
    let remap = |f: f32| if f != 0.0 { f } else { 1.0 };
    let mut sum = 0.0f32;
    // Strategies with more light vertices: camera vertices t-1 .. 1 made
    // by the light side instead.
    let mut ri = 1.0f32;
    for i in (1..t).rev() {
        let v = cv(i);
        let rev = if i == t - 1 {
            pt_rev
        } else if i == t - 2 {
            pt_minus_rev.unwrap_or(0.0)
        } else {
            v.pdf_rev
        };
        let r = remap(rev) / remap(v.pdf_fwd);
        ri *= r * r;
        let delta_here = i != t - 1 && v.delta;
        if !delta_here && !cv(i - 1).delta {
            sum += ri;
        }
    }
    // Strategies with fewer light vertices.
    let mut ri = 1.0f32;
    for i in (0..s).rev() {
        let v = lv(i);
        let rev = if i == s - 1 {
            qs_rev.unwrap_or(0.0)
        } else if i == s - 2 {
            qs_minus_rev.unwrap_or(0.0)
        } else {
            v.pdf_rev
        };
        let r = remap(rev) / remap(v.pdf_fwd);
        ri *= r * r;
        let delta_here = i != s - 1 && v.delta;
        let delta_before = if i > 0 {
            lv(i - 1).delta
        } else {
            is_delta_light(scene, lv(0))
        };
        if !delta_here && !delta_before {
            sum += ri;
        }
    }
    1.0 / (1.0 + sum)
}

/// A point light (point, spot, goniometric): no camera path can hit it.
fn is_delta_light(scene: &Scene, v: &Vertex) -> bool {
    match v.kind {
        Kind::Light(li) => scene.lights[li as usize].is_delta(),
        _ => false,
    }
}
