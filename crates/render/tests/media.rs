//! Participating media against analytic answers: Beer-Lambert through a
//! slab (homogeneous and both grids), an absorbing liquid behind glass, an
//! emitting medium, a closed furnace of a scattering medium of albedo 1
//! (chromatic), transmittance through random grids by delta tracking, ratio
//! tracking and quadrature; loading errors; determinism.

use crate::common;

use common::media::{per_channel, sphere_of};
use common::{assert_close, header, load, render_loaded};
use lumis_math::{Pcg32, Rgb, Transform, Vec3};
use lumis_render::load::Overrides;
use lumis_render::media::voxels::Voxels;
use lumis_render::media::{track, Grid, GridEmission, HenyeyGreenstein, Medium, MediumKind, Phase};

/// A 16x16 view (fov 1 degree, so rays are within 0.5 degree of the axis)
/// down -z at a large two-sided emitter of radiance 1 at z = -3, through
/// the box |x|,|y| < 4, |z| < `half` made of `material` with `medium` inside.
fn slab_scene(medium: &str, material: &str, half: f32) -> String {
    format!(
        r#"Integrator "path" "integer maxdepth" [ 40 ]
{}
LookAt 0 0 6  0 0 0  0 1 0
Camera "perspective" "float fov" [ 1 ]
WorldBegin
{medium}
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  Translate 0 0 -3
  Shape "trianglemesh" "point3 P" [ -20 -20 0  20 -20 0  20 20 0  -20 20 0 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
AttributeBegin
  {material}
  MediumInterface "liquid" ""
  Scale 4 4 {half}
  {BOX}
AttributeEnd
"#,
        header(16)
    )
}

/// A closed unit cube around the origin (outward normals), as a trianglemesh.
const BOX: &str = r#"Shape "trianglemesh" "point3 P" [ -1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1  -1 -1 1  1 -1 1  1 1 1  -1 1 1 ]
  "integer indices" [ 0 2 1 0 3 2  4 5 6 4 6 7  0 1 5 0 5 4  2 3 7 2 7 6  1 2 6 1 6 5  0 4 7 0 7 3 ]"#;

const SIGMA_A: [f32; 3] = [0.5, 1.0, 2.0];

#[test]
fn beer_lambert_through_a_slab_for_each_medium_type() {
    // Thickness 1; coefficients 0.5, 1, 2 per unit length.
    let media = [
        (
            "homogeneous",
            r#"MakeNamedMedium "liquid" "string type" "homogeneous" "rgb sigma_a" [ 0.25 0.5 1 ] "rgb sigma_s" [ 0 0 0 ] "float scale" 2"#.to_string(),
        ),
        (
            "uniformgrid",
            // Density 1 well inside the box (the grid fades only half a voxel from its faces).
            r#"MakeNamedMedium "liquid" "string type" "uniformgrid" "rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ]
               "integer nx" 2 "integer ny" 2 "integer nz" 2 "float density" [ 1 1 1 1 1 1 1 1 ]
               "point3 p0" [ -20 -20 -20 ] "point3 p1" [ 20 20 20 ]"#.to_string(),
        ),
        (
            "rgbgrid",
            r#"MakeNamedMedium "liquid" "string type" "rgbgrid" "rgb sigma_a" [ 0.5 1 2  0.5 1 2 ] "rgb sigma_s" [ 0 0 0  0 0 0 ]
               "integer nz" 2 "point3 p0" [ -20 -20 -20 ] "point3 p1" [ 20 20 20 ]"#.to_string(),
        ),
    ];
    for (ty, m) in media {
        let l = load(
            &slab_scene(&m, r#"Material "interface""#, 0.5),
            &Overrides::default(),
        );
        assert!(l.warnings.is_empty(), "{ty}: {:?}", l.warnings);
        let film = render_loaded(&l, 1024, 1, 0).film;
        for (c, stat) in per_channel(&film).into_iter().enumerate() {
            let expected = (-SIGMA_A[c] as f64).exp();
            assert_close(&format!("{ty} channel {c}"), stat, expected, 0.0);
        }
    }
}

#[test]
fn absorbing_liquid_inside_smooth_glass() {
    // Glass of index 1.33 holding the liquid: at normal incidence each face
    // passes 1 - R, R = ((n - 1) / (n + 1))^2, and light bounces between the
    // faces: L = (1 - R)^2 tau / (1 - R^2 tau^2), tau = exp(-sigma_a d).
    let m = r#"MakeNamedMedium "liquid" "string type" "homogeneous" "rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ]"#;
    let l = load(
        &slab_scene(m, r#"Material "dielectric" "float eta" 1.33"#, 0.5),
        &Overrides::default(),
    );
    let film = render_loaded(&l, 1024, 2, 0).film;
    let r = ((1.33f64 - 1.0) / 2.33).powi(2);
    for (c, stat) in per_channel(&film).into_iter().enumerate() {
        let tau = (-SIGMA_A[c] as f64).exp();
        let expected = (1.0 - r).powi(2) * tau / (1.0 - r * r * tau * tau);
        assert_close(
            &format!("liquid in glass, channel {c}"),
            stat,
            expected,
            0.0,
        );
    }
}

#[test]
fn emitting_medium_in_a_black_sphere() {
    // Radiance from the centre: the integral of sigma_a Le exp(-sigma_a t)
    // over the radius, 1 - exp(-sigma_a).
    let m = r#"MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ] "rgb Le" [ 1 1 1 ]"#;
    let mut ov = Overrides::default();
    ov.integrator("path");
    let l = load(&sphere_of(m, ""), &ov);
    let film = render_loaded(&l, 256, 3, 0).film;
    for (c, stat) in per_channel(&film).into_iter().enumerate() {
        assert_close(
            &format!("emission, channel {c}"),
            stat,
            1.0 - (-SIGMA_A[c] as f64).exp(),
            0.0,
        );
    }
}

#[test]
fn furnace_full_of_a_chromatic_medium_of_albedo_one() {
    // A closed emitter of radiance 1 around a medium that only scatters
    // (forward, g = 0.5, differently per channel): radiance 1 everywhere.
    let m = r#"MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0 0 0 ] "rgb sigma_s" [ 1 1.5 2 ] "float g" 0.5"#;
    let wall = r#"AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true"#;
    let l = load(&sphere_of(m, wall), &Overrides::default());
    let film = render_loaded(&l, 1024, 4, 0).film;
    for (c, stat) in per_channel(&film).into_iter().enumerate() {
        assert_close(&format!("furnace, channel {c}"), stat, 1.0, 0.0);
    }
}

/// A random density grid over a rotated, scaled box, and a ray through it.
fn random_grid(seed: u64) -> (Medium, Vec3, Vec3, f32) {
    let mut rng = Pcg32::new(seed, 7);
    let n = [4, 5, 6];
    let values = (0..120).map(|_| 4.0 * rng.next_f32().powi(2)).collect();
    let world = lumis_math::Mat4::from_rotation_y(0.4)
        * lumis_math::Mat4::from_scale(Vec3::new(2.0, 1.0, 1.5));
    let unit = Transform::new(world).unwrap().inverse();
    let grid = Grid::new(
        unit,
        Rgb::new(0.3, 0.6, 0.9),
        Rgb::new(0.7, 0.2, 0.4),
        Voxels { n, values },
        GridEmission::None,
    );
    let medium = Medium {
        kind: MediumKind::Grid(grid),
        phase: Phase::HenyeyGreenstein(HenyeyGreenstein::new(0.0)),
    };
    // Through the box's centre, from outside it to outside it.
    let c = world.transform_point3(Vec3::splat(0.5));
    let d = Vec3::new(1.0, 0.15 + 0.2 * seed as f32, 0.6).normalize();
    (medium, c - d * 2.0, d, 4.0)
}

#[test]
fn delta_and_ratio_tracking_agree_with_quadrature_on_random_grids() {
    for seed in 0..3 {
        let (m, o, d, tmax) = random_grid(seed);
        // Quadrature of the optical depth per channel.
        let steps = 20000;
        let mut tau = [0.0f64; 3];
        for i in 0..steps {
            let t = (i as f32 + 0.5) / steps as f32 * tmax;
            let u = match &m.kind {
                MediumKind::Grid(g) => g.unit_from_world.point(o + d * t),
                _ => unreachable!(),
            };
            if u.min_element() < 0.0 || u.max_element() > 1.0 {
                continue;
            }
            let p = m.point(o + d * t);
            let st = p.sigma_a + p.sigma_s;
            for c in 0..3 {
                tau[c] += st[c] as f64 * (tmax / steps as f32) as f64;
            }
        }
        let exact = tau.map(|t| (-t).exp());
        assert!(
            exact[2] < 0.5 && exact[0] > 0.01,
            "seed {seed}: a ray that tests something {exact:?}"
        );
        let mut rng = Pcg32::new(seed, 1);
        let n = 200000;
        let (mut ratio, mut ratio2) = ([0.0f64; 3], [0.0f64; 3]);
        let mut survived = [0.0f64; 3];
        for _ in 0..n {
            let tr = track::transmittance(&m, o, d, tmax, &mut rng);
            for c in 0..3 {
                ratio[c] += tr[c] as f64;
                ratio2[c] += (tr[c] as f64).powi(2);
            }
            // Delta tracking, one channel at a time: a real collision with
            // probability sigma_t / majorant ends the flight.
            for (c, survived) in survived.iter_mut().enumerate() {
                let got_through = track::collisions(&m, o, d, tmax, &mut rng, |rng, _, mp, maj| {
                    let st = mp.sigma_a[c] + mp.sigma_s[c];
                    assert!(st <= maj * 1.0001, "majorant {maj} below sigma_t {st}");
                    rng.next_f32() >= st / maj
                });
                *survived += got_through as u32 as f64;
            }
        }
        for c in 0..3 {
            let mean = ratio[c] / n as f64;
            let se = ((ratio2[c] / n as f64 - mean * mean) / n as f64).sqrt();
            assert_close(
                &format!("seed {seed} ratio tracking, channel {c}"),
                (mean, se),
                exact[c],
                0.0,
            );
            // A yes/no estimate per flight: noisier, so a 3% resolution.
            let p = survived[c] / n as f64;
            let se = (p * (1.0 - p) / n as f64).sqrt();
            let z = (p - exact[c]) / se;
            eprintln!("seed {seed} delta tracking, channel {c}: {p:.5} ± {se:.5}, expected {:.5}, z {z:.2}", exact[c]);
            assert!(
                z.abs() < 4.5 && se < 0.03 * exact[c],
                "seed {seed} channel {c}: z {z}, se {se}"
            );
        }
    }
}

#[test]
fn media_render_the_same_on_one_and_two_threads() {
    let m = r#"MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0.1 0.1 0.1 ] "rgb sigma_s" [ 0.5 1 1.5 ]"#;
    let wall = r#"AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true"#;
    let l = load(&sphere_of(m, wall), &Overrides::default());
    let bits = |threads| -> Vec<u32> {
        let img = render_loaded(&l, 4, 9, threads).film.mean_image();
        img.iter().map(|v| v.to_bits()).collect()
    };
    assert_eq!(bits(1), bits(2));
}

#[test]
fn cloud_transmittance_agrees_with_quadrature() {
    // pbrt-v4's procedural cloud in a box, bounded by sigma_t: ratio
    // tracking against the optical depth integrated along the ray.
    use lumis_render::media::Cloud;
    let unit = Transform::new(lumis_math::Mat4::from_scale(Vec3::splat(0.5))).unwrap();
    let cloud = Cloud::new(
        Transform::IDENTITY,
        unit,
        Rgb::splat(0.4),
        Rgb::splat(1.6),
        1.0,
        1.0,
        5.0,
    );
    // Solid (density 1) below y = 0, as pbrt-v4's: 2 (0.5 - y) >= 1.
    assert_eq!(cloud.density_at(Vec3::new(0.7, -0.1, 1.1)), 1.0);
    let m = Medium {
        kind: MediumKind::Cloud(cloud),
        phase: Phase::HenyeyGreenstein(HenyeyGreenstein::new(0.0)),
    };
    let (o, d) = (
        Vec3::new(-0.5, 0.55, 0.3),
        Vec3::new(1.0, 0.2, 0.4).normalize(),
    );
    let steps = 20000;
    let tmax = 3.0f32;
    let mut tau = 0.0f64;
    for i in 0..steps {
        let p = o + d * ((i as f32 + 0.5) / steps as f32 * tmax);
        if p.min_element() >= 0.0 && p.max_element() <= 2.0 {
            let mp = m.point(p);
            tau += (mp.sigma_a + mp.sigma_s).r as f64 * (tmax / steps as f32) as f64;
        }
    }
    let exact = (-tau).exp();
    assert!(
        exact > 0.02 && exact < 0.9,
        "a ray that tests something: {exact}"
    );
    let mut rng = Pcg32::new(5, 1);
    let n = 100_000;
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let t = track::transmittance(&m, o, d, tmax, &mut rng).r as f64;
        sum += t;
        sum2 += t * t;
    }
    let mean = sum / n as f64;
    let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
    assert_close("cloud ratio tracking", (mean, se), exact, 0.0);
}
