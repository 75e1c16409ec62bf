//! Direct lighting only: camera paths follow perfectly specular surfaces
//! (up to `max_depth` bounces); at the first other surface, light sampling
//! and BSDF sampling are combined by MIS. A debugging aid.

use super::lighting::{emitted_mis, escaped_mis, sample_direct};
use crate::bsdf::TransportMode;
use crate::geometry::ray::spawn_ray;
use crate::geometry::Ray;
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler};

pub fn li(
    scene: &Scene,
    mut ray: Ray,
    sampler: &mut Sampler,
    max_depth: u32,
    rays: &mut super::RayCounts,
) -> Rgb {
    let mut l = Rgb::BLACK;
    let mut beta = Rgb::WHITE;
    for d in 0..=max_depth {
        if d == 0 {
            rays.camera += 1;
        } else {
            rays.indirect += 1;
        }
        let Some(hit) = scene.intersect(&ray) else {
            return l + beta * escaped_mis(scene, &ray, ray.o, 0.0, true);
        };
        l += beta * emitted_mis(scene, &hit, &ray, ray.o, 0.0, true);
        let bsdf = scene.bsdf(&hit, -ray.d);
        let wo = -ray.d;
        let uc = sampler.get_1d();
        let u = sampler.get_2d();
        if bsdf.is_delta() {
            let Some(bs) = bsdf.sample(wo, uc, u, TransportMode::Radiance) else {
                return l;
            };
            beta *= bs.weight(hit.geom.ns);
            ray = spawn_ray(hit.geom.p, hit.geom.ng, bs.wi);
            continue;
        }
        l += beta * sample_direct(scene, &hit, &bsdf, wo, sampler, rays);
        // BSDF-sampled emission, weighted against the light sample above.
        let Some(bs) = bsdf.sample(wo, uc, u, TransportMode::Radiance) else {
            return l;
        };
        if bs.pdf == 0.0 {
            return l;
        }
        let weight = beta * bs.f * (bs.wi.dot(hit.geom.ns).abs() / bs.pdf);
        let next = spawn_ray(hit.geom.p, hit.geom.ng, bs.wi);
        if bs.delta {
            // The delta lobe of a mixed BSDF (a smooth coat): light sampling
            // cannot find it, so it continues like a specular chain.
            beta = weight;
            ray = next;
            continue;
        }
        rays.indirect += 1;
        match scene.intersect(&next) {
            Some(h2) => l += weight * emitted_mis(scene, &h2, &next, hit.geom.p, bs.pdf, false),
            None => l += weight * escaped_mis(scene, &next, hit.geom.p, bs.pdf, false),
        }
        return l;
    }
    l
}
