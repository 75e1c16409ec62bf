//! Photon emission from every light type: the flux of the photons stored at
//! their first hit equals the light's power reaching the receiver.

mod support;

use lumis_math::PI;
use lumis_render::integrator::photon::trace::{trace_photons, MapKind};
use support::*;

const N: u64 = 200_000;

/// Sum of first-hit photon power (luminance) for a scene.
fn first_hit_flux(world: &str) -> f64 {
    let text = format!("Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\n{world}\n");
    let l = load(&text, &Default::default());
    let t = trace_photons(&l.scene, N, MapKind::Global, 5, 0, None);
    t.photons.iter().map(|p| p.power().luminance() as f64).sum()
}

fn check(label: &str, got: f64, expected: f64, rel_tol: f64) {
    let rel = got / expected - 1.0;
    eprintln!(
        "{label}: {got:.5} expected {expected:.5} ({:+.3}%)",
        rel * 100.0
    );
    assert!(rel.abs() < rel_tol, "{label}: {:+.3}%", rel * 100.0);
}

const ENCLOSURE: &str = "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\nShape \"sphere\" \"float radius\" [ 3 ]\nAttributeEnd";

#[test]
fn point_spot_and_area_lights_emit_their_power() {
    // Every photon of an enclosed light lands once: the total is the power
    // exactly (up to 16-bit float rounding of each photon's power).
    check(
        "point",
        first_hit_flux(&format!(
            "LightSource \"point\" \"rgb I\" [ 1 1 1 ]\n{ENCLOSURE}"
        )),
        4.0 * PI as f64,
        1e-3,
    );
    let (start, end) = ((25f64).to_radians().cos(), (30f64).to_radians().cos());
    let spot = 2.0 * std::f64::consts::PI * ((1.0 - start) + (start - end) / 2.0);
    // Spot photons are uniform in the outer cone and weighted by the falloff: a Monte Carlo sum.
    check("spot", first_hit_flux(&format!("LightSource \"spot\" \"rgb I\" [ 1 1 1 ] \"float coneangle\" [ 30 ] \"float conedelta\" [ 5 ]\n{ENCLOSURE}")), spot, 0.01);
    let area = PI as f64 * 4.0 * PI as f64 * 0.04;
    check("area sphere", first_hit_flux(&format!("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\nShape \"sphere\" \"float radius\" [ 0.2 ]\nAttributeEnd\n{ENCLOSURE}")), area, 1e-3);
}

#[test]
fn distant_and_infinite_lights_emit_their_power() {
    // A unit sphere under a distant light of radiance-scale 1 intercepts pi r^2;
    // in a uniform environment of radiance 1 it receives pi L * 4 pi r^2.
    // The photons that hit are a binomial fraction: tolerance of a few percent.
    let d = first_hit_flux("LightSource \"distant\" \"rgb L\" [ 1 1 1 ] \"point3 from\" [ 0 0 1 ] \"point3 to\" [ 0 0 0 ]\nShape \"sphere\" \"float radius\" [ 1 ]");
    check("distant", d, PI as f64, 0.02);
    let i = first_hit_flux(
        "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\nShape \"sphere\" \"float radius\" [ 1 ]",
    );
    check("infinite", i, 4.0 * (PI as f64).powi(2), 0.02);
}

/// The textured emitter: photons from an image environment light. A unit
/// sphere intercepts `pi R² ∫ L dω` whatever the map's shape; `∫ L dω` by an
/// independent quadrature of the light's radiance. Binomial hit fraction:
/// a few percent.
#[test]
fn image_infinite_light_emits_its_power() {
    use support::envmap::{lumpy, write_env};
    for (name, w, h) in [("ph-ea.exr", 32, 32), ("ph-ll.exr", 64, 32)] {
        let path = write_env(name, w, h, lumpy(w, h));
        let world = format!(
            "Rotate 50 1 1 0\nLightSource \"infinite\" \"string filename\" \"{}\"\nIdentity\nShape \"sphere\" \"float radius\" [ 1 ]",
            path.display()
        );
        let text = format!("Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\n{world}\n");
        let l = load(&text, &Default::default());
        let light = &l.scene.lights[0];
        let mut rng = lumis_math::Pcg32::new(8, 8);
        let n = 2_000_000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let d = lumis_math::sampling::square_to_uniform_sphere(lumis_math::Vec2::new(
                rng.next_f32(),
                rng.next_f32(),
            ));
            sum += light.le(d).luminance() as f64;
        }
        let integral = sum * 4.0 * PI as f64 / n as f64;
        check(name, first_hit_flux(&world), PI as f64 * integral, 0.03);
    }
}

/// The goniometric light (a textured point emitter) inside an absorbing
/// sphere: every photon lands once, carrying the power set by `power`.
#[test]
fn goniometric_light_emits_its_power() {
    use support::envmap::{lumpy, write_env};
    let path = write_env("ph-gonio.exr", 16, 16, lumpy(16, 16));
    check(
        "goniometric",
        first_hit_flux(&format!(
            "Rotate 40 1 1 0\nLightSource \"goniometric\" \"string filename\" \"{}\" \"float power\" [ 7 ]\nIdentity\n{ENCLOSURE}",
            path.display()
        )),
        7.0,
        1e-3,
    );
}
