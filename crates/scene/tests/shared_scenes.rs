//! Load-only tests of the real scenes in /work/shared/scenes (skipped when the
//! folder is absent, unless LUMIS_REQUIRE_SHARED=1).

use lumis_math::{Mat4, Vec3};
use lumis_scene::ply::read_ply;
use lumis_scene::*;
use std::path::{Path, PathBuf};

fn shared() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    if dir.is_dir() {
        return Some(dir);
    }
    if std::env::var("LUMIS_REQUIRE_SHARED").as_deref() == Ok("1") {
        panic!("LUMIS_REQUIRE_SHARED=1 but {} is missing", dir.display());
    }
    println!("skipping: ../shared/scenes not found");
    None
}

fn load(rel: &str) -> Option<SceneDesc> {
    let path = shared()?.join(rel);
    match load_file(&path) {
        Ok(d) => Some(d),
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn cornell_box() {
    let Some(d) = load("bitterli-cornell-box/scene-v4.pbrt") else {
        return;
    };
    assert!(d.saw_world_begin);
    assert_eq!(d.shapes.len(), 8);
    assert!(d.shapes.iter().all(|s| s.entity.ty == "trianglemesh"));
    let expected = Mat4::from_cols_array(&[
        1.0, -0.0, -0.0, -0.0, -0.0, 1.0, -0.0, -0.0, -0.0, -0.0, -1.0, -0.0, -0.0, -1.0, 6.8, 1.0,
    ]);
    let cam = d.camera.as_ref().unwrap();
    assert_eq!(cam.camera_from_world.m, expected);
    assert_eq!(cam.entity.params.get_float("fov", 0.0).unwrap(), 19.5);
    assert_eq!(d.named_materials.len(), 8);
    let lights: Vec<&ShapeDesc> = d.shapes.iter().filter(|s| s.area_light.is_some()).collect();
    assert_eq!(lights.len(), 1);
    let l = lights[0].area_light.as_ref().unwrap();
    assert_eq!(
        l.params.get_spectrum("L").unwrap(),
        Some(SpectrumValue::Rgb([17.0, 12.0, 4.0]))
    );
    let m = d.material(&lights[0].material).unwrap().unwrap();
    assert_eq!(m.name.as_deref(), Some("Light"));
    let floor = &d.shapes[0].entity.params;
    assert_eq!(floor.get_point3s("P").unwrap().unwrap().len(), 4);
    assert_eq!(floor.get_normals("N").unwrap().unwrap().len(), 4);
    assert_eq!(floor.get_point2s("uv").unwrap().unwrap().len(), 4);
    assert_eq!(
        floor.get_ints("indices").unwrap().unwrap(),
        vec![0, 1, 2, 0, 2, 3]
    );
    assert_eq!(
        d.film
            .as_ref()
            .unwrap()
            .params
            .get_int("xresolution", 0)
            .unwrap(),
        1024
    );
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
}

#[test]
fn veach_mis() {
    let Some(d) = load("bitterli-veach-mis/scene-v4.pbrt") else {
        return;
    };
    assert_eq!(d.shapes.len(), 9);
    assert_eq!(d.named_materials.len(), 6);
    let spheres: Vec<&ShapeDesc> = d
        .shapes
        .iter()
        .filter(|s| s.entity.ty == "sphere")
        .collect();
    assert_eq!(spheres.len(), 3);
    assert!(spheres.iter().all(|s| s.area_light.is_some()));
    let smooth = &d.materials[d.named_materials["Smooth"] as usize].entity;
    assert_eq!(smooth.ty, "conductor");
    assert!(!smooth.params.get_bool("remaproughness", true).unwrap());
    assert_eq!(smooth.params.get_float("uroughness", 0.0).unwrap(), 0.01);
    assert_eq!(
        d.film
            .as_ref()
            .unwrap()
            .params
            .get_int("xresolution", 0)
            .unwrap(),
        1280
    );
    // The last shape (after all AttributeEnds) has no area light.
    assert!(d.shapes.last().unwrap().area_light.is_none());
}

#[test]
fn killeroo_simple() {
    let Some(d) = load("pbrt-v4-killeroos/killeroo-simple.pbrt") else {
        return;
    };
    let tys: Vec<&str> = d.shapes.iter().map(|s| s.entity.ty.as_str()).collect();
    assert_eq!(
        tys,
        [
            "sphere",
            "trianglemesh",
            "trianglemesh",
            "loopsubdiv",
            "loopsubdiv"
        ]
    );
    assert!(d.shapes[3]
        .entity
        .loc
        .file
        .path
        .ends_with("geometry/killeroo.pbrt"));
    assert_eq!(d.shapes[3].entity.params.get_int("levels", 0).unwrap(), 1);
    assert!(
        d.shapes[3]
            .entity
            .params
            .get_point3s("P")
            .unwrap()
            .unwrap()
            .len()
            > 100
    );
    let (a, b) = (d.shapes[3].object_to_world, d.shapes[4].object_to_world);
    // The second killeroo is Translate -200 0 0 further, under Scale 0.5 and Rotate -60 about z.
    let delta = b.point(Vec3::ZERO) - a.point(Vec3::ZERO);
    assert!(
        (delta - Vec3::new(-50.0, 86.60254, 0.0)).length() < 1e-3,
        "{delta}"
    );
    let ma = d.material(&d.shapes[3].material).unwrap().unwrap();
    let mb = d.material(&d.shapes[4].material).unwrap().unwrap();
    assert_eq!(ma.entity.params.get_float("roughness", 0.0).unwrap(), 0.025);
    assert_eq!(mb.entity.params.get_float("roughness", 0.0).unwrap(), 0.15);
    assert!(d.shapes[0].area_light.is_some() && d.shapes[1].area_light.is_none());
    assert!(d.camera.is_some() && d.sampler.as_ref().unwrap().ty == "halton");
}

#[test]
fn caustic_glass_v4() {
    let Some(d) = load("pbrt-caustic-glass/pbrt-v4-w3ntao/caustic-glass-v4.pbrt") else {
        return;
    };
    assert_eq!(d.lights.len(), 1);
    let spot = &d.lights[0].entity;
    assert_eq!(spot.ty, "spot");
    assert_eq!(
        spot.params.get_spectrum("I").unwrap(),
        Some(SpectrumValue::Blackbody(5500.0))
    );
    assert_eq!(
        spot.params.get_point3("from", Vec3::ZERO).unwrap(),
        Vec3::new(0.0, 5.0, 9.0)
    );
    assert_eq!(d.shapes.len(), 2);
    assert!(d.shapes.iter().all(|s| s.entity.ty == "plymesh"));
    let file = d.shapes[0]
        .entity
        .params
        .get_string("filename", "")
        .unwrap();
    let mesh = read_ply(&d.resolve_path(&file)).unwrap();
    assert_eq!(mesh.positions.len(), 44034);
    assert_eq!(mesh.indices.len(), 88064 * 3);
    let file = d.shapes[1]
        .entity
        .params
        .get_string("filename", "")
        .unwrap();
    let floor = read_ply(&d.resolve_path(&file)).unwrap();
    assert_eq!((floor.positions.len(), floor.indices.len()), (4, 6));
}

#[test]
fn caustic_glass_ply_mesh() {
    let Some(dir) = shared() else { return };
    let mesh = read_ply(&dir.join("pbrt-caustic-glass/pbrt-v3/geometry/mesh_00001.ply")).unwrap();
    assert_eq!(mesh.positions.len(), 44034);
    assert_eq!(mesh.indices.len(), 88064 * 3);
    let normals = mesh.normals.as_ref().unwrap();
    assert_eq!(normals.len(), 44034);
    assert!(normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-2));
    assert!(mesh.uvs.is_none());
    assert!(mesh
        .indices
        .iter()
        .all(|&i| (i as usize) < mesh.positions.len()));
}
