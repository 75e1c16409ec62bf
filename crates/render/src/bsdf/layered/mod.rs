//! pbrt-v4's layered BSDF (`LayeredBxDF`, §14.3): a dielectric coat (smooth
//! or rough) over an opaque base (diffuse or conductor), with a homogeneous
//! slab of `thickness` (in mean free paths), single-scattering `albedo` and
//! Henyey-Greenstein `g` between them. Light paths through the slab are
//! followed by a random walk of at most `max_depth` events:
//!
//! - [`Layered::eval`] is an unbiased stochastic estimate of `f` (`n_samples`
//!   walks with next-event estimation towards `wi`),
//! - [`Layered::sample`] returns one walk; its `pdf` is only proportional to
//!   the density (pbrt-v4's `pdfIsProportional`): `f / pdf` is the weight,
//! - [`Layered::pdf`] is a stochastic approximation of the density, mixed
//!   with 10% of the uniform hemisphere.
//!
//! The walks' random numbers are hashed from the directions (and, for
//! `sample`, the sample), so every call is deterministic and `eval` and
//! `pdf` give the same answer for the same arguments. Both coated materials
//! are two-sided, as in pbrt-v4: seen from below, the frame is flipped.

mod eval;
mod hg;
mod pdf;
mod sample;

use super::{BsdfSample, TransportMode};
use super::{Conductor, Dielectric, Diffuse, GLOSSY_ALPHA};
use lumis_math::rng::{hash, mix64};
use lumis_math::{Pcg32, Rgb, Vec2, Vec3, ONE_MINUS_EPSILON};

/// The opaque base under the coat.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Base {
    Diffuse(Diffuse),
    Conductor(Conductor),
}

impl Base {
    fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        match self {
            Base::Diffuse(b) => b.eval(wo, wi),
            Base::Conductor(b) => b.eval(wo, wi),
        }
    }

    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Base::Diffuse(b) => b.pdf(wo, wi),
            Base::Conductor(b) => b.pdf(wo, wi),
        }
    }

    fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        let s = match self {
            Base::Diffuse(b) => b.sample(wo, u),
            Base::Conductor(b) => b.sample(wo, u),
        }?;
        usable(s)
    }

    fn is_delta(&self) -> bool {
        match self {
            Base::Diffuse(_) => false,
            Base::Conductor(b) => b.is_delta(),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layered {
    /// The coat; its inside (-z) is the slab.
    pub top: Dielectric,
    pub bottom: Base,
    /// Slab thickness in mean free paths (at least the smallest normal f32).
    pub thickness: f32,
    /// Single-scattering albedo of the slab (black: no medium).
    pub albedo: Rgb,
    /// Henyey-Greenstein asymmetry in [-1, 1].
    pub g: f32,
    pub max_depth: u32,
    pub n_samples: u32,
}

impl Layered {
    pub fn new(
        top: Dielectric,
        bottom: Base,
        thickness: f32,
        albedo: Rgb,
        g: f32,
        max_depth: u32,
        n_samples: u32,
    ) -> Self {
        Layered {
            top,
            bottom,
            thickness: thickness.max(f32::MIN_POSITIVE),
            albedo,
            g: g.clamp(-1.0, 1.0),
            max_depth,
            n_samples: n_samples.max(1),
        }
    }

    /// Every walk is a chain of delta events: a perfect mirror.
    pub fn is_delta(&self) -> bool {
        self.top.is_delta() && self.bottom.is_delta() && self.albedo.is_black()
    }

    /// Some samples are delta: the smooth coat's own reflection.
    pub fn has_delta_lobe(&self) -> bool {
        self.top.is_delta()
    }

    /// A sharp non-delta lobe: a rough coat or rough metal base below
    /// [`GLOSSY_ALPHA`].
    pub fn is_glossy(&self) -> bool {
        let sharp = |d: &super::microfacet::Microfacet| {
            !d.effectively_smooth() && d.alpha_x.max(d.alpha_y) < GLOSSY_ALPHA
        };
        (!self.top.is_delta() && sharp(&self.top.distrib))
            || matches!(&self.bottom, Base::Conductor(c) if sharp(&c.distrib))
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        if wo.z * wi.z <= 0.0 || self.is_delta() {
            return Rgb::BLACK;
        }
        let (wo, wi) = if wo.z < 0.0 { (-wo, -wi) } else { (wo, wi) };
        eval::f(self, wo, wi, mode)
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        if wo.z * wi.z <= 0.0 || self.is_delta() {
            return 0.0;
        }
        let (wo, wi) = if wo.z < 0.0 { (-wo, -wi) } else { (wo, wi) };
        pdf::pdf(self, wo, wi, mode)
    }

    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let flip = wo.z < 0.0;
        let mut s = sample::sample(self, if flip { -wo } else { wo }, uc, u, mode)?;
        if flip {
            s.wi = -s.wi;
        }
        Some(s)
    }
}

/// The adjoint transport mode (for paths traced from `wi`).
fn adjoint(mode: TransportMode) -> TransportMode {
    match mode {
        TransportMode::Radiance => TransportMode::Importance,
        TransportMode::Importance => TransportMode::Radiance,
    }
}

/// Samples a walk may continue with (pbrt-v4 drops zero values and
/// densities and horizontal directions).
fn usable(s: BsdfSample) -> Option<BsdfSample> {
    (!s.f.is_black() && s.pdf > 0.0 && s.wi.z != 0.0).then_some(s)
}

/// Transmittance across a height `dz` along `w` (unit extinction).
fn tr(dz: f32, w: Vec3) -> f32 {
    if dz.abs() <= f32::MIN_POSITIVE {
        1.0
    } else {
        (-(dz / w.z).abs()).exp()
    }
}

/// Deterministic random numbers for one evaluation, keyed by its arguments.
struct WalkRng(Pcg32);

impl WalkRng {
    fn new(key: &[u64]) -> Self {
        let h = hash(key);
        WalkRng(Pcg32::new(h, mix64(h)))
    }

    fn next(&mut self) -> f32 {
        self.0.next_f32().min(ONE_MINUS_EPSILON)
    }

    fn next2(&mut self) -> Vec2 {
        Vec2::new(self.next(), self.next())
    }
}

/// Bits of a direction, for hashing.
fn key(w: Vec3) -> [u64; 2] {
    [
        w.x.to_bits() as u64 | (w.y.to_bits() as u64) << 32,
        w.z.to_bits() as u64,
    ]
}

#[cfg(test)]
mod tests;
