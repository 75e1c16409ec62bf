//! Unit tests of the layered BSDF's building blocks; the statistical tests
//! are in `tests/bsdf_layered.rs`.

use super::*;

#[test]
fn transmittance_of_the_slab() {
    let w = Vec3::new(0.6, 0.0, 0.8);
    assert_eq!(tr(0.0, w), 1.0);
    assert!((tr(0.4, w) - (-0.5f32).exp()).abs() < 1e-6);
    assert!((tr(-0.4, -w) - (-0.5f32).exp()).abs() < 1e-6);
}

#[test]
fn walk_numbers_are_keyed_and_below_one() {
    let mut a = WalkRng::new(&[1, 2, 3]);
    let mut b = WalkRng::new(&[1, 2, 3]);
    let mut c = WalkRng::new(&[1, 2, 4]);
    let (x, y, z) = (a.next(), b.next(), c.next());
    assert_eq!(x, y);
    assert_ne!(x, z);
    for _ in 0..10_000 {
        let v = a.next();
        assert!((0.0..1.0).contains(&v));
    }
}

#[test]
fn delta_and_glossy_classes() {
    let diffuse = Base::Diffuse(Diffuse::new(Rgb::splat(0.5)));
    let mirror = Base::Conductor(Conductor::new(Rgb::splat(0.2), Rgb::splat(3.0), 0.0, 0.0));
    let rough = Base::Conductor(Conductor::new(Rgb::splat(0.2), Rgb::splat(3.0), 0.1, 0.1));
    let l = |alpha: f32, base: Base, albedo: f32| {
        Layered::new(
            Dielectric::new(1.5, alpha, alpha),
            base,
            0.01,
            Rgb::splat(albedo),
            0.0,
            10,
            1,
        )
    };
    assert!(l(0.0, mirror, 0.0).is_delta());
    assert!(!l(0.0, mirror, 0.2).is_delta() && l(0.0, mirror, 0.2).has_delta_lobe());
    assert!(!l(0.0, diffuse, 0.0).is_glossy() && l(0.0, diffuse, 0.0).has_delta_lobe());
    assert!(l(0.0, rough, 0.0).is_glossy());
    assert!(l(0.1, diffuse, 0.0).is_glossy() && !l(0.1, diffuse, 0.0).has_delta_lobe());
    assert!(!l(0.5, diffuse, 0.0).is_glossy());
}
