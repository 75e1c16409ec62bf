//! Same scene, seed and sample count: bit-identical image, whatever the thread count.

use crate::common;

use common::*;
use lumis_render::load::{Overrides, DEFAULT_SCENE};

#[test]
fn image_is_independent_of_thread_count() {
    for sampler in ["sobol", "independent"] {
        let mut ov = Overrides::default();
        ov.resolution(40, 30).sampler(sampler);
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
    let mut ov = Overrides::default();
    ov.resolution(24, 24)
        .integrator("photon")
        .integrator_param("integer photons", "20000")
        .integrator_param("integer causticphotons", "50000")
        .integrator_param("integer gatherrays", "4");
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
