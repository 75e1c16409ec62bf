//! Statistical tests of BSDF sampling: chi-square goodness of fit of
//! `sample()` against `pdf()`, consistency of sampled values with `eval()` and
//! `pdf()`, reciprocity, and the exact behaviour of the smooth (delta) BSDFs.

use crate::common;

use common::chi2::{self, Chi2Config};
use lumis_math::{sampling::square_to_uniform_sphere, Pcg32, Rgb, Vec2, Vec3};
use lumis_render::bsdf::{
    fresnel::{fr_complex_rgb, fr_dielectric},
    microfacet::Microfacet,
    Bsdf, Conductor, Dielectric, Diffuse, DiffuseTransmission, Phong, ThinDielectric,
    TransportMode,
};

/// Overall significance of all chi-square tests in this file.
const ALPHA: f64 = 0.01;

struct Case {
    name: String,
    bsdf: Bsdf,
    wo: Vec3,
    /// `cos theta_i` of lines across which the pdf jumps.
    z_breaks: Vec<f64>,
}

/// Unit direction with the given `cos theta` and an azimuth that is not
/// aligned with the frame axes (so anisotropy matters).
fn dir(cos_theta: f32) -> Vec3 {
    let s = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let phi = 0.7f32;
    Vec3::new(s * phi.cos(), s * phi.sin(), cos_theta)
}

fn diffuse_cases() -> Vec<Case> {
    [0.9, 0.5, 0.1, -0.5]
        .iter()
        .map(|&c| Case {
            name: format!("diffuse cos_o {c}"),
            bsdf: Diffuse::new(Rgb::new(0.5, 0.7, 0.9)).into(),
            wo: dir(c),
            z_breaks: vec![],
        })
        .collect()
}

fn conductor_cases() -> Vec<Case> {
    let mut v = Vec::new();
    for (ax, ay) in [(0.05, 0.05), (0.2, 0.2), (0.5, 0.5), (0.1, 0.4)] {
        for c in [0.9, 0.5, 0.1] {
            v.push(Case {
                name: format!("conductor alpha ({ax}, {ay}) cos_o {c}"),
                bsdf: Conductor::new(Rgb::new(0.2, 0.9, 1.1), Rgb::new(3.9, 2.4, 2.2), ax, ay)
                    .into(),
                wo: dir(c),
                z_breaks: vec![],
            });
        }
    }
    // Two-sided: seen from below.
    v.push(Case {
        name: "conductor alpha (0.2, 0.2) cos_o -0.5".into(),
        bsdf: Conductor::from_reflectance(Rgb::splat(0.8), 0.2, 0.2).into(),
        wo: dir(-0.5),
        z_breaks: vec![],
    });
    // Beckmann: sampled by D cos, not by visible normals.
    for (ax, ay) in [(0.05, 0.05), (0.3, 0.3), (0.1, 0.4)] {
        for c in [0.9, 0.5, 0.1, -0.5] {
            let m = Microfacet::beckmann(ax, ay);
            v.push(Case {
                name: format!("beckmann conductor alpha ({ax}, {ay}) cos_o {c}"),
                bsdf: Conductor::with_microfacet(
                    Rgb::new(0.2, 0.9, 1.1),
                    Rgb::new(3.9, 2.4, 2.2),
                    m,
                )
                .into(),
                wo: dir(c),
                z_breaks: vec![],
            });
        }
    }
    v
}

/// The rough dielectric's transmission pdf jumps where the generalized half
/// vector `etap wi + wo` becomes horizontal (GGX's D does not vanish at the
/// horizon; on one side the microfacet is back-facing): at
/// `cos theta_i = -cos theta_o / etap`.
fn dielectric_break(eta: f32, wo: Vec3) -> Vec<f64> {
    let etap = if wo.z > 0.0 { eta } else { 1.0 / eta };
    vec![-(wo.z as f64) / etap as f64]
}

fn dielectric_cases() -> Vec<Case> {
    let mut v = Vec::new();
    for eta in [1.5, 1.0 / 1.5] {
        for alpha in [0.1, 0.3] {
            for c in [0.9, 0.5, 0.1, -0.9, -0.5, -0.1] {
                v.push(Case {
                    name: format!("dielectric eta {eta:.3} alpha {alpha} cos_o {c}"),
                    bsdf: Dielectric::new(eta, alpha, alpha).into(),
                    wo: dir(c),
                    z_breaks: dielectric_break(eta, dir(c)),
                });
            }
        }
    }
    for c in [0.5, -0.5] {
        v.push(Case {
            name: format!("dielectric eta 1.5 alpha (0.1, 0.3) cos_o {c}"),
            bsdf: Dielectric::new(1.5, 0.1, 0.3).into(),
            wo: dir(c),
            z_breaks: dielectric_break(1.5, dir(c)),
        });
    }
    for (ax, ay) in [(0.2, 0.2), (0.1, 0.3)] {
        for c in [0.9, 0.3, -0.5, -0.9] {
            v.push(Case {
                name: format!("beckmann dielectric eta 1.5 alpha ({ax}, {ay}) cos_o {c}"),
                bsdf: Dielectric::with_microfacet(1.5, Microfacet::beckmann(ax, ay)).into(),
                wo: dir(c),
                z_breaks: dielectric_break(1.5, dir(c)),
            });
        }
    }
    v
}

fn phong_cases() -> Vec<Case> {
    let mut v = Vec::new();
    for n in [1.0, 10.0, 100.0] {
        for (kd, ks) in [(0.5, 0.3), (0.0, 0.8), (0.8, 0.1)] {
            for c in [0.9, 0.5, 0.1] {
                v.push(Case {
                    name: format!("phong n {n} kd {kd} ks {ks} cos_o {c}"),
                    bsdf: Phong::new(Rgb::splat(kd), Rgb::new(ks, ks * 0.5, ks), n).into(),
                    wo: dir(c),
                    z_breaks: vec![],
                });
            }
        }
    }
    v
}

/// Lobe weights by the largest channel: reflection-heavy, transmission-heavy,
/// pure reflection, pure transmission; `wo` on both sides.
fn diffuse_transmission_cases() -> Vec<Case> {
    let mut v = Vec::new();
    for (r, t) in [
        (Rgb::new(0.25, 0.5, 0.1), Rgb::new(0.1, 0.2, 0.15)),
        (Rgb::splat(0.25), Rgb::new(0.9, 0.3, 0.6)),
        (Rgb::splat(0.7), Rgb::BLACK),
        (Rgb::BLACK, Rgb::splat(0.6)),
    ] {
        for c in [0.8, 0.2, -0.6] {
            v.push(Case {
                name: format!("diffusetransmission R {r:?} T {t:?} cos_o {c}"),
                bsdf: DiffuseTransmission::new(r, t).into(),
                wo: dir(c),
                z_breaks: vec![],
            });
        }
    }
    v
}

fn all_cases() -> Vec<Case> {
    let mut v = diffuse_cases();
    v.extend(conductor_cases());
    v.extend(dielectric_cases());
    v.extend(phong_cases());
    v.extend(diffuse_transmission_cases());
    v
}

/// Run the chi-square test on every case, collecting all failures.
fn chi2_family(cases: Vec<Case>) {
    let alpha = chi2::sidak_alpha(ALPHA, all_cases().len());
    let cfg = Chi2Config::default();
    let mut failures = Vec::new();
    for (i, case) in cases.iter().enumerate() {
        let (bsdf, wo) = (case.bsdf, case.wo);
        let mode = TransportMode::Radiance;
        let cfg = Chi2Config {
            seed: 1000 + i as u64,
            z_breaks: case.z_breaks.clone(),
            ..cfg.clone()
        };
        let out = chi2::run(
            &cfg,
            |u, uc| {
                bsdf.sample(wo, uc, u, mode)
                    .filter(|s| !s.delta)
                    .map(|s| s.wi)
            },
            |wi| bsdf.pdf(wo, wi, mode),
        );
        // The pdf must integrate to the fraction of (non-delta) samples
        // produced: up to binomial noise and quadrature error.
        let mass_ok = (out.pdf_mass - out.sampled_fraction).abs() < 2e-3;
        let ok = out.passes(alpha) && mass_ok;
        println!(
            "{}: {} {}",
            case.name,
            out.report(),
            if ok { "ok" } else { "FAIL" }
        );
        if !ok {
            failures.push(format!("{}: {}", case.name, out.report()));
        }
    }
    assert!(
        failures.is_empty(),
        "chi2 failures (alpha {alpha:.2e}):\n{}",
        failures.join("\n")
    );
}

#[test]
fn chi2_diffuse() {
    chi2_family(diffuse_cases());
}

#[test]
fn chi2_conductor() {
    chi2_family(conductor_cases());
}

#[test]
fn chi2_dielectric() {
    chi2_family(dielectric_cases());
}

#[test]
fn chi2_phong() {
    chi2_family(phong_cases());
}

#[test]
fn chi2_diffuse_transmission() {
    chi2_family(diffuse_transmission_cases());
}

/// The lobes are chosen by the largest channel of R and T: the fraction of
/// transmitted samples is `max T / (max R + max T)` (binomial, 4.5 sigma).
#[test]
fn diffuse_transmission_lobe_choice() {
    let (r, t) = (Rgb::new(0.25, 0.5, 0.1), Rgb::new(0.1, 0.2, 0.3));
    let b: Bsdf = DiffuseTransmission::new(r, t).into();
    assert!(!b.is_delta() && b.has_transmission() && !b.is_glossy());
    assert!(b.diffuse_albedo().is_none());
    let mut rng = Pcg32::new(5, 5);
    for c in [0.7f32, -0.4] {
        let wo = dir(c);
        let n = 100_000;
        let mut transmitted = 0;
        for _ in 0..n {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            let s = b
                .sample(wo, rng.next_f32(), u, TransportMode::Radiance)
                .unwrap();
            assert_eq!(s.transmission, s.wi.z * wo.z < 0.0);
            assert!(!s.delta && s.eta == 1.0);
            let want = if s.transmission { t } else { r };
            assert!((0..3).all(|k| (s.f[k] - want[k] * lumis_math::INV_PI).abs() < 1e-7));
            transmitted += s.transmission as u32;
        }
        let p = 0.3 / 0.8;
        let f = transmitted as f64 / n as f64;
        assert!(
            (f - p).abs() < 4.5 * (p * (1.0 - p) / n as f64).sqrt(),
            "cos {c}: {f} vs {p}"
        );
    }
    // Nothing to scatter: no sample, zero pdf.
    let black: Bsdf = DiffuseTransmission::new(Rgb::BLACK, Rgb::BLACK).into();
    assert!(black
        .sample(Vec3::Z, 0.5, Vec2::new(0.5, 0.5), TransportMode::Radiance)
        .is_none());
    assert_eq!(black.pdf(Vec3::Z, -Vec3::Z, TransportMode::Radiance), 0.0);
}

// ---------------------------------------------------------------------------
// The harness itself must be able to fail.

#[test]
fn chi2_harness_detects_wrong_pdf() {
    let cfg = Chi2Config {
        samples: 200_000,
        ..Chi2Config::default()
    };
    let bsdf: Bsdf = Diffuse::new(Rgb::WHITE).into();
    let wo = dir(0.7);
    let sampler = |u: Vec2, uc: f32| {
        bsdf.sample(wo, uc, u, TransportMode::Radiance)
            .map(|s| s.wi)
    };
    // Correct pdf passes.
    let good = chi2::run(&cfg, sampler, |wi| {
        bsdf.pdf(wo, wi, TransportMode::Radiance)
    });
    assert!(good.passes(0.01), "{}", good.report());
    // Uniform hemisphere instead of cosine: rejected.
    let bad = chi2::run(&cfg, sampler, |wi| {
        if wi.z > 0.0 {
            0.5 / lumis_math::PI
        } else {
            0.0
        }
    });
    assert!(!bad.passes(1e-6), "{}", bad.report());
    // A slightly too wide Phong lobe is rejected too.
    let p: Bsdf = Phong::new(Rgb::BLACK, Rgb::splat(0.9), 20.0).into();
    let q: Bsdf = Phong::new(Rgb::BLACK, Rgb::splat(0.9), 18.0).into();
    let bad = chi2::run(
        &cfg,
        |u, uc| p.sample(wo, uc, u, TransportMode::Radiance).map(|s| s.wi),
        |wi| q.pdf(wo, wi, TransportMode::Radiance),
    );
    assert!(!bad.passes(1e-6), "{}", bad.report());
}

#[test]
fn chi2_distribution_values() {
    // Reference quantiles of the chi-square distribution.
    for (x, k, p) in [
        (3.841_458_8, 1, 0.05),
        (18.307_038, 10, 0.05),
        (6.634_897, 1, 0.01),
        (124.342_113, 100, 0.05),
        (0.114_831_8, 3, 0.99),
    ] {
        let q = chi2::chi2_sf(x, k);
        assert!(
            (q - p).abs() < 1e-6 * p.max(1e-3) * 100.0,
            "sf({x}, {k}) = {q}, want {p}"
        );
    }
    // Large dof: chi2 = dof is near the median.
    let q = chi2::chi2_sf(10_000.0, 10_000);
    assert!((q - 0.4967).abs() < 2e-3, "{q}");
    assert!((chi2::ln_gamma(10.0) - 362_880f64.ln()).abs() < 1e-10);
    assert!((chi2::ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-10);
    let gl = chi2::gauss_legendre(5);
    let int: f64 = gl.iter().map(|&(x, w)| w * x.powi(8)).sum();
    assert!((int - 2.0 / 9.0).abs() < 1e-12);
}

// ---------------------------------------------------------------------------
// Sampled values agree with eval() and pdf().

fn rel_close(a: f32, b: f32, tol: f32) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()) || (a.abs() < 1e-30 && b.abs() < 1e-30)
}

#[test]
fn sample_matches_eval_and_pdf() {
    let mut rng = Pcg32::new(77, 1);
    let mut bad = Vec::new();
    for case in all_cases() {
        for mode in [TransportMode::Radiance, TransportMode::Importance] {
            let mut checked = 0;
            for _ in 0..20_000 {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                let Some(s) = case.bsdf.sample(case.wo, rng.next_f32(), u, mode) else {
                    continue;
                };
                assert!(!s.delta);
                assert!(s.pdf > 0.0 && s.f.is_finite(), "{}: {s:?}", case.name);
                assert!((s.wi.length() - 1.0).abs() < 1e-4, "{}: {s:?}", case.name);
                assert_eq!(s.transmission, s.wi.z * case.wo.z < 0.0, "{}", case.name);
                let f = case.bsdf.eval(case.wo, s.wi, mode);
                let pdf = case.bsdf.pdf(case.wo, s.wi, mode);
                let ok =
                    rel_close(s.pdf, pdf, 1e-3) && (0..3).all(|c| rel_close(s.f[c], f[c], 1e-3));
                if !ok && bad.len() < 20 {
                    bad.push(format!(
                        "{} {mode:?}: wi {:?} sample f {:?} pdf {} vs eval {:?} pdf {}",
                        case.name, s.wi, s.f, s.pdf, f, pdf
                    ));
                }
                checked += 1;
            }
            assert!(checked > 5_000, "{}: only {checked} samples", case.name);
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

// ---------------------------------------------------------------------------
// Reciprocity.

#[test]
fn reciprocity() {
    let mut rng = Pcg32::new(3, 9);
    let mut uniform = || square_to_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
    for case in all_cases() {
        let b = case.bsdf;
        for _ in 0..2000 {
            let (wo, wi) = (uniform(), uniform());
            if wo.z * wi.z > 0.0 {
                // Reflection is symmetric in either mode.
                for mode in [TransportMode::Radiance, TransportMode::Importance] {
                    let (a, c) = (b.eval(wo, wi, mode), b.eval(wi, wo, mode));
                    for k in 0..3 {
                        assert!(rel_close(a[k], c[k], 1e-3), "{}: {a:?} vs {c:?}", case.name);
                    }
                }
            } else {
                // Transmission: the importance BTDF is the adjoint of the
                // radiance one, f_imp(wo, wi) = f_rad(wi, wo).
                // The generalized half vector `eta wi + wo` loses relative
                // precision in f32 when it is nearly tangent (its z is a
                // difference), where D is tiny: allow a small absolute error.
                let a = b.eval(wo, wi, TransportMode::Importance);
                let c = b.eval(wi, wo, TransportMode::Radiance);
                assert!(
                    (a.g - c.g).abs() <= 1e-3 * a.g.max(c.g) + 1e-5,
                    "{}: {wo:?} {wi:?}: {a:?} vs {c:?}",
                    case.name
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Smooth (delta) BSDFs.

#[test]
fn smooth_conductor_is_an_exact_mirror() {
    let (eta, k) = (Rgb::new(0.2, 0.9, 1.1), Rgb::new(3.9, 2.4, 2.2));
    let b: Bsdf = Conductor::new(eta, k, 0.0, 0.0).into();
    assert!(b.is_delta() && !b.has_transmission());
    for c in [1.0, 0.7, 0.2, -0.6] {
        let wo = dir(c);
        let s = b
            .sample(wo, 0.3, Vec2::new(0.1, 0.9), TransportMode::Radiance)
            .unwrap();
        assert!(s.delta && !s.transmission && s.eta == 1.0);
        assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z));
        let w = s.f * (s.wi.z.abs() / s.pdf);
        let fr = fr_complex_rgb(wo.z.abs(), eta, k);
        for i in 0..3 {
            assert!((w[i] - fr[i]).abs() < 1e-5);
        }
        assert!(b.eval(wo, s.wi, TransportMode::Radiance).is_black());
        assert_eq!(b.pdf(wo, s.wi, TransportMode::Radiance), 0.0);
    }
}

#[test]
fn smooth_dielectric_fresnel_split() {
    let b: Bsdf = Dielectric::new(1.5, 0.0, 0.0).into();
    assert!(b.is_delta() && b.has_transmission());
    let r0 = ((1.5f32 - 1.0) / (1.5 + 1.0)).powi(2);
    assert!((fr_dielectric(1.0, 1.5) - r0).abs() < 1e-6);
    let mut rng = Pcg32::new(4, 4);
    for c in [1.0f32, 0.8, 0.3, -1.0, -0.95] {
        let wo = dir(c);
        let r = fr_dielectric(c, 1.5);
        let n = 200_000;
        let mut transmitted = 0;
        for _ in 0..n {
            let s = b
                .sample(
                    wo,
                    rng.next_f32(),
                    Vec2::new(0.5, 0.5),
                    TransportMode::Radiance,
                )
                .unwrap();
            assert!(s.delta);
            if s.transmission {
                transmitted += 1;
            }
        }
        let frac = transmitted as f64 / n as f64;
        let sd = ((1.0 - r as f64) * r as f64 / n as f64).sqrt();
        assert!(
            (frac - (1.0 - r as f64)).abs() < 4.0 * sd + 1e-6,
            "cos {c}: {frac} vs {}",
            1.0 - r
        );
    }
}

#[test]
fn smooth_dielectric_snell_and_weights() {
    for eta in [1.5f32, 1.0 / 1.33] {
        let b: Bsdf = Dielectric::new(eta, 0.0, 0.0).into();
        for c in [0.95f32, 0.6, 0.2, -0.95, -0.6, -0.2] {
            let wo = dir(c);
            let r = fr_dielectric(c, eta);
            // Reflection branch (uc = 0 < R unless R = 0).
            let s = b
                .sample(wo, 0.0, Vec2::ZERO, TransportMode::Radiance)
                .unwrap();
            assert!(!s.transmission && s.eta == 1.0);
            assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z));
            assert!((s.pdf - r).abs() < 1e-6 && (s.f.g * s.wi.z.abs() - r).abs() < 1e-6);
            if r >= 1.0 {
                continue;
            }
            // Transmission branch.
            for mode in [TransportMode::Radiance, TransportMode::Importance] {
                let s = b.sample(wo, 0.999_999, Vec2::ZERO, mode).unwrap();
                assert!(s.transmission && s.delta);
                assert!(s.wi.z * wo.z < 0.0);
                // Snell: eta_i sin_i = eta_t sin_t; etap = eta_t / eta_i.
                let etap = if c > 0.0 { eta } else { 1.0 / eta };
                assert!((s.eta - etap).abs() < 1e-6);
                let (sin_o, sin_i) = (wo.truncate().length(), s.wi.truncate().length());
                assert!(
                    (sin_o - etap * sin_i).abs() < 1e-5,
                    "{sin_o} vs {etap} * {sin_i}"
                );
                // Azimuth opposite.
                assert!(wo.truncate().normalize().dot(s.wi.truncate().normalize()) < -0.9999);
                let w = s.f.g * s.wi.z.abs() / s.pdf;
                let expect = if mode == TransportMode::Radiance {
                    1.0 / (etap * etap)
                } else {
                    1.0
                };
                assert!((w - expect).abs() < 1e-5, "{mode:?}: {w} vs {expect}");
            }
        }
    }
}

#[test]
fn smooth_dielectric_total_internal_reflection() {
    let eta = 1.5f32;
    let b: Bsdf = Dielectric::new(eta, 0.0, 0.0).into();
    let crit = (1.0 / eta).asin();
    let mut rng = Pcg32::new(8, 8);
    for theta in [crit + 0.01, crit + 0.3, 1.5] {
        let wo = dir(-theta.cos());
        for _ in 0..1000 {
            let s = b
                .sample(wo, rng.next_f32(), Vec2::ZERO, TransportMode::Radiance)
                .unwrap();
            assert!(!s.transmission && s.pdf == 1.0);
            assert!((s.f.g * s.wi.z.abs() - 1.0).abs() < 1e-6);
        }
    }
    // Just inside the critical angle, some light escapes.
    let wo = dir(-(crit - 0.01).cos());
    let s = b
        .sample(wo, 0.999, Vec2::ZERO, TransportMode::Radiance)
        .unwrap();
    assert!(s.transmission);
}

#[test]
fn index_matched_dielectric_passes_through() {
    for alpha in [0.0, 0.3] {
        let b: Bsdf = Dielectric::new(1.0, alpha, alpha).into();
        assert!(b.is_delta());
        for c in [0.9f32, 0.1, -0.4] {
            let wo = dir(c);
            for uc in [0.0, 0.5, 0.99] {
                let s = b
                    .sample(wo, uc, Vec2::new(0.2, 0.7), TransportMode::Radiance)
                    .unwrap();
                assert!(s.transmission && s.delta && s.pdf == 1.0 && s.eta == 1.0);
                assert!((s.wi + wo).length() < 1e-6);
                assert!((s.f.g * s.wi.z.abs() - 1.0).abs() < 1e-6);
            }
        }
    }
}

/// pbrt-v4's ThinDielectricBxDF: `R' = R + T^2 R / (1 - R^2)`, `T' = 1 - R'`,
/// a mirror reflection and straight-through transmission, both delta, chosen
/// in proportion to `R'` and `T'`; every sample's weight `f |cos| / pdf` is
/// exactly `R' + T' = 1`.
#[test]
fn thin_dielectric_formula_and_weights() {
    for eta in [1.5f32, 1.33, 1.0 / 1.5, 2.4] {
        let b: Bsdf = ThinDielectric::new(eta).into();
        assert!(b.is_delta() && b.has_transmission() && !b.is_glossy());
        for c in [1.0f32, 0.8, 0.3, 0.05, -0.2, -0.9] {
            let wo = dir(c);
            let r = fr_dielectric(c.abs(), eta);
            let t = 1.0 - r;
            // Total internal reflection (eta < 1): R' = 1.
            let r2 = if r < 1.0 {
                r + t * t * r / (1.0 - r * r)
            } else {
                1.0
            };
            let t2 = 1.0 - r2;
            // Reflection branch.
            let s = b
                .sample(wo, 0.0, Vec2::new(0.3, 0.6), TransportMode::Radiance)
                .unwrap();
            assert!(s.delta && !s.transmission && s.eta == 1.0);
            assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z));
            assert!(
                (s.pdf - r2).abs() < 1e-6,
                "eta {eta} cos {c}: {} vs {r2}",
                s.pdf
            );
            assert!((s.f.g * s.wi.z.abs() - r2).abs() < 1e-6);
            if t2 == 0.0 {
                continue;
            }
            // Transmission branch, in both modes (no radiance scaling).
            for mode in [TransportMode::Radiance, TransportMode::Importance] {
                let s = b.sample(wo, 0.999_999, Vec2::ZERO, mode).unwrap();
                assert!(s.delta && s.transmission && s.eta == 1.0);
                assert_eq!(s.wi, -wo);
                assert!((s.pdf - t2).abs() < 1e-6);
                assert!((s.f.g * s.wi.z.abs() - t2).abs() < 1e-6);
                assert!((s.f.g * s.wi.z.abs() / s.pdf - 1.0).abs() < 1e-5);
            }
            assert!(b.eval(wo, -wo, TransportMode::Radiance).is_black());
            assert_eq!(b.pdf(wo, -wo, TransportMode::Radiance), 0.0);
        }
    }
    // Normal incidence, eta 1.5: R = 0.04, R' = 2R / (1 + R) = 0.0769...
    let b: Bsdf = ThinDielectric::new(1.5).into();
    let s = b
        .sample(Vec3::Z, 0.0, Vec2::ZERO, TransportMode::Radiance)
        .unwrap();
    assert!((s.pdf - 0.08 / 1.04).abs() < 1e-6);
    // The branch frequencies follow R' and T'.
    let mut rng = Pcg32::new(6, 6);
    let wo = dir(0.2);
    let r2 = {
        let r = fr_dielectric(0.2, 1.5);
        r + (1.0 - r) * (1.0 - r) * r / (1.0 - r * r)
    };
    let n = 200_000;
    let mut reflected = 0;
    for _ in 0..n {
        let s = b
            .sample(wo, rng.next_f32(), Vec2::ZERO, TransportMode::Importance)
            .unwrap();
        reflected += !s.transmission as u32;
    }
    let f = reflected as f64 / n as f64;
    let p = r2 as f64;
    assert!(
        (f - p).abs() < 4.5 * (p * (1.0 - p) / n as f64).sqrt(),
        "{f} vs {p}"
    );
}
