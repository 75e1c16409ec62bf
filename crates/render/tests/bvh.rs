//! BVH correctness against brute force over all primitives.

use lumis_math::{Mat4, Pcg32, Rgb, Transform, Vec3};
use lumis_render::accel::bench::{bumpy_sphere, inward_rays, mesh_bounds, random_rays, MeshAccel};
use lumis_render::accel::Bvh;
use lumis_render::camera::Camera;
use lumis_render::geometry::triangle::{intersect_triangle, RayShear};
use lumis_render::geometry::{Aabb, Disk, Prim, Ray, Sphere, TriangleMesh};
use lumis_render::material::{DiffuseMaterial, MaterialKind};
use lumis_render::scene::{PrimInfo, Scene, Shapes, NO_LIGHT};
use lumis_render::texture::TexRgb;
use proptest::prelude::*;

type Tri = [Vec3; 3];

fn tri_bounds(v: &Tri) -> Aabb {
    let mut b = Aabb::from_point(v[0]);
    b.grow(v[1]);
    b.grow(v[2]);
    b
}

fn rand_vec(rng: &mut Pcg32, lo: f32, hi: f32) -> Vec3 {
    Vec3::new(
        lo + (hi - lo) * rng.next_f32(),
        lo + (hi - lo) * rng.next_f32(),
        lo + (hi - lo) * rng.next_f32(),
    )
}

/// Snaps to a grid of 1/8 so rays and planes coincide exactly.
fn snap(v: Vec3) -> Vec3 {
    (v * 8.0).round() / 8.0
}

/// A soup of `n` triangles of mixed kinds: ordinary, tiny, huge, thin,
/// degenerate (collinear or a point), duplicated, axis-aligned on a grid.
fn soup(n: usize, seed: u64) -> Vec<Tri> {
    let mut rng = Pcg32::new(seed, 11);
    let mut tris: Vec<Tri> = Vec::with_capacity(n);
    for _ in 0..n {
        let c = rand_vec(&mut rng, -1.0, 1.0);
        let s = 10f32.powf(-3.0 * rng.next_f32()); // 1e-3 .. 1
        let kind = rng.next_below(8);
        let t = match kind {
            0 | 1 => [
                c + s * rand_vec(&mut rng, -1.0, 1.0),
                c + s * rand_vec(&mut rng, -1.0, 1.0),
                c + s * rand_vec(&mut rng, -1.0, 1.0),
            ],
            2 => {
                // Thin: third vertex almost on the first edge.
                let a = c + s * rand_vec(&mut rng, -1.0, 1.0);
                let b = c + s * rand_vec(&mut rng, -1.0, 1.0);
                let m = a.lerp(b, rng.next_f32()) + 1e-5 * s * rand_vec(&mut rng, -1.0, 1.0);
                [a, b, m]
            }
            3 => {
                // Degenerate: collinear, or all three vertices equal.
                let a = c + s * rand_vec(&mut rng, -1.0, 1.0);
                if rng.next_below(2) == 0 {
                    [a, a, a]
                } else {
                    let b = c + s * rand_vec(&mut rng, -1.0, 1.0);
                    [a, b, a + 2.0 * (b - a)]
                }
            }
            4 if !tris.is_empty() => {
                let i = rng.next_below(tris.len() as u32) as usize;
                tris[i]
            }
            5 | 6 => {
                // Axis-aligned, on a grid: all vertices share one coordinate.
                let ax = rng.next_below(3) as usize;
                let c = snap(c);
                let mut v = [
                    snap(c + rand_vec(&mut rng, -0.5, 0.5)),
                    snap(c + rand_vec(&mut rng, -0.5, 0.5)),
                    snap(c + rand_vec(&mut rng, -0.5, 0.5)),
                ];
                for p in v.iter_mut() {
                    p[ax] = c[ax];
                }
                if rng.next_below(2) == 0 {
                    // Axis-aligned right triangle (box-shaped in-plane extent).
                    let (u, w) = ((ax + 1) % 3, (ax + 2) % 3);
                    v[1][w] = v[0][w];
                    v[2][u] = v[0][u];
                }
                v
            }
            _ => [
                c + 3.0 * rand_vec(&mut rng, -1.0, 1.0),
                c + 3.0 * rand_vec(&mut rng, -1.0, 1.0),
                c + 3.0 * rand_vec(&mut rng, -1.0, 1.0),
            ],
        };
        tris.push(t);
    }
    tris
}

/// Rays with origins inside and outside the soup's bounds, random, axis-aligned
/// (with exact zero and negative-zero components) or aimed at triangle vertices.
fn rays(tris: &[Tri], n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Pcg32::new(seed, 12);
    (0..n)
        .map(|_| {
            let o = match rng.next_below(3) {
                0 => rand_vec(&mut rng, -1.2, 1.2),
                1 => rand_vec(&mut rng, -4.0, 4.0),
                _ => snap(rand_vec(&mut rng, -1.5, 1.5)),
            };
            let d = match rng.next_below(5) {
                0 => {
                    let ax = rng.next_below(3) as usize;
                    let mut d = Vec3::new(0.0, -0.0, 0.0);
                    d[ax] = if rng.next_below(2) == 0 { 1.0 } else { -1.0 };
                    d
                }
                1 => {
                    let mut d = rand_vec(&mut rng, -1.0, 1.0);
                    d[rng.next_below(3) as usize] = if rng.next_below(2) == 0 { 0.0 } else { -0.0 };
                    d
                }
                2 => {
                    let t = tris[rng.next_below(tris.len() as u32) as usize];
                    t[rng.next_below(3) as usize] - o
                }
                3 => {
                    let t = tris[rng.next_below(tris.len() as u32) as usize];
                    (t[0] + t[1] + t[2]) / 3.0 - o
                }
                _ => rand_vec(&mut rng, -1.0, 1.0),
            };
            let d = if d == Vec3::ZERO { Vec3::Z } else { d };
            // Unnormalised directions on purpose: the BVH must not assume unit length.
            Ray::new(
                o,
                if rng.next_below(2) == 0 {
                    d.normalize()
                } else {
                    d
                },
            )
        })
        .collect()
}

fn brute_closest(tris: &[Tri], ray: &Ray) -> Option<f32> {
    let sh = RayShear::new(ray.d);
    let mut best: Option<f32> = None;
    for v in tris {
        if let Some((t, _, _)) = intersect_triangle(ray, &sh, v, ray.tmax) {
            if best.is_none_or(|b| t < b) {
                best = Some(t);
            }
        }
    }
    best
}

fn brute_any(tris: &[Tri], ray: &Ray) -> bool {
    let sh = RayShear::new(ray.d);
    tris.iter()
        .any(|v| intersect_triangle(ray, &sh, v, ray.tmax).is_some())
}

/// Checks closest and any-hit queries of a BVH over `tris` against brute force.
fn check(tris: &[Tri], bvh: &Bvh, rays: &[Ray], rng: &mut Pcg32) -> Result<(), TestCaseError> {
    for ray in rays {
        let sh = RayShear::new(ray.d);
        let got = bvh.closest(ray, |slot, r, tmax| {
            intersect_triangle(r, &sh, &tris[bvh.order[slot as usize] as usize], tmax).map(|h| h.0)
        });
        let want = brute_closest(tris, ray);
        prop_assert_eq!(got.map(|h| h.0), want, "closest t, ray {:?}", ray);
        if let Some((t, slot)) = got {
            // With ties, any triangle at exactly that t is fine; it must really be hit there.
            let v = &tris[bvh.order[slot as usize] as usize];
            let own = intersect_triangle(ray, &sh, v, f32::INFINITY).map(|h| h.0);
            prop_assert_eq!(own, Some(t));
        }
        // Any-hit with a random tmax, around and beyond the closest hit.
        for _ in 0..3 {
            let tmax = match want {
                Some(t) if rng.next_below(2) == 0 => t * (0.5 + rng.next_f32()),
                _ => 8.0 * rng.next_f32() * rng.next_f32(),
            };
            let mut r = *ray;
            r.tmax = tmax;
            let got = bvh.any(&r, |slot, r, tmax| {
                intersect_triangle(r, &sh, &tris[bvh.order[slot as usize] as usize], tmax).is_some()
            });
            prop_assert_eq!(got, brute_any(tris, &r), "any-hit, ray {:?}", r);
        }
        // The exact closest distance as tmax: the hit itself must not count (t < tmax).
        if let Some(t) = want {
            let mut r = *ray;
            r.tmax = t;
            let got = bvh.any(&r, |slot, r, tmax| {
                intersect_triangle(r, &sh, &tris[bvh.order[slot as usize] as usize], tmax).is_some()
            });
            prop_assert!(!got, "any-hit at tmax = closest t");
        }
    }
    Ok(())
}

fn bvh_of(tris: &[Tri]) -> Bvh {
    let boxes: Vec<Aabb> = tris.iter().map(tri_bounds).collect();
    Bvh::build(&boxes)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn soup_matches_brute_force(n in 1usize..2000, seed in any::<u64>()) {
        let tris = soup(n, seed);
        let bvh = bvh_of(&tris);
        let mut rng = Pcg32::new(seed, 13);
        check(&tris, &bvh, &rays(&tris, 64, seed), &mut rng)?;
    }

    #[test]
    fn small_soups_match_brute_force(n in 1usize..12, seed in any::<u64>()) {
        let tris = soup(n, seed);
        let bvh = bvh_of(&tris);
        let mut rng = Pcg32::new(seed, 14);
        check(&tris, &bvh, &rays(&tris, 64, seed), &mut rng)?;
    }
}

#[test]
fn bvh_covers_every_box_once() {
    let tris = soup(1500, 3);
    let bvh = bvh_of(&tris);
    let non_empty = tris.iter().filter(|t| !tri_bounds(t).is_empty()).count();
    let mut seen = bvh.order.clone();
    seen.sort_unstable();
    seen.dedup();
    assert_eq!(seen.len(), non_empty);
    assert_eq!(bvh.order.len(), non_empty);
    let mut all = Aabb::EMPTY;
    for t in &tris {
        all = all.union(&tri_bounds(t));
    }
    assert_eq!(bvh.bounds(), all);
}

/// Boxes with NaN or empty extents are skipped, the rest still work.
#[test]
fn empty_boxes_are_skipped() {
    let tris = soup(100, 4);
    let mut boxes: Vec<Aabb> = tris.iter().map(tri_bounds).collect();
    boxes.insert(10, Aabb::EMPTY);
    boxes.push(Aabb::EMPTY);
    let bvh = Bvh::build(&boxes);
    assert_eq!(bvh.order.len(), 100);
    assert!(!bvh.order.contains(&10) && !bvh.order.contains(&101));
}

fn nested_same_centroid(n: usize) -> Vec<Tri> {
    // Box centre exactly (0.5, 0.5, 0.5) for every triangle: sizes 2^-k, six orientations.
    let c = Vec3::splat(0.5);
    (0..n)
        .map(|k| {
            let s = 0.5f32.powi((k % 20) as i32);
            let (a, b, d) = match k % 6 {
                0 => (
                    Vec3::new(-1.0, -1.0, 0.0),
                    Vec3::new(1.0, 0.0, -1.0),
                    Vec3::new(0.0, 1.0, 1.0),
                ),
                1 => (
                    Vec3::new(1.0, -1.0, 0.0),
                    Vec3::new(-1.0, 0.0, 1.0),
                    Vec3::new(0.0, 1.0, -1.0),
                ),
                2 => (
                    Vec3::new(0.0, -1.0, -1.0),
                    Vec3::new(-1.0, 1.0, 0.0),
                    Vec3::new(1.0, 0.0, 1.0),
                ),
                3 => (
                    Vec3::new(-1.0, 0.0, -1.0),
                    Vec3::new(1.0, -1.0, 1.0),
                    Vec3::new(0.0, 1.0, 0.0),
                ),
                4 => (
                    Vec3::new(-1.0, -1.0, -1.0),
                    Vec3::new(1.0, 1.0, -1.0),
                    Vec3::new(0.0, 0.0, 1.0),
                ),
                _ => (
                    Vec3::new(-1.0, 1.0, 1.0),
                    Vec3::new(1.0, -1.0, 1.0),
                    Vec3::new(0.0, 0.0, -1.0),
                ),
            };
            [c + s * a, c + s * b, c + s * d]
        })
        .collect()
}

fn geometric_series(n: usize) -> Vec<Tri> {
    // Triangles shrinking and moving towards the origin geometrically: a binned
    // SAH peels off one or two per split, the worst case for tree depth.
    let mut rng = Pcg32::new(99, 1);
    (0..n)
        .map(|k| {
            let s = 0.8f32.powi((k % 400) as i32) * (1.0 + 0.001 * (k / 400) as f32);
            let c = Vec3::new(s, 0.5 * s, 0.25 * s);
            [
                c + 0.3 * s * rand_vec(&mut rng, -1.0, 1.0),
                c + 0.3 * s * rand_vec(&mut rng, -1.0, 1.0),
                c + 0.3 * s * rand_vec(&mut rng, -1.0, 1.0),
            ]
        })
        .collect()
}

#[test]
fn deep_degenerate_inputs_build_and_trace() {
    for (name, tris) in [
        ("same centroid", nested_same_centroid(100_000)),
        ("geometric series", geometric_series(100_000)),
    ] {
        let bvh = bvh_of(&tris);
        assert_eq!(bvh.order.len(), tris.len(), "{name}");
        let mut rng = Pcg32::new(5, 5);
        let mut rs = rays(&tris[..2000], 150, 7);
        // Rays through the dense core.
        for _ in 0..100 {
            let o = rand_vec(&mut rng, -2.0, 2.0);
            let target = tris[rng.next_below(tris.len() as u32) as usize][0];
            rs.push(Ray::new(o, target - o));
        }
        check(&tris, &bvh, &rs, &mut rng).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn mesh_accel_matches_brute_force() {
    let mesh = bumpy_sphere(20_000, 3);
    let tris: Vec<Tri> = (0..mesh.triangle_count() as u32)
        .map(|t| mesh.vertices(t))
        .collect();
    let acc = MeshAccel::new(&mesh);
    let b = mesh_bounds(&mesh);
    let mut hits = 0;
    for r in random_rays(&b, 300, 1)
        .iter()
        .chain(&inward_rays(&b, 300, 2))
    {
        let got = acc.closest(r);
        assert_eq!(got.map(|h| h.0), brute_closest(&tris, r));
        if let Some((t, tri)) = got {
            hits += 1;
            let sh = RayShear::new(r.d);
            let own = intersect_triangle(r, &sh, &tris[tri as usize], f32::INFINITY);
            assert_eq!(own.map(|h| h.0), Some(t));
        }
        let mut s = *r;
        s.tmax = 1.0;
        assert_eq!(acc.any(&s), brute_any(&tris, &s));
    }
    assert!(hits > 300, "inward rays must hit: {hits}");
}

// --- Through the public Scene API, with spheres and disks mixed in ---

enum Shape {
    Tri(Tri),
    Sphere(Sphere),
    Disk(Disk),
}

fn shape_hit(s: &Shape, ray: &Ray, tmax: f32) -> Option<f32> {
    match s {
        Shape::Tri(v) => intersect_triangle(ray, &RayShear::new(ray.d), v, tmax).map(|h| h.0),
        Shape::Sphere(sp) => sp.intersect(ray, tmax),
        Shape::Disk(d) => d.intersect(ray, tmax),
    }
}

fn mixed_scene(seed: u64, n_tris: usize) -> (Scene, Vec<Shape>) {
    let mut rng = Pcg32::new(seed, 21);
    let tris = soup(n_tris, seed);
    let mesh = TriangleMesh {
        positions: tris.iter().flatten().copied().collect(),
        normals: None,
        uvs: None,
        indices: (0..3 * tris.len() as u32).collect(),
        flip_normals: false,
    };
    let mut shapes = Shapes {
        meshes: vec![mesh],
        ..Default::default()
    };
    let mut prims = Vec::new();
    let mut reference = Vec::new();
    let info = |prim| PrimInfo {
        prim,
        material: 0,
        light: NO_LIGHT,
    };
    for (i, t) in tris.iter().enumerate() {
        prims.push(info(Prim::Triangle {
            mesh: 0,
            tri: i as u32,
        }));
        reference.push(Shape::Tri(*t));
    }
    for i in 0..40 {
        let c = rand_vec(&mut rng, -1.0, 1.0);
        let tf = Transform::new(Mat4::from_translation(c)).unwrap();
        if i % 2 == 0 {
            let s = Sphere::new(tf, 0.02 + 0.3 * rng.next_f32(), false);
            shapes.spheres.push(s);
            prims.push(info(Prim::Sphere(shapes.spheres.len() as u32 - 1)));
            reference.push(Shape::Sphere(s));
        } else {
            let axis = rand_vec(&mut rng, -1.0, 1.0).normalize();
            let rot = Mat4::from_axis_angle(axis, 3.0 * rng.next_f32());
            let tf = tf.compose(&Transform::new(rot).unwrap());
            let d = Disk::new(
                tf,
                0.1 * rng.next_f32(),
                0.05 + 0.4 * rng.next_f32(),
                0.0,
                false,
            );
            shapes.disks.push(d);
            prims.push(info(Prim::Disk(shapes.disks.len() as u32 - 1)));
            reference.push(Shape::Disk(d));
        }
    }
    let scene = Scene::new(
        shapes,
        prims,
        vec![MaterialKind::Diffuse(DiffuseMaterial {
            reflectance: TexRgb::Const(Rgb::splat(0.5)),
        })
        .into()],
        vec![],
        Camera::perspective(Transform::IDENTITY, (4, 4), 60.0, 0.0, 1.0),
    );
    (scene, reference)
}

#[test]
fn scene_matches_brute_force() {
    for seed in 0..6u64 {
        let (scene, reference) = mixed_scene(seed, 400 + 300 * seed as usize);
        let tris: Vec<Tri> = reference
            .iter()
            .filter_map(|s| match s {
                Shape::Tri(t) => Some(*t),
                _ => None,
            })
            .collect();
        let mut rng = Pcg32::new(seed, 22);
        let mut rs = rays(&tris, 300, seed);
        for _ in 0..100 {
            let o = rand_vec(&mut rng, -3.0, 3.0);
            rs.push(Ray::new(o, (rand_vec(&mut rng, -1.0, 1.0) - o).normalize()));
        }
        for ray in &rs {
            let want = reference
                .iter()
                .filter_map(|s| shape_hit(s, ray, f32::INFINITY))
                .min_by(f32::total_cmp);
            let got = scene.intersect(ray);
            assert_eq!(got.map(|h| h.t), want, "seed {seed} ray {ray:?}");
            if let Some(h) = got {
                let s = match h.prim {
                    Prim::Triangle { tri, .. } => &reference[tri as usize],
                    Prim::Sphere(i) => &reference[tris.len() + 2 * i as usize],
                    Prim::Disk(i) => &reference[tris.len() + 2 * i as usize + 1],
                    Prim::Cylinder(_) => unreachable!("no cylinders in this scene"),
                };
                assert_eq!(shape_hit(s, ray, f32::INFINITY), Some(h.t), "seed {seed}");
            }
            let mut r = *ray;
            r.tmax = 4.0 * rng.next_f32();
            let want = reference.iter().any(|s| shape_hit(s, &r, r.tmax).is_some());
            assert_eq!(scene.occluded(&r), want, "seed {seed} ray {r:?}");
        }
    }
}
