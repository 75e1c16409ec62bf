//! Bidirectional path tracing (Veach 1997, ch. 10; pbrt-v4's `bdpt`): per
//! camera sample, a camera subpath and a light subpath, every pair of
//! their vertices connected (strategy `(s, t)`: `s` light vertices, `t`
//! camera vertices, path depth `s + t - 2 <= maxdepth`), each
//! contribution weighted by the power heuristic over all strategies that
//! could have sampled the same path (`mis.rs`). Strategies with `t = 1`
//! connect a light vertex to the lens and splat where they land on the
//! film (as `lighttracer`); `s = 1` samples a point on a light (next-event
//! estimation); `s = 0` is a camera path that hit an emitter.
//!
//! Infinite and distant lights start no light subpath (a vertex at
//! infinity would need its own densities): they are reached by light
//! samples and escaped camera rays, weighted against each other as
//! `path` does, and every other strategy has no share in them.
//!
//! For the MIS test, `strategy` renders one `(s, t)` alone, and `mis false`
//! leaves its contributions unweighted: each strategy alone is then an
//! unbiased estimate of the light over paths of its depth.

pub mod mis;
pub mod vertex;
pub mod walk;

use super::driver::SampleCx;
use super::lighting::{escaped_mis, shadow_ray};
use crate::bsdf::TransportMode;
use crate::geometry::ray::spawn_ray_to;
use crate::geometry::Ray;
use crate::scene::Scene;
use lumis_math::mis::power_heuristic;
use lumis_math::{Rgb, Sampler, Vec2, Vec3};
use lumis_scene::ParamSpec;
use std::cell::RefCell;
use vertex::{light_origin_pdf, Vertex};

#[derive(Clone, Debug, PartialEq)]
pub struct BdptSettings {
    pub max_depth: u32,
    /// Render only this `(s, t)` (a debugging and testing aid).
    pub strategy: Option<(u32, u32)>,
    /// Weight the strategies by MIS (false: each at full weight, for one
    /// strategy alone).
    pub mis: bool,
}

impl BdptSettings {
    pub fn new(max_depth: u32) -> BdptSettings {
        BdptSettings {
            max_depth,
            strategy: None,
            mis: true,
        }
    }

    fn wants(&self, s: usize, t: usize) -> bool {
        self.strategy
            .is_none_or(|(a, b)| a as usize == s && b as usize == t)
    }
}

/// The parameters of `Integrator "bdpt"` besides `maxdepth`, declared once.
pub const PARAMS: &[ParamSpec] = &[
    ParamSpec {
        ty: "integer",
        name: "strategy",
        words: "strategy",
        value: "S,T",
        help: "render only the strategy with S light and T camera vertices (testing)",
    },
    ParamSpec {
        ty: "bool",
        name: "mis",
        words: "mis",
        value: "true|false",
        help: "weight the strategies by MIS (false: full weight, for one strategy alone)",
    },
];

thread_local! {
    static PATHS: RefCell<(Vec<Vertex>, Vec<Vertex>)> = const { RefCell::new((Vec::new(), Vec::new())) };
}

/// The radiance of the camera sample `ray` from strategies with `t >= 2`;
/// those with `t = 1` go to `cx`'s splats, scaled by `scale` (the film's
/// pixels over the rendered ones, as for `lighttracer`).
pub fn li(
    scene: &Scene,
    ray: Ray,
    sampler: &mut Sampler,
    st: &BdptSettings,
    scale: f32,
    cx: &mut SampleCx,
) -> Rgb {
    PATHS.with(|cell| {
        let (camera, light) = &mut *cell.borrow_mut();
        let margin = cx.filter.radius;
        let depth = st.max_depth as usize;
        let escape = walk::camera_path(scene, ray, margin, sampler, depth + 2, camera, cx.rays);
        walk::light_path(scene, sampler, depth + 1, light, cx.rays);
        let c = Connect {
            scene,
            st,
            eta: 0.0,
            margin,
            light,
            camera,
        };
        c.all(escape, sampler, scale, cx)
    })
}

/// What the connections of one sample share: the two subpaths and, with
/// vertex merging (`vcm`), its `eta` in the MIS weights (0: bdpt).
pub(crate) struct Connect<'a> {
    pub scene: &'a Scene,
    pub st: &'a BdptSettings,
    pub eta: f32,
    pub margin: Vec2,
    pub light: &'a [Vertex],
    pub camera: &'a [Vertex],
}

impl Connect<'_> {
    /// Every strategy: the radiance of those with `t >= 2` and of the
    /// camera subpath's `escape`; those with `t = 1` splat through `cx`,
    /// scaled by `scale`.
    pub fn all(
        &self,
        escape: Option<walk::Escape>,
        sampler: &mut Sampler,
        scale: f32,
        cx: &mut SampleCx,
    ) -> Rgb {
        let (st, camera, light) = (self.st, self.camera, self.light);
        let depth = st.max_depth as usize;
        let mut l = Rgb::BLACK;
        // `s = 1` samples its own light point: it runs also when the light
        // subpath is empty (a light at infinity was chosen for it).
        for t in 1..=camera.len() {
            for s in 0..=light.len().max(1) {
                let d = (s + t) as isize - 2;
                if (s == 1 && t == 1) || d < 0 || d as usize > depth {
                    continue;
                }
                // Every strategy draws its samples whether it is rendered
                // or not: one strategy alone sees the same paths as all.
                match (s, t) {
                    (_, 1) => {
                        let u = sampler.get_2d();
                        if !st.wants(s, t) {
                            continue;
                        }
                        if let Some((p, v)) = self.to_camera(s, u, cx) {
                            cx.splat_at(p, v * scale);
                        }
                    }
                    (1, _) => {
                        let (ul, u) = (sampler.get_1d(), sampler.get_2d());
                        if st.wants(s, t) {
                            l += self.light_sample(t, ul, u, cx);
                        }
                    }
                    _ if !st.wants(s, t) => {}
                    (0, _) => l += self.emitted(t),
                    _ => l += self.join(s, t, cx),
                }
            }
        }
        if let Some(e) = escape.filter(|_| st.wants(0, camera.len() + 1)) {
            let last = camera.last().expect("the camera vertex");
            let fully = e.specular || !st.mis;
            l += last.beta * escaped_mis(self.scene, &e.ray, last.p, e.pdf, fully);
        }
        l
    }

    fn weight(&self, s: usize, t: usize, sampled: Option<&Vertex>) -> f32 {
        if !self.st.mis {
            return 1.0;
        }
        mis::weight(
            self.scene,
            self.margin,
            self.light,
            self.camera,
            s,
            t,
            sampled,
            self.eta,
        )
    }

    fn visible(&self, from: &Vertex, to: Vec3, cx: &mut SampleCx) -> bool {
        cx.rays.shadow += 1;
        !self.scene.occluded(&spawn_ray_to(from.p, from.ng, to))
    }

    /// `s = 0`: the camera subpath's last vertex is on an emitter.
    fn emitted(&self, t: usize) -> Rgb {
        let pt = &self.camera[t - 1];
        let Some(li) = pt.light else {
            return Rgb::BLACK;
        };
        let le = self.scene.lights[li as usize].l(pt.ng, pt.uv, pt.wo);
        if le.is_black() {
            return Rgb::BLACK;
        }
        pt.beta * le * self.weight(0, t, None)
    }

    /// `s = 1`: a light sample seen from the camera subpath's last vertex.
    fn light_sample(&self, t: usize, ul: f32, u: Vec2, cx: &mut SampleCx) -> Rgb {
        let scene = self.scene;
        let pt = &self.camera[t - 1];
        if !pt.connectible() {
            return Rgb::BLACK;
        }
        let Some((li, pmf)) = scene.light_sampler.sample(ul) else {
            return Rgb::BLACK;
        };
        let light = &scene.lights[li as usize];
        let Some(ls) = light.sample_li(&scene.shapes, pt.p, u) else {
            return Rgb::BLACK;
        };
        if ls.pdf == 0.0 || ls.li.is_black() {
            return Rgb::BLACK;
        }
        let f = pt.f(ls.wi, TransportMode::Radiance) * pt.cos(ls.wi);
        if f.is_black() {
            return Rgb::BLACK;
        }
        let l = pt.beta * f * (ls.li / (pmf * ls.pdf));
        cx.rays.shadow += 1;
        if scene.occluded(&shadow_ray(pt.p, pt.ng, &ls)) {
            return Rgb::BLACK;
        }
        if light.is_infinite() {
            // Only light sampling and escaped rays reach lights at infinity.
            if ls.delta || !self.st.mis {
                return l;
            }
            let bsdf_pdf = pt
                .bsdf
                .map_or(0.0, |b| b.pdf(pt.wo, ls.wi, TransportMode::Radiance));
            return l * power_heuristic(1.0, pmf * ls.pdf, 1.0, bsdf_pdf);
        }
        let v = Vertex::light(
            li,
            ls.p_light,
            ls.n_light,
            light_origin_pdf(scene, li, ls.p_light),
        );
        l * self.weight(1, t, Some(&v))
    }

    /// `t = 1`: the light subpath's vertex `s - 1` seen by the camera: the
    /// raster position and the contribution to splat there.
    fn to_camera(&self, s: usize, u: Vec2, cx: &mut SampleCx) -> Option<(Vec2, Rgb)> {
        let qs = &self.light[s - 1];
        if !qs.connectible() {
            return None;
        }
        let c = self.scene.camera.sample_wi(qs.p, u, self.margin)?;
        let f = qs.f(c.wi, TransportMode::Importance) * qs.cos(c.wi);
        let l = qs.beta * f * (c.we / c.pdf);
        if l.is_black() || !l.is_finite() || !self.visible(qs, c.p_lens, cx) {
            return None;
        }
        let v = Vertex::camera(c.p_lens);
        Some((c.p_raster, l * self.weight(s, 1, Some(&v))))
    }

    /// `s, t >= 2`: the two subpaths' last vertices joined by a segment.
    fn join(&self, s: usize, t: usize, cx: &mut SampleCx) -> Rgb {
        let (qs, pt) = (&self.light[s - 1], &self.camera[t - 1]);
        if !qs.connectible() || !pt.connectible() {
            return Rgb::BLACK;
        }
        let d = pt.p - qs.p;
        let d2 = d.length_squared();
        if !(d2 > 0.0) {
            return Rgb::BLACK;
        }
        let w = d / d2.sqrt();
        let g = qs.cos(w) * pt.cos(w) / d2;
        let l = qs.beta
            * qs.f(w, TransportMode::Importance)
            * pt.f(-w, TransportMode::Radiance)
            * pt.beta
            * g;
        if l.is_black() || !l.is_finite() || !self.visible(qs, pt.p, cx) {
            return Rgb::BLACK;
        }
        l * self.weight(s, t, None)
    }
}
