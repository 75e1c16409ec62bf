//! Photon emission from every light type: the flux of the photons stored at
//! their first hit equals the light's power reaching the receiver.

use crate::common;

use lumis_math::PI;
use lumis_render::integrator::photon::aim::{Aims, Targets};
use lumis_render::integrator::photon::trace::{trace_photons, MapKind};
use std::sync::atomic::AtomicBool;

/// Photon passes here are never interrupted.
static NEVER: AtomicBool = AtomicBool::new(false);
use common::*;

const N: u64 = 200_000;

/// Sum of first-hit photon power (luminance) for a scene.
fn first_hit_flux(world: &str) -> f64 {
    let text = format!("Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\n{world}\n");
    let l = load(&text, &Default::default());
    let none = Aims::default();
    let t = trace_photons(&l.scene, N, MapKind::Global, 5, 0, &none, None, &NEVER).unwrap();
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
    check("spot", first_hit_flux(&format!("LightSource \"spot\" \"rgb I\" [ 1 1 1 ] \"float coneangle\" [ 30 ] \"float conedeltaangle\" [ 5 ]\n{ENCLOSURE}")), spot, 0.01);
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
    use common::envmap::{lumpy, write_env};
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
    use common::envmap::{lumpy, write_env};
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

/// Writes a `w` x `h` image of the given texels (row 0 at the top).
fn image(name: &str, w: u32, h: u32, texels: &[[f32; 3]]) -> std::path::PathBuf {
    common::envmap::write_env(name, w, h, |x, y| {
        let t = texels[(y * w + x) as usize];
        lumis_math::Rgb::new(t[0], t[1], t[2])
    })
}

fn lum(c: [f32; 3]) -> f64 {
    lumis_math::Rgb::new(c[0], c[1], c[2]).luminance() as f64
}

/// A 2-texel image interpolated bilinearly with clamping: `a` up to 1/4 of
/// the way, `b` from 3/4, linear between.
fn ramp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * ((t - 0.25) / 0.5).clamp(0.0, 1.0)
}

const A: [f32; 3] = [0.2, 0.4, 1.0];
const B: [f32; 3] = [3.0, 2.0, 0.5];
const QUAD: &str = r#"Shape "trianglemesh" "point3 P" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] "integer indices" [ 0 1 2 0 2 3 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]"#;

/// Textured area lights (an image `filename`) in an absorbing sphere: the
/// photons' total flux is pi (per side) times the image's radiance
/// integrated over the surface, and so is the light's `power`.
#[test]
fn textured_area_lights_emit_their_power() {
    let wide = image("ph-emit-2x1.exr", 2, 1, &[A, B]);
    let tall = image("ph-emit-1x2.exr", 1, 2, &[A, B]);
    let pi = PI as f64;
    // Quad, uv over the unit square once: the texels' mean, times the area 4.
    let quad = pi * 4.0 * (lum(A) + lum(B)) / 2.0;
    // Disk of radii 1 and 1/4, two-sided, scale 2: v = (1 - r) / (3/4), and
    // the image's y = 1 - v (A on top); the area element is 2 pi r dr.
    let m = 100_000;
    let mut disk = 0.0;
    for i in 0..m {
        let r = 0.25 + 0.75 * (i as f64 + 0.5) / m as f64;
        let y = 1.0 - (1.0 - r) / 0.75;
        disk += ramp(lum(A), lum(B), y) * 2.0 * pi * r * 0.75 / m as f64;
    }
    let disk = 2.0 * pi * 2.0 * disk;
    for (label, world, expected) in [
        (
            "textured quad",
            format!(
                "AreaLightSource \"diffuse\" \"string filename\" \"{}\"\n{QUAD}",
                wide.display()
            ),
            quad,
        ),
        (
            "textured disk",
            format!(
                "AreaLightSource \"diffuse\" \"string filename\" \"{}\" \"float scale\" [ 2 ] \"bool twosided\" true\nShape \"disk\" \"float radius\" [ 1 ] \"float innerradius\" [ 0.25 ]",
                tall.display()
            ),
            disk,
        ),
        (
            "textured sphere, power 7",
            format!(
                "AreaLightSource \"diffuse\" \"string filename\" \"{}\" \"float power\" [ 7 ]\nShape \"sphere\" \"float radius\" [ 0.5 ]",
                tall.display()
            ),
            7.0,
        ),
    ] {
        let world = format!("AttributeBegin\n{world}\nAttributeEnd\n{ENCLOSURE}");
        let text = format!("Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\n{world}\n");
        let l = load(&text, &Default::default());
        assert!(l.warnings.is_empty(), "{label}: {:?}", l.warnings);
        let power: f64 = l
            .scene
            .lights
            .iter()
            .map(|x| x.power(&l.scene.shapes).luminance() as f64)
            .sum();
        check(&format!("{label}: power"), power, expected, 1e-3);
        check(&format!("{label}: photons"), first_hit_flux(&world), expected, 2e-3);
    }
}

/// Where photons leave a textured quad: binned by the emitter's uv (8 x 2
/// bins), the flux they carry matches `pi ∫_bin L dA` (a Z-test per bin),
/// and, photons being of nearly equal power, so do their counts.
#[test]
fn textured_photon_origins_follow_the_image() {
    let path = image("ph-origins.exr", 2, 1, &[A, B]);
    let text = format!(
        "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\nAreaLightSource \"diffuse\" \"string filename\" \"{}\"\n{QUAD}\n",
        path.display()
    );
    let l = load(&text, &Default::default());
    let (nu, nv) = (8usize, 2usize);
    let n = 400_000usize;
    let mut flux = vec![0f64; nu * nv];
    let mut flux2 = vec![0f64; nu * nv];
    let mut counts = vec![0f64; nu * nv];
    let mut powers = Vec::with_capacity(n);
    let mut rng = lumis_math::Pcg32::new(11, 3);
    let mut u2 = || lumis_math::Vec2::new(rng.next_f32(), rng.next_f32());
    for _ in 0..n {
        let (li, pmf) = l.scene.light_sampler.sample(u2().x).unwrap();
        let Some(s) = l.scene.lights[li as usize].sample_le(&l.scene.shapes, u2(), u2()) else {
            continue;
        };
        let f = (s.flux_weight() / pmf).luminance() as f64;
        let (u, v) = (
            (s.ray.o.x as f64 + 1.0) / 2.0,
            (s.ray.o.y as f64 + 1.0) / 2.0,
        );
        let b =
            ((v * nv as f64) as usize).min(nv - 1) * nu + ((u * nu as f64) as usize).min(nu - 1);
        flux[b] += f;
        flux2[b] += f * f;
        counts[b] += 1.0;
        powers.push(f);
    }
    let pi = PI as f64;
    let total: f64 = pi * 4.0 * (lum(A) + lum(B)) / 2.0;
    let mut worst_count = 0f64;
    for b in 0..nu * nv {
        let (u0, u1) = ((b % nu) as f64 / nu as f64, (b % nu + 1) as f64 / nu as f64);
        let m = 10_000;
        let mut expected = 0.0;
        for i in 0..m {
            let u = u0 + (u1 - u0) * (i as f64 + 0.5) / m as f64;
            expected += ramp(lum(A), lum(B), u) * (u1 - u0) / m as f64;
        }
        // Bin area in uv is (u1 - u0) / nv; the quad's area is 4 times its uv area.
        let expected = pi * 4.0 * expected / nv as f64;
        let mean = flux[b] / n as f64;
        let se = ((flux2[b] / n as f64 - mean * mean) / n as f64).sqrt();
        let z = (mean - expected) / se;
        let count_dev = counts[b] / n as f64 / (expected / total) - 1.0;
        worst_count = worst_count.max(count_dev.abs());
        eprintln!(
            "bin {b}: flux {mean:.5} expected {expected:.5} z {z:+.2}; count {count_dev:+.4}"
        );
        assert!(
            z.abs() < 4.0,
            "bin {b}: flux {mean} vs {expected} (z {z:.1})"
        );
    }
    let (lo, hi) = powers
        .iter()
        .fold((f64::MAX, 0f64), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let mean_p = powers.iter().sum::<f64>() / powers.len() as f64;
    eprintln!(
        "photon power: min {:.4} max {:.4} of the mean; counts off by at most {worst_count:.4}",
        lo / mean_p,
        hi / mean_p
    );
    assert!(
        worst_count < 0.05,
        "counts do not follow the image: {worst_count}"
    );
    assert!(hi / lo < 1.5, "photon powers differ: {lo} .. {hi}");
}

/// Caustic photons from a textured quad through a glass sphere onto a black
/// floor, emitted everywhere or aimed at the sphere: the same caustic flux
/// (a Z-test between the two sums), many more photons stored when aimed.
#[test]
fn aimed_caustic_photons_from_a_textured_light() {
    let path = image("ph-aim.exr", 2, 1, &[A, B]);
    let text = format!(
        "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\nAttributeBegin\nTranslate 0 0 2\nAreaLightSource \"diffuse\" \"string filename\" \"{}\"\nMaterial \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\nShape \"trianglemesh\" \"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] \"integer indices\" [ 0 2 1 0 3 2 ] \"point2 uv\" [ 0 0  1 0  1 1  0 1 ]\nAttributeEnd\nAttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0.3 0 1\nShape \"sphere\" \"float radius\" [ 0.3 ]\nAttributeEnd\nMaterial \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\nShape \"trianglemesh\" \"point3 P\" [ -9 -9 0  9 -9 0  9 9 0  -9 9 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n",
        path.display()
    );
    let l = load(&text, &Default::default());
    let targets = Targets::from_scene(&l.scene);
    assert!(!targets.is_empty());
    let n = 200_000;
    let sums: Vec<(f64, f64, usize)> = [None, Some(&targets)]
        .into_iter()
        .map(|t| {
            let aims = Aims {
                aim: t.cloned(),
                starts: Targets::starts(&l.scene),
            };
            let tr =
                trace_photons(&l.scene, n, MapKind::Caustic, 7, 5, &aims, None, &NEVER).unwrap();
            let p: Vec<f64> = tr
                .photons
                .iter()
                .map(|p| p.power().luminance() as f64)
                .collect();
            let s: f64 = p.iter().sum();
            let s2: f64 = p.iter().map(|x| x * x).sum();
            // The sum of n per-photon contributions (most of them zero).
            (s, (s2 - s * s / n as f64).max(0.0).sqrt(), p.len())
        })
        .collect();
    let (plain, aimed) = (sums[0], sums[1]);
    let z = (aimed.0 - plain.0) / (plain.1 * plain.1 + aimed.1 * aimed.1).sqrt();
    eprintln!(
        "caustic flux: plain {:.5} ± {:.5} ({} photons), aimed {:.5} ± {:.5} ({} photons), z {z:+.2}",
        plain.0, plain.1, plain.2, aimed.0, aimed.1, aimed.2
    );
    assert!(
        z.abs() < 4.5,
        "aimed and plain caustic fluxes differ: z {z:.1}"
    );
    assert!(plain.1 < 0.05 * plain.0, "too noisy");
    assert!(aimed.2 > 3 * plain.2, "aiming stores more caustic photons");
}

/// Caustic photons are not traced where their first ray misses every shape
/// that can be specular (`Targets::starts`): rays that meet such a shape
/// first, grazing ones included, are never refused, and most others are.
#[test]
fn caustic_photons_are_skipped_only_where_no_specular_shape_can_be_hit() {
    use lumis_math::rng::Pcg32;
    use lumis_math::sampling::square_to_uniform_sphere;
    use lumis_math::{Vec2, Vec3};
    use lumis_render::geometry::Ray;
    // A glass sphere, smooth conductor meshes (a tetrahedron, instanced
    // twice, and another one in the world), a rough conductor and diffuse
    // walls.
    let text = "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\n\
        ObjectBegin \"tet\"\nMaterial \"conductor\"\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0  0.4 0 0  0 0.4 0  0 0 0.4 ] \"integer indices\" [ 0 2 1  0 1 3  0 3 2  1 2 3 ]\nObjectEnd\n\
        AttributeBegin\nTranslate -1 0.2 0.5\nObjectInstance \"tet\"\nAttributeEnd\n\
        AttributeBegin\nTranslate 1 -0.5 0.3\nRotate 40 1 1 0\nObjectInstance \"tet\"\nAttributeEnd\n\
        AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0.2 0.1 1\nShape \"sphere\" \"float radius\" [ 0.3 ]\nAttributeEnd\n\
        AttributeBegin\nMaterial \"conductor\"\nTranslate 0.1 1.2 0.8\nRotate 70 0 1 1\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0  0.5 0 0  0 0.5 0  0 0 0.5 ] \"integer indices\" [ 0 2 1  0 1 3  0 3 2  1 2 3 ]\nAttributeEnd\n\
        AttributeBegin\nMaterial \"conductor\" \"float roughness\" [ 0.05 ]\nShape \"trianglemesh\" \"point3 P\" [ -2 -2 0.01  2 -2 0.01  2 2 0.01  -2 2 0.01 ] \"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n\
        Material \"diffuse\"\nShape \"trianglemesh\" \"point3 P\" [ -9 -9 0  9 -9 0  9 9 0  -9 9 0  -9 -9 5  9 -9 5 ] \"integer indices\" [ 0 1 2 0 2 3  0 1 5  0 5 4 ]\n";
    let l = load(text, &Default::default());
    let scene = &l.scene;
    let never: Vec<bool> = scene.materials.iter().map(|m| m.never_delta()).collect();
    // The rough conductor has no delta part; the smooth ones and glass do.
    assert_eq!(never.iter().filter(|&&n| !n).count(), 3, "{never:?}");
    let starts = Targets::starts(scene).expect("few specular shapes");
    // Rays from anywhere in the room towards points near the specular
    // shapes' surfaces (grazing them) and in random directions.
    let aims = [
        (Vec3::new(0.2, 0.1, 1.0), 0.3),
        (Vec3::new(-0.9, 0.3, 0.6), 0.25),
        (Vec3::new(1.1, -0.4, 0.4), 0.25),
        (Vec3::new(0.2, 1.35, 0.95), 0.3),
    ];
    let mut rng = Pcg32::new(11, 0);
    let mut u2 = || Vec2::new(rng.next_f32(), rng.next_f32());
    let (mut specular, mut skipped, n) = (0, 0, 200_000);
    for i in 0..n {
        let o = Vec3::new(4.0, 4.0, 2.4) * (square_to_uniform_sphere(u2()) * 0.999)
            + Vec3::new(0.0, 0.0, 2.5);
        let d = match i % 2 {
            0 => {
                let (c, r) = aims[i / 2 % aims.len()];
                c + square_to_uniform_sphere(u2()) * r * (0.9 + 0.2 * u2().x) - o
            }
            _ => square_to_uniform_sphere(u2()),
        };
        let ray = Ray::new(o, d * (0.5 + u2().x));
        let can = starts.may_hit(&ray);
        if let Some(h) = scene.intersect(&ray) {
            if !never[h.material as usize] {
                specular += 1;
                assert!(can, "ray {i} from {o:?} along {d:?} hits a specular shape");
            }
        }
        skipped += usize::from(!can);
    }
    eprintln!("{specular} of {n} rays hit a specular shape first; {skipped} skipped");
    assert!(
        specular > n / 10,
        "the rays should often hit the specular shapes"
    );
    assert!(
        skipped > n / 3,
        "most random rays cannot reach them: {skipped}"
    );
}

/// A glass sphere and a smooth conductor tetrahedron with two area lights
/// close to them (wide cones; the second two-sided), for the emission
/// culling tests; each adds a light and [`FLOOR`].
const NEAR_LIGHTS: &str = "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\n\
    AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0.2 0.1 1\nShape \"sphere\" \"float radius\" [ 0.3 ]\nAttributeEnd\n\
    AttributeBegin\nMaterial \"conductor\"\nTranslate -0.6 0.2 0.4\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0  0.4 0 0  0 0.4 0  0 0 0.4 ] \"integer indices\" [ 0 2 1  0 1 3  0 3 2  1 2 3 ]\nAttributeEnd\n\
    AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\nShape \"trianglemesh\" \"point3 P\" [ -0.5 -0.5 1.5  0.5 -0.5 1.5  0.5 0.5 1.5  -0.5 0.5 1.5 ] \"integer indices\" [ 0 2 1 0 3 2 ]\nAttributeEnd\n\
    AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 2 1 1 ] \"bool twosided\" true\nShape \"trianglemesh\" \"point3 P\" [ -1 -1 0.1  1.5 -1 0.3  0 1.5 0.9 ] \"integer indices\" [ 0 1 2 ]\nAttributeEnd\n";
const FLOOR: &str = "Material \"diffuse\"\nShape \"trianglemesh\" \"point3 P\" [ -9 -9 0  9 -9 0  9 9 0  -9 9 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n";

/// The point and direction numbers of emission `i`: a quarter of them
/// (`i % 4 == 1`) with the direction's `x` (or `y`) within 1e-7..1e-4 of
/// 0 or 1, so within as little of the horizon.
fn emission_numbers(
    rng: &mut lumis_math::rng::Pcg32,
    i: usize,
    y: bool,
) -> (lumis_math::Vec2, lumis_math::Vec2) {
    let mut u = || rng.next_f32();
    let u1 = lumis_math::Vec2::new(u(), u());
    let mut u2 = lumis_math::Vec2::new(u(), u());
    if i % 4 == 1 {
        let edge = 10f32.powf(-7.0 + 3.0 * u());
        let v = if u() < 0.5 { edge } else { 1.0 - edge };
        *(if y { &mut u2.y } else { &mut u2.x }) = v;
    }
    (u1, u2)
}

/// Area lights drop a caustic photon before finishing its sample only when
/// no direction at its polar angle can meet a shape that can be specular
/// (`Light::sample_le_culled` with `Targets::starts`): every sample the
/// exact test would keep comes back, bit for bit, and most of those it
/// refuses are dropped early. Lights sit close to the shapes (large cones)
/// and the samples include directions within 1e-7 of the horizon.
#[test]
fn early_dropped_emissions_are_only_those_the_exact_test_refuses() {
    use lumis_math::rng::Pcg32;
    let text = format!("{NEAR_LIGHTS}\
        AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 2 1 ]\nTranslate 0.9 0.1 1.1\nShape \"sphere\" \"float radius\" [ 0.15 ]\nAttributeEnd\n{FLOOR}");
    let l = load(&text, &Default::default());
    let scene = &l.scene;
    let starts = Targets::starts(scene).expect("few specular shapes");
    assert_eq!(
        scene.lights.len(),
        4,
        "two quad triangles, a triangle, a sphere"
    );
    let mut rng = Pcg32::new(5, 3);
    let (mut refused, mut early, mut kept, n) = (0, 0, 0, 400_000);
    for i in 0..n {
        let light = &scene.lights[i % scene.lights.len()];
        let (u1, u2) = emission_numbers(&mut rng, i, false);
        let full = light.sample_le(&scene.shapes, u1, u2);
        let culled = light.sample_le_culled(&scene.shapes, u1, u2, Some(&starts));
        let Some(full) = full else {
            assert!(culled.is_none());
            continue;
        };
        if starts.may_hit(&full.ray) {
            kept += 1;
            let culled = culled.unwrap_or_else(|| panic!("sample {i} refused early: {full:?}"));
            assert_eq!(format!("{culled:?}"), format!("{full:?}"), "sample {i}");
        } else {
            refused += 1;
            early += usize::from(culled.is_none());
        }
    }
    eprintln!("{kept} kept, {refused} refused, {early} of those early");
    assert!(kept > n / 20 && refused > n / 4, "{kept} {refused}");
    // Only the polar angle is tested early: directions at an angle some
    // of whose azimuths meet a sphere pass (here about 30% of refusals).
    assert!(
        early * 10 >= refused * 6,
        "most refusals early: {early} of {refused}"
    );
}

/// A photon the windows refuse is one whose ray `may_hit` refuses, for
/// lights close to the spheres (wide windows), a two-sided light and
/// directions within 1e-7 of the horizon; and the windows refuse most
/// of the photons refused on a light far from the spheres.
#[test]
fn windows_refuse_only_rays_that_miss_every_start() {
    use lumis_math::rng::Pcg32;
    use lumis_math::safe_sqrt;
    use lumis_math::sampling::disk_concentric_radius;
    use lumis_render::integrator::photon::polar::PolarWindows;
    use lumis_render::light::{EmitCull, Light};
    let text = format!("{NEAR_LIGHTS}\
        AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 2 ]\nShape \"trianglemesh\" \"point3 P\" [ 3 3 6  3.2 3 6  3 3.2 6 ] \"integer indices\" [ 0 2 1 ]\nAttributeEnd\n{FLOOR}");
    let l = load(&text, &Default::default());
    let scene = &l.scene;
    let starts = Targets::starts(scene).expect("two specular shapes");
    let windows = PolarWindows::new(scene, &starts);
    assert_eq!(scene.lights.len(), 4, "two quad triangles, two triangles");
    let mut rng = Pcg32::new(9, 1);
    // Per light: refused by `may_hit`, and of those by the windows.
    let mut refused = [(0u32, 0u32); 4];
    for i in 0..400_000 {
        let li = i % scene.lights.len();
        let light = &scene.lights[li];
        let (u1, u2) = emission_numbers(&mut rng, i, true);
        // The side and polar angle `sample_le_culled` gives the windows.
        let Light::Area(area) = light else {
            panic!("area lights only")
        };
        let (back, u) = area.emission_side(u2);
        let sin_t = disk_concentric_radius(u);
        let cos_t = safe_sqrt(1.0 - sin_t * sin_t);
        let pass = windows.cull(li as u32, &starts).polar_may_pass(back, cos_t);
        let Some(full) = light.sample_le(&scene.shapes, u1, u2) else {
            continue;
        };
        if starts.may_hit(&full.ray) {
            assert!(pass, "light {li}, sample {i} refused: {full:?}");
        } else {
            refused[li].0 += 1;
            refused[li].1 += u32::from(!pass);
        }
    }
    eprintln!("refused by may_hit, and of those by the windows: {refused:?}");
    // The far light sees both spheres in a narrow window.
    let (all, early) = refused[3];
    assert!(early * 10 >= all * 8, "{early} of {all}");
}
