//! Chi-square tests of the phase functions' sampling against their
//! densities over the sphere (`common/chi2.rs`), for several asymmetries.

use crate::common;

use common::chi2::{self, sidak_alpha, Chi2Config};
use lumis_math::Vec3;
use lumis_render::media::{HenyeyGreenstein, Phase};

#[test]
fn henyey_greenstein_samples_its_density() {
    let gs = [-0.7f32, -0.2, 0.0, 0.3, 0.8, 0.95];
    let wo = Vec3::new(0.3, -0.2, 0.9).normalize();
    for g in gs {
        let phase = Phase::HenyeyGreenstein(HenyeyGreenstein::new(g));
        let out = chi2::run(
            &Chi2Config::default(),
            |u, _| {
                let s = phase.sample(wo, u)?;
                // The sample's density is the one the test checks against.
                let p = phase.pdf(wo, s.wi);
                assert!((s.pdf - p).abs() <= 1e-3 * p, "g {g}: pdf {} vs {p}", s.pdf);
                Some(s.wi)
            },
            |wi| phase.pdf(wo, wi),
        );
        assert!(
            out.passes(sidak_alpha(0.01, gs.len())),
            "g {g}: {}",
            out.report()
        );
    }
}
