//! Partial renders merged: the parts of a render, split anywhere (uneven
//! ranges, a progressive `photon` iteration cut in two), rendered on
//! different thread counts and merged in any order through the part file
//! format, give the film and image of the whole render bit for bit, for
//! every integrator. Parts that do not make one render are refused.

// A split into one range is one of the splits tested, not a mistaken `Vec`.
#![allow(clippy::single_range_in_vec_init)]

use crate::common;
use lumis_render::film::Film;

use lumis_render::integrator::RenderOutcome;
use lumis_render::session::{merge, Part, RenderJob, Session};
use std::ops::Range;

/// The default scene, small, with `integrator` and its parameters.
fn job(integrator: &str, spp: u32, params: &[(&str, &str)]) -> RenderJob {
    let mut j = RenderJob::new(None);
    j.overrides
        .resolution_from(20, 14, "test")
        .integrator_from(integrator, "test");
    for (name, value) in params {
        j.overrides.param("Integrator", name, value, "test");
    }
    j.seed = 5;
    j.budget.spp = Some(spp);
    j
}

/// Renders `job`, stopping after `stop` passes if given.
fn render(job: RenderJob, stop: Option<u32>) -> (Session, RenderOutcome) {
    let s = Session::without_outputs(job).expect("the job loads");
    let out = common::render_session(&s, stop);
    (s, out)
}

/// The part file's bytes for passes `r` of `base`, rendered on `threads`.
fn part(base: &RenderJob, r: Range<u32>, threads: usize) -> Part {
    let mut j = base.clone();
    j.passes = Some(r.clone());
    j.threads = threads;
    let (s, out) = render(j, None);
    assert!(!out.interrupted);
    let bytes = s.part(&out).encode();
    Part::decode(&bytes, &format!("part {}..{}", r.start, r.end)).expect("a part decodes")
}

fn assert_same_film(a: &Film, b: &Film, what: &str) {
    for (i, (p, q)) in a.pixels.iter().zip(&b.pixels).enumerate() {
        assert_eq!(p, q, "{what}: pixel {i}");
    }
    assert_eq!(a.pixels.len(), b.pixels.len());
    assert_eq!(a.splats, b.splats, "{what}: splats");
    assert_eq!(a.splat_samples, b.splat_samples, "{what}: splat samples");
    assert_eq!(a.weights, b.weights, "{what}: weights");
}

/// Each split of `base`'s passes, merged (in reverse order), equals the whole.
fn merges_to_whole(base: RenderJob, splits: &[&[Range<u32>]]) {
    let (ws, whole) = render(base.clone(), None);
    let whole_img = ws.image(&whole, None);
    for (k, split) in splits.iter().enumerate() {
        let mut parts: Vec<Part> = split
            .iter()
            .enumerate()
            .map(|(i, r)| part(&base, r.clone(), 1 + (i + k) % 2))
            .collect();
        parts.reverse();
        let what = format!("split {split:?}");
        let (ms, merged) = merge(&parts, None).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(merged.spp, whole.spp, "{what}");
        assert_same_film(&merged.film, &whole.film, &what);
        let img = ms.image(&merged, None);
        let bits = |d: &[f32]| d.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&img.data), bits(&whole_img.data), "{what}: image");
        // A part alone is not the whole (the comparison can fail).
        if split.len() > 1 {
            let one = &parts[0].checkpoint.state.film;
            assert!(one
                .pixels
                .iter()
                .zip(&whole.film.pixels)
                .any(|(p, q)| p != q));
        }
    }
}

const PHOTONS: [(&str, &str); 3] = [
    ("integer photons", "20000"),
    ("integer causticphotons", "20000"),
    ("integer gatherrays", "4"),
];

/// With a splatting filter the film holds weights too; they travel in
/// part files and merge like the sums.
#[test]
fn splatted_parts_merge_to_the_whole_render() {
    let mut j = job("path", 6, &[]);
    j.overrides.filter_splat(true);
    merges_to_whole(j, &[&[0..1, 1..6], &[0..3, 3..4, 4..6]]);
}

#[test]
fn path_parts_merge_to_the_whole_render() {
    merges_to_whole(
        job("path", 8, &[]),
        &[
            &[0..1, 1..5, 5..8],
            &[0..4, 4..8],
            &[0..8],
            &[0..2, 2..3, 3..7, 7..8],
        ],
    );
}

/// Two samples per iteration: the split 0..3, 3..4 starts a part inside
/// iteration 1, which it traces again from its seed.
#[test]
fn progressive_photon_parts_merge_to_the_whole_render() {
    let mut params = PHOTONS.to_vec();
    params.push(("integer iterationspp", "2"));
    merges_to_whole(
        job("photon", 8, &params),
        &[
            &[0..3, 3..4, 4..8],
            &[0..2, 2..8],
            &[0..1, 1..2, 2..3, 3..8],
        ],
    );
}

#[test]
fn single_map_photon_parts_merge_to_the_whole_render() {
    let mut params = PHOTONS.to_vec();
    params.push(("bool progressive", "false"));
    merges_to_whole(job("photon", 4, &params), &[&[0..1, 1..4]]);
}

#[test]
fn splatting_integrators_parts_merge_to_the_whole_render() {
    for name in ["lighttracer", "bdpt", "vcm"] {
        merges_to_whole(job(name, 5, &[]), &[&[0..2, 2..3, 3..5]]);
    }
    merges_to_whole(job("direct", 3, &[]), &[&[0..1, 1..3]]);
}

fn merge_error(parts: &[Part]) -> String {
    match merge(parts, None) {
        Ok(_) => panic!("merged parts that are not one render"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn parts_that_are_not_one_render_are_refused() {
    let base = job("path", 6, &[]);
    let (a, b, c) = (
        part(&base, 0..2, 2),
        part(&base, 2..4, 2),
        part(&base, 4..6, 2),
    );
    let e = merge_error(&[a.clone(), c.clone()]);
    assert!(e.contains("passes 2..4 are missing"), "{e}");
    let e = merge_error(&[a.clone(), b.clone()]);
    assert!(e.contains("passes 4..6 are missing"), "{e}");
    let e = merge_error(&[a.clone(), b.clone(), c.clone(), part(&base, 3..5, 1)]);
    assert!(e.contains("overlaps"), "{e}");
    let mut other = base.clone();
    other.seed = 6;
    let e = merge_error(&[a.clone(), b.clone(), part(&other, 4..6, 2)]);
    assert!(e.contains("different renders"), "{e}");
    let mut other = base.clone();
    other.budget.spp = Some(7);
    let e = merge_error(&[a.clone(), b.clone(), part(&other, 4..6, 2)]);
    assert!(e.contains("different renders"), "{e}");
    // An interrupted part is unfinished.
    let mut j = base.clone();
    j.passes = Some(4..6);
    let (s, out) = render(j, Some(1));
    assert!(out.interrupted);
    let cut = Part::decode(&s.part(&out).encode(), "cut").unwrap();
    let e = merge_error(&[a, b, cut]);
    assert!(
        e.contains("cut is unfinished") && e.contains("5 of 6"),
        "{e}"
    );
    assert!(merge_error(&[]).contains("nothing to merge"));
    // A damaged part file is refused by its checksum.
    let mut bytes = s.part(&out).encode();
    let n = bytes.len();
    bytes[n / 2] ^= 1;
    assert!(Part::decode(&bytes, "bad").is_err());
}

#[test]
fn pass_ranges_the_render_does_not_have_are_refused() {
    let err = |j: RenderJob| match Session::without_outputs(j) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    let mut j = job("path", 4, &[]);
    j.passes = Some(2..5);
    assert!(err(j.clone()).contains("not inside this render's passes 0..4"));
    j.passes = Some(2..2);
    assert!(err(j.clone()).contains("empty"));
    j.passes = Some(0..2);
    j.budget.time = Some(3.0);
    assert!(err(j.clone()).contains("time budget"));
    j.budget.spp = None;
    assert!(err(j).contains("needs a sample count"));
}
