//! The photon pass's shortcuts change nothing it stores: caustic photons
//! traced sorted by where they meet a specular shape (`photon/order.rs`),
//! and refused by a light-wide polar-angle window (`photon/polar.rs`).

use crate::common::*;
use lumis_math::rng::Pcg32;
use lumis_math::{Vec2, Vec3};
use lumis_render::integrator::photon::aim::{Aims, Targets};
use lumis_render::integrator::photon::order::SORT_ABOVE_BYTES;
use lumis_render::integrator::photon::polar::PolarWindows;
use lumis_render::integrator::photon::trace::{trace_photons, MapKind, Traced};
use std::sync::atomic::AtomicBool;

/// A UV sphere of `stacks` stacks and `2 stacks` slices as a pbrt
/// triangle mesh.
fn sphere_mesh(c: Vec3, r: f32, stacks: u32) -> String {
    let slices = 2 * stacks;
    let mut p = vec![c + Vec3::Z * r, c - Vec3::Z * r];
    for i in 1..stacks {
        let t = std::f32::consts::PI * i as f32 / stacks as f32;
        for j in 0..slices {
            let f = 2.0 * std::f32::consts::PI * j as f32 / slices as f32;
            p.push(c + Vec3::new(t.sin() * f.cos(), t.sin() * f.sin(), t.cos()) * r);
        }
    }
    let at = |i: u32, j: u32| 2 + (i - 1) * slices + j % slices;
    let mut idx = Vec::new();
    for j in 0..slices {
        idx.extend([0, at(1, j), at(1, j + 1)]);
        idx.extend([1, at(stacks - 1, j + 1), at(stacks - 1, j)]);
        for i in 1..stacks - 1 {
            idx.extend([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            idx.extend([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let p: Vec<String> = p
        .iter()
        .map(|v| format!("{} {} {}", v.x, v.y, v.z))
        .collect();
    let idx: Vec<String> = idx.iter().map(u32::to_string).collect();
    format!(
        "Shape \"trianglemesh\" \"point3 P\" [ {} ] \"integer indices\" [ {} ]",
        p.join(" "),
        idx.join(" ")
    )
}

/// On a scene whose geometry is large enough for the sorted order, the
/// caustic photons, their normals and their connections to the camera are
/// bit for bit those traced in photon order with neither shortcut (no
/// start spheres: every photon traced, in order, none refused early).
#[test]
fn sorted_and_windowed_caustic_photons_store_what_plain_tracing_stores() {
    let text = format!(
        "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\n\
         LookAt 0 -3 1.5  0 0 0.5  0 0 1\nCamera \"perspective\"\nWorldBegin\n\
         AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\nShape \"trianglemesh\" \"point3 P\" [ -0.2 -0.2 2.5  0.2 -0.2 2.5  0.2 0.2 2.5  -0.2 0.2 2.5 ] \"integer indices\" [ 0 2 1 0 3 2 ]\nAttributeEnd\n\
         AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\n{}\nAttributeEnd\n\
         AttributeBegin\nMaterial \"conductor\"\nTranslate -0.9 0.2 0.2\nShape \"sphere\" \"float radius\" [ 0.2 ]\nAttributeEnd\n\
         Material \"diffuse\"\nShape \"trianglemesh\" \"point3 P\" [ -9 -9 0  9 -9 0  9 9 0  -9 9 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n",
        sphere_mesh(Vec3::new(0.2, 0.1, 0.7), 0.4, 120)
    );
    let l = load(&text, &Default::default());
    let scene = &l.scene;
    assert!(scene.geometry_memory_bytes() > SORT_ABOVE_BYTES);
    let never = AtomicBool::new(false);
    let connect = Some(Vec2::splat(1.0));
    let trace = |aims: &Aims| {
        trace_photons(
            scene,
            100_000,
            MapKind::Caustic,
            3,
            8,
            aims,
            connect,
            &never,
        )
        .unwrap()
    };
    let aims = Aims::new(scene, false);
    assert!(aims.starts.is_some());
    let (fast, plain) = (trace(&aims), trace(&Aims::default()));
    assert!(plain.photons.len() > 1000, "{}", plain.photons.len());
    assert!(!plain.connections.is_empty());
    let text = |t: &Traced| {
        format!(
            "{:?}\n{:?}\n{:?}\n{:?}",
            t.photons, t.normals, t.volume, t.connections
        )
    };
    assert!(
        text(&fast) == text(&plain),
        "the shortcuts changed what is stored"
    );
}

/// A photon the windows refuse is one whose ray `may_hit` refuses, for
/// lights close to the spheres (wide windows), a two-sided light and
/// directions within 1e-7 of the horizon; and the windows refuse most
/// of the photons refused on a light far from the spheres.
#[test]
fn windows_refuse_only_rays_that_miss_every_start() {
    let text = "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nCamera \"perspective\"\nWorldBegin\n\
        AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0.2 0.1 1\nShape \"sphere\" \"float radius\" [ 0.3 ]\nAttributeEnd\n\
        AttributeBegin\nMaterial \"conductor\"\nTranslate -0.6 0.2 0.4\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0  0.4 0 0  0 0.4 0  0 0 0.4 ] \"integer indices\" [ 0 2 1  0 1 3  0 3 2  1 2 3 ]\nAttributeEnd\n\
        AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\nShape \"trianglemesh\" \"point3 P\" [ -0.5 -0.5 1.5  0.5 -0.5 1.5  0.5 0.5 1.5  -0.5 0.5 1.5 ] \"integer indices\" [ 0 2 1 0 3 2 ]\nAttributeEnd\n\
        AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 2 1 1 ] \"bool twosided\" true\nShape \"trianglemesh\" \"point3 P\" [ -1 -1 0.1  1.5 -1 0.3  0 1.5 0.9 ] \"integer indices\" [ 0 1 2 ]\nAttributeEnd\n\
        AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 2 ]\nShape \"trianglemesh\" \"point3 P\" [ 3 3 6  3.2 3 6  3 3.2 6 ] \"integer indices\" [ 0 2 1 ]\nAttributeEnd\n\
        Material \"diffuse\"\nShape \"trianglemesh\" \"point3 P\" [ -9 -9 0  9 -9 0  9 9 0  -9 9 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n";
    let l = load(text, &Default::default());
    let scene = &l.scene;
    let starts = Targets::starts(scene).expect("two specular shapes");
    let windows = PolarWindows::new(scene, &starts);
    assert_eq!(scene.lights.len(), 4, "two quad triangles, two triangles");
    let mut rng = Pcg32::new(9, 1);
    // Per light: refused by `may_hit`, and of those by the windows.
    let mut refused = [(0u32, 0u32); 4];
    for i in 0..400_000 {
        let li = i % scene.lights.len();
        let light = &scene.lights[li];
        let mut u = || rng.next_f32();
        let u1 = Vec2::new(u(), u());
        let mut u2 = Vec2::new(u(), u());
        if i % 4 == 1 {
            let edge = 10f32.powf(-7.0 + 3.0 * u());
            u2.y = if u() < 0.5 { edge } else { 1.0 - edge };
        }
        let pass = windows.may_pass(li as u32, light, u2);
        let Some(full) = light.sample_le(&scene.shapes, u1, u2) else {
            continue;
        };
        if starts.may_hit(&full.ray) {
            assert!(pass, "light {li}, sample {i} refused: {full:?}");
        } else {
            refused[li].0 += 1;
            refused[li].1 += u32::from(!pass);
        }
    }
    eprintln!("refused by may_hit, and of those by the windows: {refused:?}");
    // The far light sees both spheres in a narrow window.
    let (all, early) = refused[3];
    assert!(early * 10 >= all * 8, "{early} of {all}");
}
