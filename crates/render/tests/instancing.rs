//! Object instancing: instances share one copy of their geometry, and an
//! instanced scene gives the same hits as the same geometry written out
//! (flattened) in world space.

use crate::common;

use common::*;
use lumis_math::{Pcg32, Vec3};
use lumis_render::geometry::{Prim, Ray};
use lumis_render::material::Material;

/// A binary little-endian PLY height field of `nx * ny * 2` triangles.
fn write_grid_ply(path: &std::path::Path, nx: usize, ny: usize) {
    let nv = (nx + 1) * (ny + 1);
    let nf = nx * ny * 2;
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {nv}\n\
         property float x\nproperty float y\nproperty float z\n\
         element face {nf}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    .into_bytes();
    for j in 0..=ny {
        for i in 0..=nx {
            let (x, y) = (i as f32 / nx as f32, j as f32 / ny as f32);
            let z = 0.05 * (9.0 * x).sin() * (7.0 * y).cos();
            for c in [x, y, z] {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    for j in 0..ny {
        for i in 0..nx {
            let v = (j * (nx + 1) + i) as i32;
            let w = v + nx as i32 + 1;
            for tri in [[v, v + 1, w + 1], [v, w + 1, w]] {
                out.push(3);
                for k in tri {
                    out.extend_from_slice(&k.to_le_bytes());
                }
            }
        }
    }
    std::fs::write(path, out).unwrap();
}

#[test]
fn ten_thousand_instances_share_one_mesh() {
    let dir = std::env::temp_dir().join(format!("lumis-inst-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ply = dir.join("grid.ply");
    write_grid_ply(&ply, 250, 200); // 100,000 triangles
    let mut text = format!(
        "LookAt 50 -40 60  50 50 0  0 0 1\nCamera \"perspective\" \"float fov\" 50\n\
         Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16\n\
         WorldBegin\nLightSource \"distant\" \"point3 from\" [0 0 1] \"point3 to\" [0 0 0]\n\
         ObjectBegin \"grid\"\nMaterial \"diffuse\"\nShape \"plymesh\" \"string filename\" \"{}\"\nObjectEnd\n",
        ply.display()
    );
    for k in 0..10_000 {
        let (x, y) = ((k % 100) as f32, (k / 100) as f32);
        text += &format!(
            "AttributeBegin Translate {x} {y} 0 Rotate {} 0 0 1 ObjectInstance \"grid\" AttributeEnd\n",
            (k % 4) * 90
        );
    }
    let l = load(&text, &Default::default());
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let s = &l.scene;
    assert_eq!(s.instances.instances.len(), 10_000);
    assert_eq!(s.instances.objects.len(), 1);
    assert_eq!(s.instances.objects[0].prims.len(), 100_000);
    assert_eq!(s.shapes.meshes.len(), 1);
    // One mesh's geometry (vertices, indices, its BVH and leaf-ordered
    // triangles) plus a small record per instance. Copying the mesh per
    // instance would need at least 10,000 * 100,000 * 40 bytes.
    let one_mesh = s.instances.objects[0].memory_bytes() + s.shapes.memory_bytes();
    let total = s.geometry_memory_bytes();
    eprintln!(
        "one mesh {:.1} MiB, whole scene {:.1} MiB",
        one_mesh as f64 / 1048576.0,
        total as f64 / 1048576.0
    );
    assert!(total < one_mesh + 10_000 * 256, "{total} bytes");
    // Rays from above hit the grid of instances; it renders.
    let hit = s.intersect(&Ray::new(Vec3::new(37.3, 61.6, 5.0), -Vec3::Z));
    let h = hit.expect("the instanced grids cover [0,100]^2");
    assert!((h.geom.p.z).abs() < 0.06 && (h.t - 5.0).abs() < 0.06);
    let out = render_loaded(&l, 1, 1, 0);
    assert_eq!(out.bad_samples, 0);
    assert!(image_mean(&out.film, None) > 0.0);
    std::fs::remove_dir_all(&dir).ok();
}

/// A closed bumpy sphere as pbrt `trianglemesh` parameters (object space).
fn bumpy_sphere(n: usize) -> String {
    let mut p = String::new();
    let mut idx = String::new();
    for j in 0..=n {
        for i in 0..=2 * n {
            let th = std::f32::consts::PI * j as f32 / n as f32;
            let ph = std::f32::consts::PI * i as f32 / n as f32;
            let r = 1.0 + 0.1 * (5.0 * ph).sin() * (3.0 * th).sin();
            p += &format!(
                "{} {} {} ",
                r * th.sin() * ph.cos(),
                r * th.sin() * ph.sin(),
                r * th.cos()
            );
        }
    }
    for j in 0..n {
        for i in 0..2 * n {
            let v = j * (2 * n + 1) + i;
            let w = v + 2 * n + 1;
            idx += &format!("{v} {} {} {v} {} {w} ", v + 1, w + 1, w + 1);
        }
    }
    format!("\"point3 P\" [{p}] \"integer indices\" [{idx}]")
}

#[test]
fn instanced_and_flattened_geometry_give_the_same_hits() {
    let mesh = bumpy_sphere(12);
    let placements = [
        "Translate 0 0 0",
        "Translate 3 0 0 Rotate 30 1 1 0 Scale 0.6 0.6 0.6",
        "Translate -2 2 1 Scale -1 1 1",
        "Translate 0 -3 0 Rotate 75 0 0 1 Scale 1.5 1.5 1.5",
        "Translate 1 2 -2 Rotate -40 0 1 0",
    ];
    let head = "Camera \"perspective\"\nWorldBegin\nLightSource \"distant\"\n";
    let mut inst = format!(
        "{head}Translate 0.5 0 0\nObjectBegin \"m\"\nMaterial \"diffuse\"\nTranslate 0 0 0.25\n\
         Shape \"trianglemesh\" {mesh}\nShape \"sphere\" \"float radius\" 0.3\nObjectEnd\nIdentity\n"
    );
    let mut flat = format!("{head}Material \"diffuse\"\n");
    for pl in placements {
        inst += &format!("AttributeBegin {pl} ObjectInstance \"m\" AttributeEnd\n");
        flat += &format!(
            "AttributeBegin {pl} Translate 0.5 0 0 Translate 0 0 0.25 Shape \"trianglemesh\" {mesh}\n\
             Shape \"sphere\" \"float radius\" 0.3 AttributeEnd\n"
        );
    }
    let a = load(&inst, &Default::default()).scene;
    let b = load(&flat, &Default::default()).scene;
    assert_eq!(a.instances.instances.len(), placements.len());
    assert!(b.instances.is_empty());
    // Instance boxes are boxes of transformed object boxes: never tighter.
    assert!((b.bounds.min - a.bounds.min).min_element() > -1e-3);
    assert!((a.bounds.max - b.bounds.max).min_element() > -1e-3);
    let mut rng = Pcg32::new(7, 3);
    let mut rv = |s: f32| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 * s - s;
    let (mut hits, mut disagree) = (0, 0);
    for _ in 0..20_000 {
        let o = rv(6.0);
        let target = rv(3.0);
        let ray = Ray::new(o, (target - o).normalize());
        let (ha, hb) = (a.intersect(&ray), b.intersect(&ray));
        match (ha, hb) {
            (Some(x), Some(y)) => {
                hits += 1;
                let close = (x.t - y.t).abs() <= 1e-4 * x.t.max(1.0)
                    && (x.geom.p - y.geom.p).length() < 1e-3
                    && facing(x.prim, x.geom.ng.dot(y.geom.ng))
                    && same_prim(x.prim, y.prim);
                if !close {
                    disagree += 1;
                }
            }
            (None, None) => {}
            _ => disagree += 1,
        }
        let mut r = ray;
        r.tmax = 8.0 * rng_f(&ray);
        if a.occluded(&r) != b.occluded(&r) {
            disagree += 1;
        }
    }
    eprintln!("{hits} hits, {disagree} disagreements");
    assert!(hits > 5000);
    assert_eq!(disagree, 0);
}

/// A deterministic pseudo-random fraction from a ray (for shadow-ray lengths).
fn rng_f(r: &Ray) -> f32 {
    let h = (r.d.x * 12.9898 + r.d.y * 78.233 + r.d.z * 37.719).sin() * 43758.547;
    h - h.floor()
}

/// Normals agree. Triangles: same side. Spheres: same line only — pbrt-v4
/// flips a sphere's normal when its own transform swaps handedness (the
/// flattened mirrored copy) but not for an instance's transform (the normal
/// is carried by the inverse transpose), and lumis does as pbrt-v4.
fn facing(p: Prim, cos: f32) -> bool {
    match p {
        Prim::Sphere(_) => cos.abs() > 0.999,
        _ => cos > 0.999,
    }
}

/// The same primitive of the object (mesh ids differ between the scenes).
fn same_prim(a: Prim, b: Prim) -> bool {
    match (a, b) {
        (Prim::Triangle { tri: x, .. }, Prim::Triangle { tri: y, .. }) => x == y,
        (Prim::Sphere(_), Prim::Sphere(_)) => true,
        _ => false,
    }
}

/// `Scene::intersect_unless` (geometry only for hits the caller keeps)
/// gives `intersect`'s hits bit for bit, on the world's primitives and on
/// instances, and skips exactly the hits on materials it is told end there.
#[test]
fn hits_without_geometry_are_the_same_hits() {
    let mesh = bumpy_sphere(8);
    let text = format!(
        "Camera \"perspective\"\nWorldBegin\nLightSource \"distant\"\n\
         ObjectBegin \"m\"\nMaterial \"diffuse\"\nShape \"trianglemesh\" {mesh}\nObjectEnd\n\
         AttributeBegin Translate 2 0 0 ObjectInstance \"m\" AttributeEnd\n\
         AttributeBegin Translate -2 0 0 Rotate 30 0 0 1 ObjectInstance \"m\" AttributeEnd\n\
         Material \"dielectric\"\nShape \"trianglemesh\" {mesh}\n\
         Material \"diffuse\"\nShape \"sphere\" \"float radius\" 0.5\n"
    );
    let s = load(&text, &Default::default()).scene;
    assert!(!s.instances.is_empty());
    let mut rng = Pcg32::new(11, 0);
    let mut rv = |k: f32| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 * k - k;
    let (mut kept, mut skipped) = (0, 0);
    for _ in 0..20_000 {
        let o = rv(6.0);
        let ray = Ray::new(o, (rv(2.5) - o).normalize());
        let full = s.intersect(&ray);
        match (full, s.intersect_unless(&ray, Material::never_delta)) {
            (None, None) => {}
            (Some(h), Some(None)) => {
                assert!(s.materials[h.material as usize].never_delta());
                skipped += 1;
            }
            (Some(h), Some(Some(g))) => {
                assert!(!s.materials[h.material as usize].never_delta());
                assert_eq!(
                    (
                        h.t.to_bits(),
                        h.geom.p.to_array(),
                        h.geom.ns.to_array(),
                        h.material
                    ),
                    (
                        g.t.to_bits(),
                        g.geom.p.to_array(),
                        g.geom.ns.to_array(),
                        g.material
                    )
                );
                kept += 1;
            }
            (a, b) => panic!(
                "{:?} against {:?}",
                a.map(|h| h.t),
                b.map(|h| h.map(|h| h.t))
            ),
        }
        let all = s.intersect_unless(&ray, |_| false).flatten();
        assert_eq!(
            full.map(|h| h.geom.ng.to_array()),
            all.map(|h| h.geom.ng.to_array())
        );
    }
    assert!(
        kept > 1000 && skipped > 1000,
        "{kept} kept, {skipped} skipped"
    );
}
