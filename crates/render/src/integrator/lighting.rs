//! Light sampling and multiple importance sampling shared by integrators.

use crate::bsdf::{SurfaceBsdf, TransportMode};
use crate::geometry::ray::{spawn_ray, spawn_ray_to};
use crate::geometry::Ray;
use crate::light::LiSample;
use crate::scene::{Hit, Scene};
use lumis_math::mis::power_heuristic;
use lumis_math::{Rgb, Sampler, Vec3};

/// Next-event estimation at a hit: one light chosen by power, one point on
/// it, weighted against BSDF sampling by the power heuristic. Consumes
/// three sampler dimensions.
pub fn sample_direct(
    scene: &Scene,
    hit: &Hit,
    bsdf: &SurfaceBsdf,
    wo: Vec3,
    sampler: &mut Sampler,
    rays: &mut super::RayCounts,
) -> Rgb {
    sample_direct_n(scene, hit, bsdf, wo, 1.0, sampler, rays)
}

/// As [`sample_direct`], weighted against `n_bsdf` BSDF samples taken at the
/// same point (e.g. final-gather rays); `n_bsdf = 0` gives full weight.
pub fn sample_direct_n(
    scene: &Scene,
    hit: &Hit,
    bsdf: &SurfaceBsdf,
    wo: Vec3,
    n_bsdf: f32,
    sampler: &mut Sampler,
    rays: &mut super::RayCounts,
) -> Rgb {
    let p = hit.geom.p;
    let Some((ls, pmf)) = sample_light(scene, p, sampler) else {
        return Rgb::BLACK;
    };
    let f = bsdf.eval(wo, ls.wi, TransportMode::Radiance) * ls.wi.dot(hit.geom.ns).abs();
    if f.is_black() {
        return Rgb::BLACK;
    }
    rays.shadow += 1;
    if scene.occluded(&shadow_ray(p, hit.geom.ng, &ls)) {
        return Rgb::BLACK;
    }
    let light_pdf = pmf * ls.pdf;
    if ls.delta {
        return f * ls.li / light_pdf;
    }
    let bsdf_pdf = bsdf.pdf(wo, ls.wi, TransportMode::Radiance);
    let w = power_heuristic(1.0, light_pdf, n_bsdf, bsdf_pdf);
    f * ls.li * (w / light_pdf)
}

/// One light chosen by power and one point on it, seen from `p`, with the
/// light's selection probability; `None` when it gives nothing. Consumes
/// three sampler dimensions.
#[inline]
pub fn sample_light(scene: &Scene, p: Vec3, sampler: &mut Sampler) -> Option<(LiSample, f32)> {
    let ul = sampler.get_1d();
    let u = sampler.get_2d();
    let (li, pmf) = scene.light_sampler.sample(ul)?;
    let ls = scene.lights[li as usize].sample_li(&scene.shapes, p, u)?;
    (ls.pdf != 0.0 && !ls.li.is_black()).then_some((ls, pmf))
}

/// The shadow ray from `p` (geometric normal `ng`) to light sample `ls`:
/// to its point, or unbounded towards a light at infinity.
pub fn shadow_ray(p: Vec3, ng: Vec3, ls: &LiSample) -> Ray {
    if ls.infinite {
        let mut r = spawn_ray(p, ng, ls.wi);
        r.tmax = f32::INFINITY;
        r
    } else {
        spawn_ray_to(p, ng, ls.p_light)
    }
}

/// Emission found by a BSDF-sampled ray, MIS-weighted against light
/// sampling from the previous vertex `p_prev` whose BSDF density was `bsdf_pdf`.
pub fn emitted_mis(
    scene: &Scene,
    hit: &Hit,
    ray: &Ray,
    p_prev: Vec3,
    bsdf_pdf: f32,
    count_fully: bool,
) -> Rgb {
    emitted_mis_n(scene, hit, ray, p_prev, 1.0, bsdf_pdf, count_fully)
}

/// As [`emitted_mis`] for one of `n_bsdf` BSDF samples taken at `p_prev`.
pub fn emitted_mis_n(
    scene: &Scene,
    hit: &Hit,
    ray: &Ray,
    p_prev: Vec3,
    n_bsdf: f32,
    bsdf_pdf: f32,
    count_fully: bool,
) -> Rgb {
    let Some(li) = hit.light else {
        return Rgb::BLACK;
    };
    let light = &scene.lights[li as usize];
    let le = light.l(hit.geom.ng, hit.geom.uv, -ray.d);
    if le.is_black() || count_fully {
        return le;
    }
    let light_pdf = scene.light_sampler.pmf(li)
        * light.pdf_li(&scene.shapes, p_prev, ray.d, hit.geom.p, hit.geom.ng);
    le * power_heuristic(n_bsdf, bsdf_pdf, 1.0, light_pdf)
}

/// Radiance of infinite lights along an escaped ray, MIS-weighted likewise.
pub fn escaped_mis(
    scene: &Scene,
    ray: &Ray,
    p_prev: Vec3,
    bsdf_pdf: f32,
    count_fully: bool,
) -> Rgb {
    escaped_mis_n(scene, ray, p_prev, 1.0, bsdf_pdf, count_fully)
}

/// As [`escaped_mis`] for one of `n_bsdf` BSDF samples taken at `p_prev`.
pub fn escaped_mis_n(
    scene: &Scene,
    ray: &Ray,
    p_prev: Vec3,
    n_bsdf: f32,
    bsdf_pdf: f32,
    count_fully: bool,
) -> Rgb {
    let mut l = Rgb::BLACK;
    for &i in &scene.infinite_lights {
        let light = &scene.lights[i as usize];
        let le = light.le(ray.d);
        if le.is_black() {
            continue;
        }
        if count_fully {
            l += le;
        } else {
            let light_pdf = scene.light_sampler.pmf(i)
                * light.pdf_li(&scene.shapes, p_prev, ray.d, Vec3::ZERO, Vec3::ZERO);
            l += le * power_heuristic(n_bsdf, bsdf_pdf, 1.0, light_pdf);
        }
    }
    l
}
