//! Same scene, seed and sample count: bit-identical image, whatever the thread count.

mod support;

use lumis_math::SamplerKind;
use lumis_render::load::{BuildOverrides, DEFAULT_SCENE};
use support::*;

#[test]
fn image_is_independent_of_thread_count() {
    for sampler in [SamplerKind::Sobol, SamplerKind::Independent] {
        let ov = BuildOverrides {
            resolution: Some((40, 30)),
            sampler: Some(sampler),
            ..Default::default()
        };
        let l = load(DEFAULT_SCENE, &ov);
        let one = render_loaded(&l, 8, 3, 1).film.mean_image();
        let two = render_loaded(&l, 8, 3, 2).film.mean_image();
        let four = render_loaded(&l, 8, 3, 4).film.mean_image();
        assert!(
            one.iter()
                .zip(&two)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "{sampler:?}: 1 vs 2 threads"
        );
        assert!(
            one.iter()
                .zip(&four)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "{sampler:?}: 1 vs 4 threads"
        );
        // A different seed gives a different image.
        let other = render_loaded(&l, 8, 4, 2).film.mean_image();
        assert!(one != other);
    }
}

#[test]
fn photon_image_is_independent_of_thread_count() {
    let mut ov = BuildOverrides {
        resolution: Some((24, 24)),
        integrator: Some("photon".into()),
        ..Default::default()
    };
    ov.photon.photons = Some(20_000);
    ov.photon.caustic_photons = Some(50_000);
    ov.photon.gather_rays = Some(4);
    let l = load(DEFAULT_SCENE, &ov);
    let one = render_loaded(&l, 2, 3, 1).film.mean_image();
    let two = render_loaded(&l, 2, 3, 2).film.mean_image();
    assert!(
        one.iter()
            .zip(&two)
            .all(|(a, b)| a.to_bits() == b.to_bits()),
        "photon: 1 vs 2 threads"
    );
    let other = render_loaded(&l, 2, 4, 2).film.mean_image();
    assert!(
        one != other,
        "a different seed must change the photon maps and the image"
    );
}
