//! Sampling the layered BSDF by a random walk (pbrt-v4's
//! `LayeredBxDF::Sample_f`): `f` and `pdf` are the products of the events'
//! values and densities, so `f / pdf` is an unbiased weight while `pdf` is
//! only proportional to the density of the returned direction.

use super::{hg, tr, usable, Layered, WalkRng};
use crate::bsdf::{BsdfSample, TransportMode};
use lumis_math::{Vec2, Vec3};

const SALT: u64 = 0x7361_6d70;

/// `wo` is above the coat (`wo.z > 0`).
pub(super) fn sample(
    l: &Layered,
    wo: Vec3,
    uc: f32,
    u: Vec2,
    mode: TransportMode,
) -> Option<BsdfSample> {
    let first = l.top.sample(wo, uc, u, mode).and_then(usable)?;
    if !first.transmission {
        // Reflected by the coat: an ordinary sample (delta if the coat is smooth).
        return Some(first);
    }
    let [a, b] = super::key(wo);
    let key = uc.to_bits() as u64 | (u.x.to_bits() as u64) << 32;
    let mut rng = WalkRng::new(&[SALT, a, b, key, u.y.to_bits() as u64]);
    let mut f = first.f * first.wi.z.abs();
    let mut pdf = first.pdf;
    let mut delta = first.delta;
    let mut w = first.wi;
    let mut z = l.thickness;
    for depth in 0..l.max_depth {
        let rr = f.max_component() / pdf;
        if depth > 3 && rr < 0.25 {
            let q = (1.0 - rr).max(0.0);
            if rng.next() < q {
                return None;
            }
            pdf *= 1.0 - q;
        }
        if w.z == 0.0 {
            return None;
        }
        if l.albedo.is_black() {
            z = if z == l.thickness { 0.0 } else { l.thickness };
            f *= tr(l.thickness, w);
        } else {
            let dz = -(1.0 - rng.next()).ln() * w.z.abs();
            let zp = if w.z > 0.0 { z + dz } else { z - dz };
            if zp == z {
                return None;
            }
            if 0.0 < zp && zp < l.thickness {
                let (wn, ppdf) = hg::sample(l.g, -w, rng.next2());
                if ppdf == 0.0 || wn.z == 0.0 {
                    return None;
                }
                f *= l.albedo * ppdf; // phase value = its density
                pdf *= ppdf;
                w = wn;
                z = zp;
                delta = false;
                continue;
            }
            z = zp.clamp(0.0, l.thickness);
        }
        let bs = if z == 0.0 {
            l.bottom.sample(-w, rng.next2())
        } else {
            let (uc, u) = (rng.next(), rng.next2());
            l.top.sample(-w, uc, u, mode).and_then(usable)
        }?;
        f *= bs.f;
        pdf *= bs.pdf;
        delta &= bs.delta;
        w = bs.wi;
        if bs.transmission {
            // Out through the coat.
            return Some(BsdfSample {
                wi: w,
                f,
                pdf,
                delta,
                transmission: false,
                eta: 1.0,
            });
        }
        f *= bs.wi.z.abs();
    }
    None
}
