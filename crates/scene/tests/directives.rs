//! Each directive and the graphics-state rules, through `load_str`.

use lumis_math::{Mat4, Vec3, Vec4};
use lumis_scene::*;
use std::path::Path;

fn load(text: &str) -> SceneDesc {
    match load_str(text, "test.pbrt", Path::new("/base")) {
        Ok(d) => d,
        Err(e) => panic!("{e}"),
    }
}

fn close(a: Mat4, b: Mat4) -> bool {
    a.abs_diff_eq(b, 1e-5)
}

#[test]
fn options_block_entities() {
    let d = load(
        r#"Film "rgb" "integer xresolution" 64
        Sampler "halton" "integer pixelsamples" 4
        Integrator "path" "integer maxdepth" [5]
        PixelFilter "gaussian"
        Camera "perspective" "float fov" 45
        WorldBegin"#,
    );
    assert!(d.saw_world_begin);
    assert_eq!(d.film.as_ref().unwrap().ty, "rgb");
    assert_eq!(
        d.film
            .as_ref()
            .unwrap()
            .params
            .get_int("xresolution", 0)
            .unwrap(),
        64
    );
    assert_eq!(d.sampler.as_ref().unwrap().ty, "halton");
    assert_eq!(
        d.integrator
            .as_ref()
            .unwrap()
            .params
            .get_int("maxdepth", 0)
            .unwrap(),
        5
    );
    assert_eq!(d.filter.as_ref().unwrap().ty, "gaussian");
    let cam = d.camera.as_ref().unwrap();
    assert_eq!(cam.entity.ty, "perspective");
    assert_eq!((cam.entity.loc.line, cam.entity.loc.col), (5, 16));
    assert_eq!(cam.camera_from_world, lumis_math::Transform::IDENTITY);
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
    assert_eq!(d.resolve_path("a.ply"), Path::new("/base/a.ply"));
}

#[test]
fn look_at_matches_hand_computed_matrix() {
    let d = load("LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin");
    let cam = d.camera.unwrap();
    // world-from-camera has columns right=(-1,0,0), up=(0,1,0), dir=(0,0,-1), eye=(0,0,5).
    let world_from_camera = Mat4::from_cols(
        Vec4::new(-1.0, 0.0, 0.0, 0.0),
        Vec4::new(0.0, 1.0, 0.0, 0.0),
        Vec4::new(0.0, 0.0, -1.0, 0.0),
        Vec4::new(0.0, 0.0, 5.0, 1.0),
    );
    assert!(close(cam.camera_from_world.m, world_from_camera.inverse()));
    // The eye maps to the camera origin, the look point to +z.
    let t = cam.camera_from_world;
    assert!((t.point(Vec3::new(0.0, 0.0, 5.0))).length() < 1e-5);
    assert!((t.point(Vec3::ZERO) - Vec3::new(0.0, 0.0, 5.0)).length() < 1e-5);
}

#[test]
fn transform_is_column_major_and_concat_post_multiplies() {
    let d = load(
        "WorldBegin\nTransform [1 0 0 0  0 1 0 0  0 0 1 0  7 8 9 1]\nShape \"sphere\"\n\
         ConcatTransform [2 0 0 0  0 2 0 0  0 0 2 0  0 0 0 1]\nShape \"sphere\"\n\
         Identity Translate 1 2 3 Scale 2 2 2 Shape \"sphere\"",
    );
    let t0 = d.shapes[0].object_to_world;
    assert_eq!(t0.point(Vec3::ZERO), Vec3::new(7.0, 8.0, 9.0));
    let t1 = d.shapes[1].object_to_world;
    assert_eq!(t1.point(Vec3::X), Vec3::new(9.0, 8.0, 9.0));
    let t2 = d.shapes[2].object_to_world;
    assert_eq!(t2.point(Vec3::X), Vec3::new(3.0, 2.0, 3.0));
}

#[test]
fn rotate_90_about_z_maps_x_to_y() {
    let d = load("WorldBegin Rotate 90 0 0 1 Shape \"sphere\"");
    let v = d.shapes[0].object_to_world.vector(Vec3::X);
    assert!((v - Vec3::Y).length() < 1e-6, "{v}");
}

#[test]
fn coordinate_systems() {
    let d = load(
        "Translate 0 0 4 Camera \"perspective\" WorldBegin\n\
         Translate 1 0 0 CoordinateSystem \"mine\" Identity\n\
         AttributeBegin CoordSysTransform \"camera\" LightSource \"distant\" AttributeEnd\n\
         CoordSysTransform \"mine\" LightSource \"point\"\nCoordSysTransform \"nope\"",
    );
    // "camera" is camera-to-world = inverse of the CTM at Camera.
    assert_eq!(
        d.lights[0].light_to_world.point(Vec3::ZERO),
        Vec3::new(0.0, 0.0, -4.0)
    );
    assert_eq!(d.lights[1].light_to_world.point(Vec3::ZERO), Vec3::X);
    assert_eq!(d.warnings.len(), 1);
    assert!(d.warnings[0]
        .message
        .contains("unknown coordinate system `nope`"));
    assert_eq!(d.warnings[0].loc.as_ref().unwrap().line, 5);
}

#[test]
fn attribute_scoping_of_material_area_light_and_orientation() {
    let d = load(
        r#"WorldBegin
        Material "diffuse"
        AttributeBegin
          Material "conductor"
          AreaLightSource "diffuse" "rgb L" [1 1 1]
          ReverseOrientation
          Translate 0 1 0
          Shape "sphere"
        AttributeEnd
        Shape "disk"
        TransformBegin Translate 5 0 0 Material "dielectric" TransformEnd
        Shape "disk""#,
    );
    assert_eq!(d.materials.len(), 3);
    let (a, b, c) = (&d.shapes[0], &d.shapes[1], &d.shapes[2]);
    assert!(matches!(a.material, MaterialRef::Index(1)));
    assert_eq!(a.area_light.as_ref().unwrap().ty, "diffuse");
    assert!(a.reverse_orientation);
    assert_eq!(a.object_to_world.point(Vec3::ZERO), Vec3::Y);
    assert!(matches!(b.material, MaterialRef::Index(0)));
    assert!(b.area_light.is_none() && !b.reverse_orientation);
    assert_eq!(b.object_to_world.point(Vec3::ZERO), Vec3::ZERO);
    // TransformEnd restores only the CTM: the material set inside survives.
    assert!(matches!(c.material, MaterialRef::Index(2)));
    assert_eq!(c.object_to_world.point(Vec3::ZERO), Vec3::ZERO);
    assert!(d
        .warnings
        .iter()
        .any(|w| w.message.contains("TransformBegin is deprecated")));
}

#[test]
fn named_materials_forward_reference_and_redefinition() {
    let d = load(
        r#"WorldBegin
        NamedMaterial "later"
        Shape "sphere"
        MakeNamedMaterial "later" "string type" "diffuse" "rgb reflectance" [0.5 0.5 0.5]
        MakeNamedMaterial "later" "string type" "conductor""#,
    );
    let MaterialRef::Named(n, loc) = &d.shapes[0].material else {
        panic!()
    };
    assert_eq!(n, "later");
    assert_eq!(loc.line, 2);
    let m = d.material(&d.shapes[0].material).unwrap().unwrap();
    assert_eq!(m.entity.ty, "conductor");
    assert_eq!(m.name.as_deref(), Some("later"));
    assert!(d.materials[0]
        .entity
        .params
        .param("type")
        .unwrap()
        .is_used());
    assert!(d.warnings[0].message.contains("redefined"));
}

#[test]
fn textures_lights_and_bool_words() {
    let d = load(
        r#"WorldBegin
        Translate 1 0 0
        Texture "grid" "spectrum" "imagemap" "string filename" "lines.png"
        Texture "r" "float" "constant" "float value" 0.1
        LightSource "point" "blackbody I" 3000
        MakeNamedMaterial "m" "string type" "conductor" "bool remaproughness" false "texture roughness" "r""#,
    );
    assert_eq!(d.textures.len(), 2);
    assert_eq!(d.textures[0].name, "grid");
    assert_eq!(d.textures[0].kind, "spectrum");
    assert_eq!(d.textures[0].entity.ty, "imagemap");
    assert_eq!(d.textures[0].object_to_world.point(Vec3::ZERO), Vec3::X);
    assert_eq!(d.textures[1].kind, "float");
    assert_eq!(d.lights[0].entity.ty, "point");
    assert_eq!(d.lights[0].light_to_world.point(Vec3::ZERO), Vec3::X);
    let p = &d.materials[0].entity.params;
    assert!(!p.get_bool("remaproughness", true).unwrap());
    assert_eq!(p.get_texture("roughness").as_deref(), Some("r"));
}

#[test]
fn unsupported_directives_warn_and_skip_their_arguments() {
    let d = load(
        r#"Option "bool disablepixeljitter" true
        ColorSpace "aces2065-1"
        MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [1 1 1]
        MakeNamedMedium "smoke" "string type" "homogeneous"
        MediumInterface "" "smoke"
        TransformTimes 0 1
        Accelerator "kdtree"
        Camera "perspective"
        WorldBegin
        MediumInterface "" "fog"
        MediumInterface "fog"
        Shape "disk"
        WorldEnd"#,
    );
    assert_eq!(d.shapes.len(), 1);
    assert_eq!(d.shapes[0].entity.ty, "disk");
    let msgs: Vec<&str> = d.warnings.iter().map(|w| w.message.as_str()).collect();
    for needle in ["Option", "aces2065-1", "Accelerator"] {
        assert!(
            msgs.iter().any(|m| m.contains(needle)),
            "no warning about {needle}: {msgs:?}"
        );
    }
    // Media are read, not warned about.
    assert_eq!(msgs.len(), 3, "{msgs:?}");
    let lines: Vec<u32> = d
        .warnings
        .iter()
        .map(|w| w.loc.as_ref().unwrap().line)
        .collect();
    assert_eq!(lines, [1, 2, 7]);
    // The camera sits in the outside medium in effect at `Camera`; the shape
    // takes the last interface (one name: both sides).
    assert_eq!(
        d.camera.as_ref().unwrap().medium.as_ref().unwrap().name,
        "smoke"
    );
    let m = &d.shapes[0].media;
    assert_eq!(m.inside.as_ref().unwrap().name, "fog");
    assert_eq!(m.outside.as_ref().unwrap().name, "fog");
    assert!(!m.is_transition());
    assert_eq!(d.media.len(), 2);
    assert_eq!(
        (d.media[0].name.as_str(), d.media[0].entity.ty.as_str()),
        ("fog", "homogeneous")
    );
}

#[test]
fn media_are_named_once_and_carry_their_transform() {
    let d = load(
        r#"WorldBegin
        Translate 0 2 0
        MakeNamedMedium "tea" "string type" "homogeneous" "float scale" 3
        AttributeBegin
          MediumInterface "tea" ""
          Shape "sphere"
        AttributeEnd
        Shape "disk"
        LightSource "point""#,
    );
    let tea = &d.media[0];
    assert_eq!(tea.medium_to_world.point(Vec3::ZERO).y, 2.0);
    assert!(tea.entity.params.has("scale"));
    let inner = &d.shapes[0].media;
    assert!(inner.is_transition());
    assert_eq!(inner.inside.as_ref().unwrap().name, "tea");
    assert!(inner.outside.is_none());
    // The interface ends with its attribute block.
    assert!(d.shapes[1].media.inside.is_none() && !d.shapes[1].media.is_transition());
    assert!(d.lights[0].medium.is_none());
    let twice = lumis_scene::load_str(
        "MakeNamedMedium \"a\" \"string type\" \"homogeneous\"\nMakeNamedMedium \"a\" \"string type\" \"homogeneous\"",
        "m.pbrt",
        std::path::Path::new("."),
    )
    .unwrap_err();
    assert!(twice.to_string().contains("m.pbrt:2:17"), "{twice}");
    assert!(twice.message.contains("defined twice"), "{twice}");
    let untyped = lumis_scene::load_str(
        "MakeNamedMedium \"a\" \"float scale\" 2",
        "m.pbrt",
        std::path::Path::new("."),
    )
    .unwrap_err();
    assert!(untyped.message.contains("no type"), "{untyped}");
}

#[test]
fn active_transform_renders_the_start_time_transform() {
    let d = load(
        r#"WorldBegin
        AttributeBegin
          ActiveTransform EndTime
          Translate 5 0 0
          ActiveTransform StartTime
          Translate 0 1 0
          ActiveTransform All
          Translate 0 0 1
          Shape "sphere"
        AttributeEnd
        Shape "disk""#,
    );
    let p = d.shapes[0].object_to_world.point(Vec3::ZERO);
    assert_eq!(p, Vec3::new(0.0, 1.0, 1.0));
    assert_eq!(d.shapes[1].object_to_world.point(Vec3::ZERO), Vec3::ZERO);
    assert_eq!(d.warnings.len(), 1, "{:?}", d.warnings);
    assert!(d.warnings[0].message.contains("motion blur"));
    assert_eq!(d.warnings[0].loc.as_ref().unwrap().line, 4);
    let e = load_str("ActiveTransform Sometimes", "t.pbrt", Path::new(".")).unwrap_err();
    assert!(e.message.contains("StartTime, EndTime or All"), "{e}");
}

#[test]
fn attribute_sets_scoped_parameter_defaults() {
    let d = load(
        r#"WorldBegin
        AttributeBegin
          Attribute "shape" "float radius" 2 "float zmax" 0.5
          Attribute "light" "float scale" 3
          Attribute "material" "rgb reflectance" [0.1 0.2 0.3]
          Material "diffuse"
          Shape "sphere" "float radius" 4
          LightSource "point"
          AreaLightSource "diffuse" "float scale" 5
          Shape "disk"
        AttributeEnd
        Shape "sphere""#,
    );
    let get = |ps: &ParamSet, n: &str| ps.get_float(n, -1.0).unwrap();
    assert_eq!(
        get(&d.shapes[0].entity.params, "radius"),
        4.0,
        "own value wins"
    );
    assert_eq!(get(&d.shapes[0].entity.params, "zmax"), 0.5);
    assert_eq!(get(&d.lights[0].entity.params, "scale"), 3.0);
    let al = d.shapes[1].area_light.as_ref().unwrap();
    assert_eq!(get(&al.params, "scale"), 5.0);
    assert!(d.materials[0].entity.params.has("reflectance"));
    assert!(
        !d.shapes[2].entity.params.has("radius"),
        "scoped by AttributeEnd"
    );
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
    let e = load_str(
        "WorldBegin\nAttribute \"camera\" \"float x\" 1",
        "t",
        Path::new("."),
    )
    .unwrap_err();
    assert!(e.message.contains("unknown Attribute target"), "{e}");
}

#[test]
fn missing_attribute_end_is_a_warning() {
    let d = load("WorldBegin\nAttributeBegin\nShape \"sphere\"");
    assert_eq!(d.shapes.len(), 1);
    assert_eq!(d.warnings.len(), 1);
    assert!(d.warnings[0].message.contains("no matching AttributeEnd"));
    assert_eq!(d.warnings[0].loc.as_ref().unwrap().line, 2);
}

#[test]
fn include_is_relative_to_the_top_level_folder() {
    let dir = std::env::temp_dir().join(format!(
        "lumis-scene-inc-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::create_dir_all(dir.join("geo")).unwrap();
    std::fs::write(
        dir.join("geo/a.pbrt"),
        "Shape \"sphere\"\nInclude \"geo/b.pbrt\"\n",
    )
    .unwrap();
    std::fs::write(dir.join("geo/b.pbrt"), "Shape \"disk\"\n").unwrap();
    std::fs::write(dir.join("geo/bad.pbrt"), "Shape \"disk\"\n  Shapee \"x\"\n").unwrap();
    std::fs::write(
        dir.join("main.pbrt"),
        "WorldBegin\nMaterial \"diffuse\"\nTranslate 0 0 1\nInclude \"geo/a.pbrt\"\nImport \"geo/b.pbrt\"\n",
    )
    .unwrap();
    let d = load_file(&dir.join("main.pbrt")).unwrap();
    assert_eq!(d.base_dir, dir);
    let tys: Vec<&str> = d.shapes.iter().map(|s| s.entity.ty.as_str()).collect();
    assert_eq!(tys, ["sphere", "disk", "disk"]);
    assert!(matches!(d.shapes[1].material, MaterialRef::Index(0)));
    assert_eq!(d.shapes[1].object_to_world.point(Vec3::ZERO), Vec3::Z);
    assert!(d.shapes[0].entity.loc.file.path.ends_with("a.pbrt"));
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);

    // Errors inside an included file point into that file.
    std::fs::write(
        dir.join("main2.pbrt"),
        "WorldBegin\nInclude \"geo/bad.pbrt\"\n",
    )
    .unwrap();
    let e = load_file(&dir.join("main2.pbrt")).unwrap_err().to_string();
    assert!(
        e.contains("bad.pbrt:2:3: error: unknown directive `Shapee`"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn include_cycle_is_an_error_not_a_hang() {
    let dir = std::env::temp_dir().join(format!("lumis-scene-cyc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("a.pbrt"), "Include \"a.pbrt\"\n").unwrap();
    let e = load_file(&dir.join("a.pbrt")).unwrap_err();
    assert!(e.message.contains("too deep"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn objects_keep_their_shapes_and_instances_their_transforms() {
    let d = load(
        r#"WorldBegin
        Translate 0 0 5
        ObjectBegin "thing"
          Material "diffuse"
          Translate 1 0 0
          Shape "sphere"
          AreaLightSource "diffuse"
          Shape "disk"
        ObjectEnd
        Shape "disk"
        AttributeBegin
          Translate 0 2 0
          ObjectInstance "later"
        AttributeEnd
        ObjectInstance "thing"
        ObjectBegin "later" Shape "sphere" ObjectEnd"#,
    );
    assert_eq!(d.shapes.len(), 1, "object shapes are not top-level shapes");
    assert!(
        d.shapes[0].area_light.is_none(),
        "ObjectEnd restores the state"
    );
    assert_eq!(d.objects.len(), 2);
    let thing = &d.objects[0];
    assert_eq!(thing.name, "thing");
    let tys: Vec<&str> = thing.shapes.iter().map(|s| s.entity.ty.as_str()).collect();
    assert_eq!(tys, ["sphere", "disk"]);
    // The shape's own CTM includes everything up to its Shape directive.
    assert_eq!(
        thing.shapes[0].object_to_world.point(Vec3::ZERO),
        Vec3::new(1.0, 0.0, 5.0)
    );
    assert!(matches!(thing.shapes[0].material, MaterialRef::Index(0)));
    // Area lights inside objects are refused with a located warning.
    assert!(thing.shapes[1].area_light.is_none());
    let w = d
        .warnings
        .iter()
        .find(|w| {
            w.message
                .contains("area lights are not supported in object instances")
        })
        .expect("a warning");
    assert_eq!(w.loc.as_ref().unwrap().line, 8);
    // Instances: forward references resolve; the CTM at the directive is kept.
    assert_eq!(d.instances.len(), 2);
    assert_eq!(d.instances[0].object, 1);
    assert_eq!(
        d.instances[0].world_from_object.point(Vec3::ZERO),
        Vec3::new(0.0, 2.0, 5.0)
    );
    assert_eq!(d.instances[1].object, 0);
    assert_eq!(d.instances[1].loc.line, 15);
}

#[test]
fn object_errors_are_located() {
    for (text, needle, line) in [
        (
            "WorldBegin\nObjectInstance \"nope\"",
            "object `nope` is not defined",
            2,
        ),
        (
            "WorldBegin\nObjectBegin \"a\"\nObjectBegin \"b\"",
            "ObjectBegin inside another object",
            3,
        ),
        (
            "WorldBegin\nObjectBegin \"a\"\nObjectInstance \"a\"",
            "ObjectInstance inside an object definition",
            3,
        ),
        (
            "WorldBegin\nObjectBegin \"a\" ObjectEnd\nObjectBegin \"a\"",
            "object `a` is defined twice",
            3,
        ),
        ("WorldBegin\nObjectEnd", "without a matching begin", 2),
    ] {
        let e = load_str(text, "t.pbrt", Path::new(".")).unwrap_err();
        assert!(e.message.contains(needle), "{text}: {e}");
        assert_eq!(e.loc.as_ref().unwrap().line, line, "{text}: {e}");
    }
}

#[test]
fn import_does_not_leak_graphics_state() {
    let dir = std::env::temp_dir().join(format!("lumis-scene-imp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("part.pbrt"),
        "Translate 0 0 3\nMaterial \"conductor\"\nShape \"sphere\"\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("main.pbrt"),
        "WorldBegin\nMaterial \"diffuse\"\nImport \"part.pbrt\"\nShape \"disk\"\nInclude \"part.pbrt\"\nShape \"disk\"\n",
    )
    .unwrap();
    let d = load_file(&dir.join("main.pbrt")).unwrap();
    let z: Vec<f32> = d
        .shapes
        .iter()
        .map(|s| s.object_to_world.point(Vec3::ZERO).z)
        .collect();
    assert_eq!(z, [3.0, 0.0, 3.0, 3.0]);
    assert!(matches!(d.shapes[1].material, MaterialRef::Index(0)));
    assert!(matches!(d.shapes[3].material, MaterialRef::Index(2)));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn gzipped_scene_files_are_read() {
    use std::io::Write;
    let dir = std::env::temp_dir().join(format!("lumis-scene-gz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let gz = |text: &str| {
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
        e.write_all(text.as_bytes()).unwrap();
        e.finish().unwrap()
    };
    std::fs::write(dir.join("part.pbrt.gz"), gz("Shape \"disk\"\n")).unwrap();
    std::fs::write(
        dir.join("main.pbrt.gz"),
        gz("WorldBegin\nShape \"sphere\"\nInclude \"part.pbrt.gz\"\n"),
    )
    .unwrap();
    let d = load_file(&dir.join("main.pbrt.gz")).unwrap();
    let tys: Vec<&str> = d.shapes.iter().map(|s| s.entity.ty.as_str()).collect();
    assert_eq!(tys, ["sphere", "disk"]);
    std::fs::write(dir.join("bad.pbrt.gz"), &gz("WorldBegin")[..8]).unwrap();
    let e = load_file(&dir.join("bad.pbrt.gz")).unwrap_err();
    assert!(e.message.contains("gzip"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}
