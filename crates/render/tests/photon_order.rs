//! The photon pass's shortcuts change nothing it stores: caustic photons
//! traced sorted by where they meet a specular shape (`photon/order.rs`),
//! and refused by a light-wide polar-angle window (`photon/polar.rs`,
//! whose own test is beside the other emission tests in
//! `photon_emission.rs`).

use crate::common::*;
use lumis_math::{Vec2, Vec3};
use lumis_render::integrator::photon::aim::Aims;
use lumis_render::integrator::photon::order::SORT_ABOVE_BYTES;
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
