//! Scattering functions in the local shading frame (normal along +z).
//!
//! Conventions follow pbrt-v4: `wo` and `wi` both point away from the
//! surface, `f` excludes the cosine factor and densities are per unit solid
//! angle. Reflection-only BSDFs are two-sided (they reflect in whichever
//! hemisphere `wo` lies); the dielectric distinguishes outside (+z) from
//! inside (-z). The thin dielectric and diffuse transmission are symmetric
//! sheets: they transmit into the other hemisphere, whichever side `wo` is on.

mod conductor;
mod dielectric;
mod diffuse;
mod diffuse_transmission;
pub mod fresnel;
pub mod layered;
pub mod microfacet;
mod phong;
mod thin_dielectric;

pub use conductor::Conductor;
pub use dielectric::Dielectric;
pub use diffuse::Diffuse;
pub use diffuse_transmission::DiffuseTransmission;
pub use layered::Layered;
pub use phong::Phong;
pub use thin_dielectric::ThinDielectric;

use lumis_math::{Frame, Rgb, Vec2, Vec3};

/// What a path carries: radiance (camera paths) or importance (light paths).
/// Only refraction is not symmetric between the two (pbrt-v4 §9.5.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TransportMode {
    Radiance,
    Importance,
}

/// Which lobes a sample may come from (pbrt-v4's `BxDFReflTransFlags`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lobes {
    All,
    Reflection,
    Transmission,
}

impl Lobes {
    /// Probabilities of choosing reflection and transmission when the
    /// Fresnel reflectance is `r`, renormalised over the allowed lobes.
    #[inline]
    pub fn choice(self, r: f32) -> (f32, f32) {
        match self {
            Lobes::All => (r, 1.0 - r),
            Lobes::Reflection if r > 0.0 => (1.0, 0.0),
            Lobes::Transmission if r < 1.0 => (0.0, 1.0),
            _ => (0.0, 0.0),
        }
    }
}

/// Result of [`Bsdf::sample`].
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// Sampled incident direction (local frame for [`Bsdf`], world space for
    /// [`SurfaceBsdf`]).
    pub wi: Vec3,
    /// BSDF value (without cosine). For delta lobes, the Fresnel-weighted
    /// value divided by `|cos wi|`.
    pub f: Rgb,
    /// Solid-angle density; for delta lobes the discrete probability of the
    /// chosen lobe. When [`Bsdf::pdf_is_proportional`], a non-delta sample's
    /// `pdf` from [`Bsdf::sample`] is only proportional to the density (only
    /// `f / pdf` is meaningful); [`SurfaceBsdf::sample`] replaces it by
    /// [`Bsdf::pdf`] and scales `f` alike, so integrators see one density
    /// for MIS from both strategies.
    pub pdf: f32,
    /// A perfectly specular lobe was sampled.
    pub delta: bool,
    /// `wi` is on the other side of the surface than `wo`.
    pub transmission: bool,
    /// Relative IOR crossed along the sampled path (1 for reflection).
    pub eta: f32,
}

impl BsdfSample {
    /// The path throughput factor of this sample at a surface with shading
    /// normal `ns` (world-space samples): `f |cos| / pdf`.
    #[inline]
    pub fn weight(&self, ns: Vec3) -> Rgb {
        self.f * (self.wi.dot(ns).abs() / self.pdf)
    }
}

/// All BSDFs of lumis.
#[derive(Clone, Copy, Debug)]
pub enum Bsdf {
    Diffuse(Diffuse),
    Conductor(Conductor),
    Dielectric(Dielectric),
    Phong(Phong),
    ThinDielectric(ThinDielectric),
    DiffuseTransmission(DiffuseTransmission),
    Layered(Layered),
}

impl Bsdf {
    /// BSDF value for the pair of local directions; 0 for delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        match self {
            Bsdf::Diffuse(b) => b.eval(wo, wi),
            Bsdf::Conductor(b) => b.eval(wo, wi),
            Bsdf::Dielectric(b) => b.eval(wo, wi, mode),
            Bsdf::Phong(b) => b.eval(wo, wi),
            Bsdf::ThinDielectric(_) => Rgb::BLACK,
            Bsdf::DiffuseTransmission(b) => b.eval(wo, wi),
            Bsdf::Layered(b) => b.eval(wo, wi, mode),
        }
    }

    /// Solid-angle density with which [`Self::sample`] produces `wi` through
    /// its non-delta lobes.
    /// For [`Bsdf::Layered`] a stochastic (hashed, deterministic) estimate.
    pub fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        match self {
            Bsdf::Diffuse(b) => b.pdf(wo, wi),
            Bsdf::Conductor(b) => b.pdf(wo, wi),
            Bsdf::Dielectric(b) => b.pdf(wo, wi),
            Bsdf::Phong(b) => b.pdf(wo, wi),
            Bsdf::ThinDielectric(_) => 0.0,
            Bsdf::DiffuseTransmission(b) => b.pdf(wo, wi),
            Bsdf::Layered(b) => b.pdf(wo, wi, mode),
        }
    }

    /// Non-delta samples carry a density only proportional to the true one
    /// (pbrt-v4's `pdfIsProportional`): the layered BSDF's random walk.
    pub fn pdf_is_proportional(&self) -> bool {
        matches!(self, Bsdf::Layered(_))
    }

    /// Sample an incident direction given the outgoing one. `uc` chooses
    /// between lobes, `u` samples within a lobe.
    ///
    /// Never returns a sample with zero or non-finite value, zero density or
    /// `wi` on the horizon: those are `None`.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample> {
        let bs = match self {
            Bsdf::Diffuse(b) => b.sample(wo, u),
            Bsdf::Conductor(b) => b.sample(wo, u),
            Bsdf::Dielectric(b) => b.sample(wo, uc, u, mode),
            Bsdf::Phong(b) => b.sample(wo, uc, u),
            Bsdf::ThinDielectric(b) => b.sample(wo, uc),
            Bsdf::DiffuseTransmission(b) => b.sample(wo, uc, u),
            Bsdf::Layered(b) => b.sample(wo, uc, u, mode),
        }?;
        if bs.f.is_black()
            || !bs.f.is_finite()
            || bs.pdf.is_nan()
            || bs.pdf <= 0.0
            || bs.wi.z == 0.0
        {
            return None;
        }
        Some(bs)
    }

    /// Every lobe is perfectly specular: `eval` and `pdf` are always zero.
    pub fn is_delta(&self) -> bool {
        match self {
            Bsdf::Diffuse(_) | Bsdf::Phong(_) | Bsdf::DiffuseTransmission(_) => false,
            Bsdf::ThinDielectric(_) => true,
            Bsdf::Conductor(b) => b.is_delta(),
            Bsdf::Dielectric(b) => b.is_delta(),
            Bsdf::Layered(b) => b.is_delta(),
        }
    }

    /// Not delta, yet some samples are delta (a smooth coat over a rough or
    /// diffuse base): `eval` and `pdf` leave that lobe out, so integrators
    /// must follow delta samples as they follow delta BSDFs.
    pub fn has_delta_lobe(&self) -> bool {
        match self {
            Bsdf::Layered(b) => !b.is_delta() && b.has_delta_lobe(),
            _ => false,
        }
    }

    pub fn has_transmission(&self) -> bool {
        matches!(
            self,
            Bsdf::Dielectric(_) | Bsdf::ThinDielectric(_) | Bsdf::DiffuseTransmission(_)
        )
    }

    /// Non-delta but sharply peaked: a photon density estimate is blurry here,
    /// so the photon integrator continues along the lobe instead of reading
    /// the global map (METHOD.md section 4). Microfacet alpha below
    /// [`GLOSSY_ALPHA`], or a Phong lobe with exponent above [`GLOSSY_EXPONENT`].
    pub fn is_glossy(&self) -> bool {
        match self {
            Bsdf::Diffuse(_) | Bsdf::ThinDielectric(_) | Bsdf::DiffuseTransmission(_) => false,
            Bsdf::Conductor(b) => {
                !b.is_delta() && b.distrib.alpha_x.max(b.distrib.alpha_y) < GLOSSY_ALPHA
            }
            Bsdf::Dielectric(b) => {
                !b.is_delta() && b.distrib.alpha_x.max(b.distrib.alpha_y) < GLOSSY_ALPHA
            }
            Bsdf::Phong(b) => b.exponent > GLOSSY_EXPONENT && b.ks.max_component() > 0.0,
            Bsdf::Layered(b) => b.is_glossy(),
        }
    }

    /// Diffuse reflectance when the BSDF is Lambertian (for radiance photons).
    pub fn diffuse_albedo(&self) -> Option<Rgb> {
        match self {
            Bsdf::Diffuse(d) => Some(d.r),
            _ => None,
        }
    }
}

/// Microfacet roughness (alpha) below which a surface counts as glossy.
pub const GLOSSY_ALPHA: f32 = 0.4;
/// Phong exponent above which a surface counts as glossy.
pub const GLOSSY_EXPONENT: f32 = 8.0;

impl From<Diffuse> for Bsdf {
    fn from(b: Diffuse) -> Self {
        Bsdf::Diffuse(b)
    }
}
impl From<Conductor> for Bsdf {
    fn from(b: Conductor) -> Self {
        Bsdf::Conductor(b)
    }
}
impl From<Dielectric> for Bsdf {
    fn from(b: Dielectric) -> Self {
        Bsdf::Dielectric(b)
    }
}
impl From<Layered> for Bsdf {
    fn from(b: Layered) -> Self {
        Bsdf::Layered(b)
    }
}
impl From<Phong> for Bsdf {
    fn from(b: Phong) -> Self {
        Bsdf::Phong(b)
    }
}
impl From<ThinDielectric> for Bsdf {
    fn from(b: ThinDielectric) -> Self {
        Bsdf::ThinDielectric(b)
    }
}
impl From<DiffuseTransmission> for Bsdf {
    fn from(b: DiffuseTransmission) -> Self {
        Bsdf::DiffuseTransmission(b)
    }
}

/// World-space wrapper used by integrators: a BSDF in a shading frame.
///
/// For BSDFs without transmission, directions on opposite sides of the
/// geometric normal `ng` never scatter (eval and pdf are 0, samples are
/// rejected): this keeps shading normals from leaking light through opaque
/// surfaces. Transmissive BSDFs classify reflection/transmission by the
/// shading frame only.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceBsdf {
    /// Shading frame.
    pub frame: Frame,
    /// Geometric normal, world space.
    pub ng: Vec3,
    pub bsdf: Bsdf,
}

impl SurfaceBsdf {
    pub fn new(frame: Frame, ng: Vec3, bsdf: Bsdf) -> Self {
        SurfaceBsdf { frame, ng, bsdf }
    }

    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        self.frame.to_local(v)
    }

    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.frame.to_world(v)
    }

    #[inline]
    fn sides_allowed(&self, wo: Vec3, wi: Vec3) -> bool {
        self.bsdf.has_transmission() || wo.dot(self.ng) * wi.dot(self.ng) > 0.0
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        let (wo_l, wi_l) = (self.to_local(wo), self.to_local(wi));
        if wo_l.z == 0.0 || !self.sides_allowed(wo, wi) {
            return Rgb::BLACK;
        }
        self.bsdf.eval(wo_l, wi_l, mode)
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        let (wo_l, wi_l) = (self.to_local(wo), self.to_local(wi));
        if wo_l.z == 0.0 || !self.sides_allowed(wo, wi) {
            return 0.0;
        }
        self.bsdf.pdf(wo_l, wi_l, mode)
    }

    /// Sample; the returned `wi` is in world space.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample> {
        let wo_l = self.to_local(wo);
        if wo_l.z == 0.0 {
            return None;
        }
        let mut bs = self.bsdf.sample(wo_l, uc, u, mode)?;
        bs.wi = self.to_world(bs.wi);
        if !self.sides_allowed(wo, bs.wi) {
            return None;
        }
        if !bs.delta && self.bsdf.pdf_is_proportional() {
            // As pbrt-v4's integrators do for proportional densities: MIS
            // needs the density that `pdf` gives for this direction (the
            // same world-space vectors, hence the same hashed estimate), and
            // the weight `f / pdf` is kept.
            let pdf = self.pdf(wo, bs.wi, mode);
            if !(pdf > 0.0) {
                return None;
            }
            bs.f *= pdf / bs.pdf;
            bs.pdf = pdf;
        }
        Some(bs)
    }

    pub fn is_delta(&self) -> bool {
        self.bsdf.is_delta()
    }

    /// See [`Bsdf::has_delta_lobe`].
    pub fn has_delta_lobe(&self) -> bool {
        self.bsdf.has_delta_lobe()
    }

    pub fn is_glossy(&self) -> bool {
        self.bsdf.is_glossy()
    }

    pub fn has_transmission(&self) -> bool {
        self.bsdf.has_transmission()
    }
}

/// `a` and `b` lie strictly in the same hemisphere of the local frame.
#[inline]
pub(crate) fn same_hemisphere(a: Vec3, b: Vec3) -> bool {
    a.z * b.z > 0.0
}

/// Mirror about the local normal.
#[inline]
pub(crate) fn reflect_z(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_blocks_leaks_through_opaque() {
        // Shading normal tilted from the geometric one.
        let ns = Vec3::new(0.5, 0.0, 1.0).normalize();
        let ng = Vec3::Z;
        let s = SurfaceBsdf::new(
            Frame::from_normal(ns),
            ng,
            Diffuse::new(Rgb::splat(0.5)).into(),
        );
        let wo = Vec3::new(0.0, 0.0, 1.0);
        // Above the shading plane but below the geometric surface.
        let wi = Vec3::new(0.9, 0.0, -0.2).normalize();
        assert!(s.to_local(wi).z > 0.0);
        assert!(s.eval(wo, wi, TransportMode::Radiance).is_black());
        assert_eq!(s.pdf(wo, wi, TransportMode::Radiance), 0.0);
        let wi2 = Vec3::new(0.1, 0.2, 0.9).normalize();
        let e = s.eval(wo, wi2, TransportMode::Radiance);
        assert!((e.g - 0.5 / lumis_math::PI).abs() < 1e-6);
    }

    #[test]
    fn surface_sample_is_world_space() {
        let n = Vec3::new(0.0, 1.0, 0.0);
        let s = SurfaceBsdf::new(
            Frame::from_normal(n),
            n,
            Conductor::new(Rgb::splat(0.2), Rgb::splat(3.0), 0.0, 0.0).into(),
        );
        let wo = Vec3::new(0.6, 0.8, 0.0);
        let bs = s
            .sample(wo, 0.5, Vec2::new(0.3, 0.3), TransportMode::Radiance)
            .unwrap();
        assert!(bs.delta);
        assert!((bs.wi - Vec3::new(-0.6, 0.8, 0.0)).length() < 1e-5);
    }
}
