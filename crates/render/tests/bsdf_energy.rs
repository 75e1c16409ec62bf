//! White-furnace style energy tests: the directional albedo
//! `∫ f(wo, wi) |cos wi| dwi`, estimated by importance sampling the BSDF
//! (mean of `f |cos| / pdf`, delta samples included, failed samples count as
//! zero), must never exceed one, and lossless BSDFs must conserve energy.

use lumis_math::{Pcg32, Rgb, Vec2, Vec3};
use lumis_render::bsdf::{
    microfacet::Microfacet, Bsdf, Conductor, Dielectric, Diffuse, DiffuseTransmission, Phong,
    ThinDielectric, TransportMode,
};

const SAMPLES: usize = 40_000;
/// Cosines of the outgoing directions tried for every BSDF.
const COS_O: [f32; 11] = [1.0, 0.9, 0.7, 0.5, 0.3, 0.15, 0.05, -0.3, -0.5, -0.8, -1.0];

fn dir(cos_theta: f32) -> Vec3 {
    let s = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let phi = 2.1f32;
    Vec3::new(s * phi.cos(), s * phi.sin(), cos_theta)
}

/// Albedo estimate and its standard error, per channel. With
/// `undo_radiance_scaling`, transmitted weights are multiplied by `eta^2` so
/// that Radiance-mode refraction counts energy rather than radiance.
fn albedo(
    bsdf: &Bsdf,
    wo: Vec3,
    mode: TransportMode,
    undo_radiance_scaling: bool,
    seed: u64,
) -> ([f64; 3], [f64; 3]) {
    let mut rng = Pcg32::new(seed, 17);
    let (mut sum, mut sum2) = ([0.0f64; 3], [0.0f64; 3]);
    for _ in 0..SAMPLES {
        let uc = rng.next_f32();
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let Some(s) = bsdf.sample(wo, uc, u, mode) else {
            continue;
        };
        if s.pdf.is_nan() || s.pdf <= 0.0 {
            continue;
        }
        let mut w = s.f * (s.wi.z.abs() / s.pdf);
        if undo_radiance_scaling && mode == TransportMode::Radiance {
            w *= s.eta * s.eta;
        }
        assert!(w.is_finite(), "{bsdf:?} wo {wo:?}: {s:?}");
        for c in 0..3 {
            sum[c] += w[c] as f64;
            sum2[c] += (w[c] as f64).powi(2);
        }
    }
    let n = SAMPLES as f64;
    let mut mean = [0.0; 3];
    let mut se = [0.0; 3];
    for c in 0..3 {
        mean[c] = sum[c] / n;
        se[c] = ((sum2[c] / n - mean[c] * mean[c]).max(0.0) / (n - 1.0)).sqrt();
    }
    (mean, se)
}

/// Asserts the albedo never exceeds one (plus 3 standard errors and float
/// slack) for all outgoing directions; returns the estimates.
fn check_bounded(
    name: &str,
    bsdf: Bsdf,
    modes: &[TransportMode],
) -> Vec<(f32, TransportMode, [f64; 3], [f64; 3])> {
    let mut out = Vec::new();
    for &mode in modes {
        for (i, &c) in COS_O.iter().enumerate() {
            let wo = dir(c);
            let (m, se) = albedo(&bsdf, wo, mode, true, 31 * i as u64 + 7);
            for ch in 0..3 {
                assert!(
                    m[ch] <= 1.0 + 3.0 * se[ch] + 1e-5,
                    "{name} {mode:?} cos_o {c}: albedo {} ± {} > 1",
                    m[ch],
                    se[ch]
                );
            }
            out.push((c, mode, m, se));
        }
    }
    let row: Vec<String> = out
        .iter()
        .filter(|r| r.1 == modes[0])
        .map(|(c, _, m, _)| format!("{c}: {:.4}", m[1]))
        .collect();
    println!("{name} ({:?}, green): {}", modes[0], row.join(", "));
    out
}

const BOTH: [TransportMode; 2] = [TransportMode::Radiance, TransportMode::Importance];

#[test]
fn diffuse_white_conserves() {
    let res = check_bounded("diffuse r=1", Diffuse::new(Rgb::WHITE).into(), &BOTH);
    for (c, mode, m, se) in res {
        for ch in 0..3 {
            assert!(
                (m[ch] - 1.0).abs() <= 3.0 * se[ch] + 1e-5,
                "cos {c} {mode:?}: {}",
                m[ch]
            );
        }
    }
    let res = check_bounded(
        "diffuse",
        Diffuse::new(Rgb::new(0.2, 0.5, 0.8)).into(),
        &BOTH,
    );
    for (_, _, m, _) in res {
        assert!((m[0] - 0.2).abs() < 1e-4 && (m[2] - 0.8).abs() < 1e-4);
    }
}

#[test]
fn conductors_bounded() {
    let alphas = [
        (0.0, 0.0),
        (0.05, 0.05),
        (0.2, 0.2),
        (0.5, 0.5),
        (1.0, 1.0),
        (0.1, 0.4),
    ];
    for (ax, ay) in alphas {
        let gold = Conductor::new(
            Rgb::new(0.143, 0.374, 1.442),
            Rgb::new(3.983, 2.385, 1.603),
            ax,
            ay,
        );
        check_bounded(&format!("gold ({ax}, {ay})"), gold.into(), &BOTH);
        let beckmann = Conductor::from_reflectance_with(Rgb::WHITE, Microfacet::beckmann(ax, ay));
        let res_b = check_bounded(
            &format!("white beckmann conductor ({ax}, {ay})"),
            beckmann.into(),
            &BOTH,
        );
        let white = Conductor::from_reflectance(Rgb::WHITE, ax, ay);
        let res = check_bounded(
            &format!("white conductor ({ax}, {ay})"),
            white.into(),
            &BOTH,
        );
        if ax == 0.0 {
            // A perfect mirror with reflectance 1 (clamped to 0.9999) is lossless.
            for (c, _, m, _) in &res {
                assert!((m[1] - 1.0).abs() < 1e-3, "cos {c}: {}", m[1]);
            }
        } else if ax <= 0.05 {
            // Nearly smooth microfacets lose little energy to single scattering,
            // except at grazing angles where masking bites.
            for (c, _, m, _) in res.iter().chain(&res_b) {
                if c.abs() >= 0.3 {
                    assert!(m[1] > 0.97, "cos {c}: {}", m[1]);
                }
            }
        }
    }
}

#[test]
fn smooth_dielectric_conserves() {
    for eta in [1.5f32, 1.0 / 1.5, 1.33, 1.0] {
        let res = check_bounded(
            &format!("smooth dielectric {eta}"),
            Dielectric::new(eta, 0.0, 0.0).into(),
            &BOTH,
        );
        for (c, mode, m, _) in res {
            assert!(
                (m[0] - 1.0).abs() < 1e-3,
                "eta {eta} cos {c} {mode:?}: {}",
                m[0]
            );
        }
    }
}

#[test]
fn smooth_dielectric_radiance_scaling() {
    // Without undoing the eta^2 scaling, transmitted radiance entering glass
    // (from outside, at normal incidence) is T / eta^2.
    let b: Bsdf = Dielectric::new(1.5, 0.0, 0.0).into();
    let (m, _) = albedo(&b, Vec3::Z, TransportMode::Radiance, false, 1);
    let expect = 0.04 + 0.96 / 2.25;
    assert!((m[0] - expect).abs() < 0.01, "{} vs {expect}", m[0]);
}

#[test]
fn rough_dielectric_bounded() {
    let params = [(0.1, 0.1), (0.3, 0.3), (0.6, 0.6), (0.1, 0.4)];
    for eta in [1.5f32, 1.0 / 1.5, 1.33] {
        for (ax, ay) in params {
            let b: Bsdf = Dielectric::new(eta, ax, ay).into();
            let res = check_bounded(&format!("rough dielectric {eta} ({ax}, {ay})"), b, &BOTH);
            let bk = Dielectric::with_microfacet(eta, Microfacet::beckmann(ax, ay));
            let res_b = check_bounded(
                &format!("rough beckmann dielectric {eta} ({ax}, {ay})"),
                bk.into(),
                &BOTH,
            );
            if ax == 0.1 && ay == 0.1 {
                // Single-scattering microfacet models lose the energy of
                // multiply scattered light; at alpha 0.1 this loss is small
                // except near grazing angles, where masking removes more.
                for (c, mode, m, _) in res.into_iter().chain(res_b) {
                    if c.abs() >= 0.3 {
                        assert!(m[0] > 0.9, "eta {eta} cos {c} {mode:?}: R+T = {}", m[0]);
                    }
                }
            }
        }
    }
}

#[test]
fn phong_bounded() {
    for n in [0.0, 1.0, 10.0, 100.0, 1000.0] {
        for (kd, ks) in [(0.0, 1.0), (0.5, 0.5), (0.9, 0.1), (0.3, 0.4)] {
            let b: Bsdf = Phong::new(Rgb::splat(kd), Rgb::splat(ks), n).into();
            let res = check_bounded(&format!("phong n {n} kd {kd} ks {ks}"), b, &BOTH);
            // At normal incidence the normalized lobe reflects exactly ks.
            let (_, _, m, se) = res[0];
            assert!(
                (m[0] - (kd + ks) as f64).abs() < 4.0 * se[0] + 1e-4,
                "n {n} kd {kd} ks {ks}: {}",
                m[0]
            );
        }
    }
    // Over-unity coefficients are clamped per channel.
    let p = Phong::new(Rgb::new(0.8, 0.2, 1.0), Rgb::new(0.8, 0.2, 1.0), 5.0);
    assert!((p.kd.r - 0.5).abs() < 1e-6 && (p.ks.r - 0.5).abs() < 1e-6);
    assert!((p.kd.g - 0.2).abs() < 1e-6 && (p.kd.b - 0.5).abs() < 1e-6);
    check_bounded("phong clamped", p.into(), &BOTH);
}

/// The thin sheet loses nothing: `R' + T' = 1` at every angle and index.
#[test]
fn thin_dielectric_conserves() {
    for eta in [1.5f32, 1.0 / 1.5, 1.33, 2.4, 1.0] {
        let res = check_bounded(
            &format!("thin dielectric {eta}"),
            ThinDielectric::new(eta).into(),
            &BOTH,
        );
        for (c, mode, m, _) in res {
            assert!(
                (m[0] - 1.0).abs() < 1e-5,
                "eta {eta} cos {c} {mode:?}: {}",
                m[0]
            );
        }
    }
}

/// Diffuse transmission's directional albedo is `R + T` per channel, from
/// either side.
#[test]
fn diffuse_transmission_albedo_is_r_plus_t() {
    for (r, t) in [
        (Rgb::new(0.25, 0.5, 0.1), Rgb::new(0.1, 0.2, 0.3)),
        (Rgb::splat(0.5), Rgb::splat(0.5)),
        (Rgb::splat(0.25), Rgb::splat(0.25)),
        (Rgb::BLACK, Rgb::new(0.9, 0.3, 0.6)),
    ] {
        let res = check_bounded(
            &format!("diffusetransmission {r:?} {t:?}"),
            DiffuseTransmission::new(r, t).into(),
            &BOTH,
        );
        for (c, mode, m, se) in res {
            for ch in 0..3 {
                let want = (r[ch] + t[ch]) as f64;
                assert!(
                    (m[ch] - want).abs() < 4.5 * se[ch] + 1e-5,
                    "{r:?} {t:?} cos {c} {mode:?} channel {ch}: {} vs {want}",
                    m[ch]
                );
            }
        }
    }
}
