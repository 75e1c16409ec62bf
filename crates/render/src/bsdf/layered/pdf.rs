//! Approximate density of the layered BSDF's non-delta samples (after
//! pbrt-v4's `LayeredBxDF::PDF`): the coat's reflection plus a stochastic
//! estimate of the transmit-reflect-transmit paths (one bounce off the
//! base), mixed with the uniform hemisphere (10%) so it is positive wherever
//! `f` can be.
//!
//! Three changes from pbrt-v4 make it integrate to about the share of
//! non-delta samples rather than up to 2: the base's density is carried
//! from inner directions to `wi` by the refraction's Jacobian, renormalised
//! over the escape cone (pbrt-v4 adds densities over inner directions, too
//! dense for narrow cones), the coat's reflection enters with
//! its Fresnel-weighted density (the density `sample` really has), and the
//! paths through the slab with the weight `1 - R(cos theta_o)` of entering
//! it; with a smooth coat the whole estimate is scaled by `1 - R`, the
//! non-delta fraction. The uniform part covers the hemisphere of `wo` only
//! (pbrt-v4: the sphere), as both coats only reflect. These are densities
//! for MIS weights: any positive function keeps the estimators unbiased.

use super::{adjoint, usable, Layered, WalkRng};
use crate::bsdf::fresnel::fr_dielectric;
use crate::bsdf::{Lobes, TransportMode};
use lumis_math::mis::power_heuristic;
use lumis_math::{Vec3, INV_2PI};

const SALT: u64 = 0x7064_6621;

/// `wo`, `wi` above the coat.
pub(super) fn pdf(l: &Layered, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
    let n = l.n_samples;
    let (top, bottom) = (&l.top, &l.bottom);
    let [a, b] = super::key(wi);
    let [c, d] = super::key(wo);
    let mut rng = WalkRng::new(&[SALT, a, b, c, d]);
    let trans = Lobes::Transmission;
    let reflected = top.pdf(wo, wi);
    let mut sum = 0.0;
    for _ in 0..n {
        let wos = top
            .sample_lobes(wo, rng.next(), rng.next2(), mode, trans)
            .and_then(usable);
        let wis = top
            .sample_lobes(wi, rng.next(), rng.next2(), adjoint(mode), trans)
            .and_then(usable);
        let (Some(wos), Some(wis)) = (wos, wis) else {
            continue;
        };
        // The base's density is over inner directions `v = -wis.wi`; over
        // `wi` it is scaled by `dω_v / dω_wi = |cos wi| / (eta² |cos v|)`
        // (exact for a smooth coat, the refraction of `wis` for a rough one),
        // here times eta²: renormalised over the escape cone, as light that
        // misses it is reflected back and escapes later, similarly spread.
        let jacobian = wi.z.abs() / wis.wi.z.abs();
        if top.is_delta() {
            sum += bottom.pdf(-wos.wi, -wis.wi) * jacobian;
            continue;
        }
        // Both the base and the coat's exit may be sampled: MIS of the two
        // estimates of the product density.
        let Some(rs) = bottom.sample(-wos.wi, rng.next2()) else {
            continue;
        };
        if bottom.is_delta() {
            sum += top.pdf(-rs.wi, wi);
        } else {
            let r_pdf = bottom.pdf(-wos.wi, -wis.wi) * jacobian;
            sum += power_heuristic(1.0, wis.pdf, 1.0, r_pdf) * r_pdf;
            let t_pdf = top.pdf(-rs.wi, wi);
            sum += power_heuristic(1.0, rs.pdf, 1.0, t_pdf) * t_pdf;
        }
    }
    let enter = 1.0 - fr_dielectric(wo.z, top.eta);
    if top.is_delta() {
        enter * (0.1 * INV_2PI + 0.9 * sum / n as f32)
    } else {
        0.1 * INV_2PI + 0.9 * (reflected + enter * sum / n as f32)
    }
}
