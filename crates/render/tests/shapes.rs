//! The shapes of the scene-loading issue through the whole load: hits
//! against analytic answers.

use crate::common;

use common::*;
use lumis_math::Vec3;
use lumis_render::geometry::Ray;

fn scene(shapes: &str) -> lumis_render::load::LoadedScene {
    let text = format!("Camera \"perspective\"\nWorldBegin\nLightSource \"distant\"\n{shapes}\n");
    let l = load(&text, &Default::default());
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    l
}

#[test]
fn bilinear_patch_hits_its_surface() {
    // z = u v on the unit square, as pbrt-v4's patch (p00, p10, p01, p11).
    let l = scene(r#"Shape "bilinearmesh" "point3 P" [0 0 0 1 0 0 0 1 0 1 1 1]"#);
    for (x, y) in [(0.25, 0.5), (0.8, 0.9), (0.1, 0.05)] {
        let h = l
            .scene
            .intersect(&Ray::new(Vec3::new(x, y, 5.0), -Vec3::Z))
            .unwrap();
        assert!(
            (h.geom.p.z - x * y).abs() < 2.0 / 512.0,
            "{x} {y}: {}",
            h.geom.p
        );
        assert!((h.geom.uv.x - x).abs() < 1e-4 && (h.geom.uv.y - y).abs() < 1e-4);
    }
    assert!(l
        .scene
        .intersect(&Ray::new(Vec3::new(1.2, 0.5, 5.0), -Vec3::Z))
        .is_none());
}

#[test]
fn cylinder_and_cut_sphere_through_the_loader() {
    let l = scene(
        r#"AttributeBegin Translate 0 0 5 Shape "cylinder" "float radius" 2 "float zmin" -1 "float zmax" 1 AttributeEnd
           Shape "sphere" "float radius" 1 "float zmax" 0"#,
    );
    // Down the axis: the cylinder is open; the lower hemisphere is hit from inside at z = -1.
    let h = l
        .scene
        .intersect(&Ray::new(Vec3::new(0.0, 0.0, 10.0), -Vec3::Z))
        .unwrap();
    assert!((h.t - 11.0).abs() < 1e-4, "{}", h.t);
    // Sideways at z = 5: the cylinder wall at x = -2.
    let h = l
        .scene
        .intersect(&Ray::new(Vec3::new(-9.0, 0.0, 5.0), Vec3::X))
        .unwrap();
    assert!((h.t - 7.0).abs() < 1e-4);
}

#[test]
fn loopsubdiv_through_the_loader() {
    let l = scene(
        r#"Shape "loopsubdiv" "integer levels" 2 "point3 P" [1 1 1 1 -1 -1 -1 1 -1 -1 -1 1]
           "integer indices" [0 1 2 0 3 1 0 2 3 1 3 2]"#,
    );
    assert_eq!(l.scene.world.prims.len(), 4 * 16);
    // The limit surface lies inside the control tetrahedron: a ray from the
    // centre outward along a vertex direction meets it before the vertex.
    let d = Vec3::ONE.normalize();
    let h = l.scene.intersect(&Ray::new(Vec3::ZERO, d)).unwrap();
    assert!(h.t > 0.0 && h.t < 3f32.sqrt());
    assert!(
        h.geom.ns.dot(d) > 0.99,
        "shading normal from the limit surface"
    );
}
