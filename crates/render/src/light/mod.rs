//! Light sources. Every light can be sampled from a reference point (next
//! event estimation) and can emit rays (photon tracing), and knows its power;
//! the [`LightSampler`] picks one in proportion to power. Area lights ask
//! [`Shapes`] about their primitives (sampling is in `geometry`), so lights
//! never depend on the scene.

pub mod area;
pub mod area_texture;
pub mod distant;
pub mod goniometric;
pub mod image_infinite;
pub mod infinite;
pub mod point;
pub mod sampler;
pub mod spot;

pub use area::{AreaLight, LightPoint};
pub use area_texture::{EmissionImage, TexturedEmission};
pub use distant::DistantLight;
pub use goniometric::GoniometricLight;
pub use image_infinite::{EnvMapping, ImageInfiniteLight};
pub use infinite::UniformInfiniteLight;
pub use point::PointLight;
pub use sampler::LightSampler;
pub use spot::SpotLight;

use crate::geometry::Shapes;
use crate::geometry::{Aabb, Ray};
use lumis_math::{Rgb, Vec2, Vec3};

/// A caller's test of the rays it drops as soon as they are emitted
/// (photon emission skips caustic photons that cannot reach a specular
/// shape), which a light may apply before finishing its sample.
pub trait EmitCull {
    /// False only when no ray from `o` whose direction makes the angle with
    /// sine `sin_t` and cosine `cos_t` with the unit vector `n` would be
    /// kept; allowed to err towards true, never towards false.
    fn cone_may_pass(&self, o: Vec3, n: Vec3, sin_t: f32, cos_t: f32) -> bool;

    /// False only when no ray from anywhere on the light whose direction
    /// makes the angle of cosine `cos_t` with its side's normal (`back`:
    /// the side against the normal) would be kept: tested before the
    /// point on the light is sampled. Allowed to err towards true.
    fn polar_may_pass(&self, _back: bool, _cos_t: f32) -> bool {
        true
    }
}

/// The [`EmitCull`] that keeps every ray.
pub struct KeepAll;

impl EmitCull for KeepAll {
    fn cone_may_pass(&self, _: Vec3, _: Vec3, _: f32, _: f32) -> bool {
        true
    }
}

/// A sample of incident light at a reference point.
#[derive(Clone, Copy, Debug)]
pub struct LiSample {
    /// Unit direction from the reference point towards the light.
    pub wi: Vec3,
    pub li: Rgb,
    /// Density per unit solid angle; 1 for delta lights.
    pub pdf: f32,
    /// Point on the light (for shadow rays); far away for infinite lights.
    pub p_light: Vec3,
    pub n_light: Vec3,
    pub delta: bool,
    /// The light is at infinity: the shadow ray is unbounded.
    pub infinite: bool,
}

impl LiSample {
    /// Light from a point source at `pos` whose intensity towards direction
    /// `w` (leaving the light) is `intensity(w)`, seen from `p_ref`; `None`
    /// when `p_ref` is at the light or no light leaves towards it.
    pub fn from_point(pos: Vec3, p_ref: Vec3, intensity: impl Fn(Vec3) -> Rgb) -> Option<LiSample> {
        let d = pos - p_ref;
        let dist2 = d.length_squared();
        if dist2 == 0.0 {
            return None;
        }
        let wi = d / dist2.sqrt();
        let li = intensity(-wi) / dist2;
        if li.is_black() {
            return None;
        }
        Some(LiSample {
            wi,
            li,
            pdf: 1.0,
            p_light: pos,
            n_light: Vec3::ZERO,
            delta: true,
            infinite: false,
        })
    }
}

/// An emitted ray: what photon tracing starts from.
#[derive(Clone, Copy, Debug)]
pub struct LeSample {
    pub ray: Ray,
    /// Emitted radiance (area, infinite) or intensity (point, spot) or radiance of a distant light.
    pub le: Rgb,
    /// Density of the origin per unit area (1 for delta positions).
    pub pdf_pos: f32,
    /// Density of the direction per unit solid angle (1 for delta directions).
    pub pdf_dir: f32,
    /// Surface normal at the origin, or zero.
    pub n: Vec3,
    pub delta_pos: bool,
    pub delta_dir: bool,
}

impl LeSample {
    /// Flux carried by the sampled ray divided by the sample's density:
    /// `Le |cos| / (pdf_pos pdf_dir)` (without the light-choice probability).
    pub fn flux_weight(&self) -> Rgb {
        let cos = if self.n == Vec3::ZERO {
            1.0
        } else {
            self.n.dot(self.ray.d).abs()
        };
        self.le * (cos / (self.pdf_pos * self.pdf_dir))
    }
}

#[derive(Clone, Debug)]
pub enum Light {
    Area(AreaLight),
    Point(PointLight),
    Spot(SpotLight),
    Distant(DistantLight),
    Infinite(UniformInfiniteLight),
    Image(ImageInfiniteLight),
    Goniometric(GoniometricLight),
}

impl Light {
    /// Luminance of the flux (times the photon count) a photon carries when
    /// it leaves this light at `p` (normal `n`) in direction `w` with
    /// emitted luminance `le_lum`: `le cos / (pdf_pos pdf_dir pmf)` with the
    /// densities of [`Light::sample_le`] (`aimed_pdf` replaces the direction
    /// density of an area light's aimed photons); infinite for delta lights.
    #[allow(clippy::too_many_arguments)]
    pub fn emitted_flux(
        &self,
        shapes: &Shapes,
        pmf: f32,
        p: Vec3,
        n: Vec3,
        w: Vec3,
        le_lum: f32,
        aimed_pdf: Option<f32>,
    ) -> f32 {
        match self {
            Light::Area(a) => {
                let pdf_pos = a.pdf_pos(shapes, p);
                let cos = n.dot(w).abs();
                let pdf_dir = match aimed_pdf {
                    Some(pdf) => pdf,
                    None => cos / lumis_math::PI * if a.two_sided { 0.5 } else { 1.0 },
                };
                le_lum * cos / (pdf_pos * pdf_dir * pmf)
            }
            Light::Infinite(l) => {
                le_lum * lumis_math::PI * l.scene_radius * l.scene_radius
                    / (lumis_math::sampling::UNIFORM_SPHERE_PDF * pmf)
            }
            // `w` is the direction of travel; the map was sampled towards `-w`.
            Light::Image(l) => {
                le_lum * lumis_math::PI * l.scene_radius * l.scene_radius / (l.pdf_li(-w) * pmf)
            }
            _ => f32::INFINITY,
        }
    }

    pub fn preprocess(&mut self, scene_bounds: &Aabb) {
        match self {
            Light::Distant(l) => l.preprocess(scene_bounds),
            Light::Infinite(l) => l.preprocess(scene_bounds),
            Light::Image(l) => l.preprocess(scene_bounds),
            _ => {}
        }
    }

    pub fn is_infinite(&self) -> bool {
        matches!(
            self,
            Light::Distant(_) | Light::Infinite(_) | Light::Image(_)
        )
    }

    /// Point, spot and distant lights: a single position or direction.
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Light::Point(_) | Light::Spot(_) | Light::Distant(_) | Light::Goniometric(_)
        )
    }

    pub fn sample_li(&self, shapes: &Shapes, p_ref: Vec3, u: Vec2) -> Option<LiSample> {
        match self {
            Light::Area(l) => l.sample_li(shapes, p_ref, u),
            Light::Point(l) => l.sample_li(p_ref),
            Light::Goniometric(l) => l.sample_li(p_ref),
            Light::Spot(l) => l.sample_li(p_ref),
            Light::Distant(l) => l.sample_li(p_ref),
            Light::Infinite(l) => l.sample_li(p_ref, u),
            Light::Image(l) => l.sample_li(p_ref, u),
        }
    }

    /// Solid-angle density with which `sample_li` from `p_ref` returns the
    /// light point `p_light` (normal `n_light`) in direction `wi`.
    pub fn pdf_li(
        &self,
        shapes: &Shapes,
        p_ref: Vec3,
        wi: Vec3,
        p_light: Vec3,
        n_light: Vec3,
    ) -> f32 {
        match self {
            Light::Area(l) => l.pdf_li(shapes, p_ref, p_light, n_light),
            Light::Infinite(l) => l.pdf_li(wi),
            Light::Image(l) => l.pdf_li(wi),
            _ => 0.0,
        }
    }

    /// Radiance leaving an area light at a point with normal `n` and surface
    /// parameters `uv` (textured emitters) in direction `w`.
    pub fn l(&self, n: Vec3, uv: Vec2, w: Vec3) -> Rgb {
        match self {
            Light::Area(l) => l.l(n, uv, w),
            _ => Rgb::BLACK,
        }
    }

    /// Radiance arriving along an escaped ray with direction `d` (infinite lights).
    pub fn le(&self, d: Vec3) -> Rgb {
        match self {
            Light::Infinite(l) => l.le(d),
            Light::Image(l) => l.le(d),
            _ => Rgb::BLACK,
        }
    }

    pub fn sample_le(&self, shapes: &Shapes, u1: Vec2, u2: Vec2) -> Option<LeSample> {
        self.sample_le_culled(shapes, u1, u2, None::<&KeepAll>)
    }

    /// [`Light::sample_le`], except that a light that can tell early that
    /// `cull` refuses every direction its sample may take returns `None`
    /// before finishing it (area lights; the others ignore `cull`). A
    /// sample it returns is `sample_le`'s.
    pub fn sample_le_culled(
        &self,
        shapes: &Shapes,
        u1: Vec2,
        u2: Vec2,
        cull: Option<&impl EmitCull>,
    ) -> Option<LeSample> {
        match self {
            Light::Area(l) => l.sample_le_culled(shapes, u1, u2, cull),
            Light::Point(l) => l.sample_le(u1),
            Light::Goniometric(l) => l.sample_le(u1),
            Light::Spot(l) => l.sample_le(u1),
            Light::Distant(l) => l.sample_le(u1),
            Light::Infinite(l) => l.sample_le(u1, u2),
            Light::Image(l) => l.sample_le(u1, u2),
        }
    }

    /// Solid-angle density with which [`Light::sample_le`] emits in
    /// direction `w` from its point with normal `n` (zero at a point
    /// light). Lights at infinity emit over a disc and a direction
    /// ([`Light::emitted_flux`] has those densities): 0 here.
    pub fn pdf_le_dir(&self, n: Vec3, w: Vec3) -> f32 {
        match self {
            Light::Area(l) => l.pdf_dir(n, w),
            Light::Point(_) => lumis_math::sampling::UNIFORM_SPHERE_PDF,
            Light::Spot(l) => l.pdf_dir(w),
            Light::Goniometric(l) => l.pdf_dir(w),
            Light::Distant(_) | Light::Infinite(_) | Light::Image(_) => 0.0,
        }
    }

    /// Total emitted power (flux), RGB.
    pub fn power(&self, shapes: &Shapes) -> Rgb {
        match self {
            Light::Area(l) => l.power(shapes),
            Light::Point(l) => l.power(),
            Light::Goniometric(l) => l.power(),
            Light::Spot(l) => l.power(),
            Light::Distant(l) => l.power(),
            Light::Infinite(l) => l.power(),
            Light::Image(l) => l.power(),
        }
    }
}
