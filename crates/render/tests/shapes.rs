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

#[test]
fn plain_diffuse_hits_are_the_full_hits_bit_for_bit() {
    // Diffuse walls (one textured), a diffuse sphere, a glass sphere, a
    // disk and a light: the lazy answer exists exactly on the world's
    // untextured diffuse triangles and spheres that emit nothing, and there
    // its point, normal and albedo are those of the full hit and its BSDF.
    let l = scene(
        r#"Material "diffuse" "rgb reflectance" [1.5 0.5 0.25]
           Shape "trianglemesh" "point3 P" [-4 -4 -3  4 -4 -3  4 4 -3  -4 4 -3] "integer indices" [0 1 2 0 2 3]
           Texture "c" "spectrum" "checkerboard" "float uscale" 4 "float vscale" 4
           Material "diffuse" "texture reflectance" "c"
           Shape "trianglemesh" "point3 P" [-4 -4 3  -4 4 3  4 4 3  4 -4 3] "integer indices" [0 1 2 0 2 3]
           Material "diffuse" "rgb reflectance" [0.2 0.4 0.6]
           AttributeBegin Translate 1 0.5 0 Scale 1.5 1.5 1.5 Shape "sphere" "float radius" 0.5 AttributeEnd
           AttributeBegin ReverseOrientation Translate -1 0 0 Shape "sphere" "float radius" 0.7 AttributeEnd
           AttributeBegin Translate 0 2 0 Shape "disk" "float radius" 0.8 AttributeEnd
           Material "dielectric"
           AttributeBegin Translate 0 -2 0 Shape "sphere" "float radius" 0.6 AttributeEnd
           AttributeBegin AreaLightSource "diffuse" "rgb L" [1 1 1]
             Material "diffuse"
             Shape "trianglemesh" "point3 P" [-4 -4 -2.9  4 -4 -2.9  4 -3.5 -2.9] "integer indices" [0 1 2]
           AttributeEnd"#,
    );
    let s = &l.scene;
    let mut rng = lumis_math::Pcg32::new(11, 2);
    let (mut plain, mut full) = (0, 0);
    for _ in 0..20_000 {
        let mut u = || 2.0 * rng.next_f32() - 1.0;
        let o = Vec3::new(3.0 * u(), 3.0 * u(), 2.0 * u());
        let d = Vec3::new(u(), u(), u());
        if d.length_squared() < 1e-4 {
            continue;
        }
        let ray = Ray::new(o, d.normalize());
        let Some(lazy) = s.intersect_lazy(&ray) else {
            assert!(s.intersect(&ray).is_none());
            continue;
        };
        let pd = s.plain_diffuse(&lazy, &ray);
        let h = s.finish(lazy, &ray);
        let same = s.intersect(&ray).unwrap();
        assert_eq!(
            (h.t, h.geom.p, h.material),
            (same.t, same.geom.p, same.material)
        );
        let m = &s.materials[h.material as usize];
        let plain_kind = h.light.is_none()
            && m.constant_diffuse().is_some()
            && !matches!(h.prim, lumis_render::geometry::Prim::Disk(_));
        assert_eq!(pd.is_some(), plain_kind, "{:?} {:?}", h.prim, h.material);
        let Some(pd) = pd else {
            full += 1;
            continue;
        };
        plain += 1;
        let albedo = s.bsdf(&h, -ray.d).bsdf.diffuse_albedo().unwrap();
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        assert_eq!(bits(pd.p), bits(h.geom.p));
        assert_eq!(bits(pd.ng), bits(h.geom.ng));
        assert_eq!(pd.albedo, albedo);
    }
    assert!(plain > 2000 && full > 2000, "{plain} plain, {full} others");
}
