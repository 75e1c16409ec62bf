//! The MIS weights of every technique that can make a path sum to one:
//! connections (`bdpt`, `eta = 0`) and connections with merges (`vcm`).
//! Paths are joined from real camera and light subpaths; for each way of
//! making them, the subpaths are rebuilt with the densities the random
//! walks would have recorded.

use lumis_math::{Sampler, SamplerKind, Vec2};
use lumis_render::bsdf::TransportMode;
use lumis_render::integrator::bdpt::mis;
use lumis_render::integrator::bdpt::vertex::{light_origin_pdf, to_area, Kind, Vertex};
use lumis_render::integrator::bdpt::walk;
use lumis_render::integrator::RayCounts;
use lumis_render::load::{load_text, Overrides};
use lumis_render::scene::Scene;
use std::path::Path;

/// The subpath of `verts` (from its first vertex, a lens or light point)
/// as the walk in `mode` would have recorded it.
fn rebuild(scene: &Scene, margin: Vec2, verts: &[Vertex], mode: TransportMode) -> Vec<Vertex> {
    let back = match mode {
        TransportMode::Radiance => TransportMode::Importance,
        TransportMode::Importance => TransportMode::Radiance,
    };
    let mut v: Vec<Vertex> = verts.to_vec();
    for x in v.iter_mut() {
        x.pdf_fwd = 0.0;
        x.pdf_rev = 0.0;
        x.delta = false;
    }
    if v[0].kind != Kind::Camera {
        let Kind::Light(li) = v[0].kind else {
            panic!("a subpath starts at the lens or a light");
        };
        v[0].pdf_fwd = light_origin_pdf(scene, li, v[0].p);
    }
    for i in 1..v.len() {
        v[i].wo = (v[i - 1].p - v[i].p).normalize();
        let w = (v[i].p - v[i - 1].p).normalize();
        let prev = v[i - 1];
        let dir = match prev.kind {
            Kind::Camera => scene.camera.pdf_dir(prev.p, w, margin),
            Kind::Light(li) => scene.lights[li as usize].pdf_le_dir(prev.ng, w),
            Kind::Surface => {
                let b = prev.bsdf.expect("a surface vertex");
                if b.is_delta() {
                    v[i - 1].delta = true;
                    0.0
                } else {
                    b.pdf(prev.wo, w, mode)
                }
            }
        };
        v[i].pdf_fwd = to_area(dir, prev.p, &v[i]);
        if i >= 2 {
            let rev = match v[i - 1].delta {
                true => 0.0,
                false => prev.bsdf.expect("a surface vertex").pdf(w, prev.wo, back),
            };
            let before = v[i - 2];
            v[i - 2].pdf_rev = to_area(rev, prev.p, &before);
        }
    }
    v
}

fn connectible(v: &Vertex) -> bool {
    v.connectible()
}

/// The sum of the weights of every technique that can make `path`
/// (`x_0` on a light, `x_k` the lens), and how many there are.
fn weight_sum(scene: &Scene, margin: Vec2, path: &[Vertex], eta: f32) -> (f32, usize) {
    let k = path.len() - 1;
    let rev: Vec<Vertex> = path.iter().rev().copied().collect();
    let (mut sum, mut n) = (0.0, 0);
    for s in 0..=k {
        let t = k + 1 - s;
        let light = rebuild_or_empty(scene, margin, &path[..s], TransportMode::Importance);
        let mut camera = rebuild(scene, margin, &rev[..t], TransportMode::Radiance);
        let valid = match (s, t) {
            (0, _) => {
                // The camera subpath ends on the emitter itself.
                let Kind::Light(li) = path[0].kind else {
                    unreachable!()
                };
                let pt = camera.last_mut().expect("a vertex");
                pt.kind = Kind::Surface;
                pt.bsdf = None;
                pt.light = Some(li);
                !scene.lights[li as usize].is_delta()
            }
            (_, 1) => connectible(&path[s - 1]),
            (1, _) => connectible(&path[1]),
            _ => connectible(&path[s - 1]) && connectible(&path[s]),
        };
        if valid {
            let w = mis::weight(scene, margin, &light, &camera, s, t, None, eta);
            sum += w;
            n += 1;
        }
    }
    if eta > 0.0 {
        for j in 1..k {
            let x = &path[j];
            if x.kind != Kind::Surface || !x.connectible() {
                continue;
            }
            let light = rebuild(scene, margin, &path[..=j], TransportMode::Importance);
            let camera = rebuild(scene, margin, &rev[..=k - j], TransportMode::Radiance);
            let w = mis::merge_weight(scene, margin, &light, &camera, eta);
            sum += w;
            n += 1;
        }
    }
    (sum, n)
}

fn rebuild_or_empty(
    scene: &Scene,
    margin: Vec2,
    verts: &[Vertex],
    mode: TransportMode,
) -> Vec<Vertex> {
    match verts {
        [] => Vec::new(),
        _ => rebuild(scene, margin, verts, mode),
    }
}

const SCENE: &str = r#"
LookAt 0 1.9 4.2   0 0.45 0   0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 30 30 30 ]
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  Shape "trianglemesh" "point3 P" [ -0.5 3 -0.5  0.5 3 -0.5  0.5 3 0.5  -0.5 3 0.5 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
LightSource "point" "rgb I" [ 5 5 5 ] "point3 from" [ 0.7 2.5 0.3 ]
AttributeBegin
  Material "dielectric" "float eta" [ 1.5 ]
  Translate 0 1 0
  Shape "sphere" "float radius" [ 0.5 ]
AttributeEnd
AttributeBegin
  Material "conductor" "float roughness" [ 0 ]
  Translate -1 0.4 -0.5
  Shape "sphere" "float radius" [ 0.4 ]
AttributeEnd
Material "conductor" "spectrum eta" [ "metal-Al-eta" ] "spectrum k" [ "metal-Al-k" ] "float roughness" [ 0.1 ]
Shape "trianglemesh" "point3 P" [ -3 0 -3  -3 0 3  3 0 3  3 0 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
Shape "trianglemesh" "point3 P" [ -3 0 -3  3 0 -3  3 4 -3  -3 4 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
"#;

/// Over many paths joined from the walks' subpaths, the weights of all
/// techniques that can make each path sum to one, with and without merging.
#[test]
fn weights_of_all_techniques_sum_to_one() {
    let loaded = load_text(SCENE, "mis.pbrt", Path::new("."), &Overrides::default())
        .expect("the test scene loads");
    let scene = &loaded.scene;
    let margin = Vec2::new(0.5, 0.5);
    let mut sampler = Sampler::new(SamplerKind::Independent, 3);
    let (mut camera, mut light) = (Vec::new(), Vec::new());
    let mut rays = RayCounts::default();
    let mut checked = [0usize; 2];
    for i in 0..3000u64 {
        sampler.start_stream(i, 0);
        let p = Vec2::new(sampler.get_1d() * 32.0, sampler.get_1d() * 32.0);
        let ray = scene.camera.generate_ray(p, Vec2::new(0.5, 0.5));
        walk::camera_path(scene, ray, margin, &mut sampler, 6, &mut camera, &mut rays);
        walk::light_path(scene, &mut sampler, 6, &mut light, &mut rays);
        for s in 1..=light.len() {
            for t in 2..=camera.len() {
                let mut path: Vec<Vertex> = light[..s].to_vec();
                path.extend(camera[..t].iter().rev());
                for (m, eta) in [0.0f32, 0.02, 50.0].into_iter().enumerate() {
                    let (sum, n) = weight_sum(scene, margin, &path, eta);
                    if n == 0 {
                        continue;
                    }
                    checked[(m > 0) as usize] += 1;
                    assert!(
                        (sum - 1.0).abs() < 1e-5,
                        "weights sum to {sum} over {n} techniques (eta {eta}, {s} light and {t} camera vertices joined)"
                    );
                }
            }
        }
    }
    assert!(checked[0] > 1000 && checked[1] > 2000, "{checked:?}");
}
