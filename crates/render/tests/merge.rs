//! Parts merged one at a time (`session::Merger`), in any order, give the
//! whole render's film bit for bit; a loaded session pointed at another
//! job (`Session::set_job`) makes that job's parts.

use crate::common;

use common::render_session;
use lumis_render::session::{Budget, Merger, Part, RenderJob, Session};

fn job(seed: u64, passes: Option<std::ops::Range<u32>>) -> RenderJob {
    let mut job = RenderJob::new(None);
    job.overrides.resolution(12, 8).integrator("path");
    job.budget = Budget {
        spp: Some(6),
        time: None,
    };
    job.seed = seed;
    job.passes = passes;
    job
}

/// The part `s` renders, through its bytes.
fn part(s: &Session, name: &str) -> Part {
    Part::decode(&s.part(&render_session(s, None)).encode(), name).unwrap()
}

#[test]
fn parts_in_any_order_merge_to_the_whole_film() {
    let whole = Session::without_outputs(job(1, None)).unwrap();
    let expected = whole.scaled(&render_session(&whole, None).film);
    let mut m = Merger::default();
    for r in [3..6, 0..1, 1..3] {
        let s = Session::without_outputs(job(1, Some(r.clone()))).unwrap();
        m.add(&part(&s, &format!("{r:?}"))).unwrap();
    }
    assert_eq!(m.len(), 3);
    let (session, out) = m.finish(None).unwrap();
    assert_eq!(out.spp, 6);
    let got = session.scaled(&out.film);
    assert!(got
        .iter()
        .zip(&expected)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    // Another seed's film differs: the comparison can fail.
    let other = Session::without_outputs(job(2, None)).unwrap();
    assert_ne!(other.scaled(&render_session(&other, None).film), expected);
}

#[test]
fn a_gap_and_another_render_are_refused() {
    let a = part(&Session::without_outputs(job(1, Some(0..2))).unwrap(), "a");
    let c = part(&Session::without_outputs(job(1, Some(4..6))).unwrap(), "c");
    let mut m = Merger::default();
    m.add(&a).unwrap();
    m.add(&c).unwrap();
    let e = m.finish(None).err().expect("a gap").to_string();
    assert!(e.contains("passes 2..4 are missing"), "{e}");
    let b = part(&Session::without_outputs(job(2, Some(2..4))).unwrap(), "b");
    let mut m = Merger::default();
    m.add(&a).unwrap();
    let e = m.add(&b).expect_err("another seed").to_string();
    assert!(e.contains("a and b are parts of different renders"), "{e}");
}

#[test]
fn a_loaded_session_set_to_another_job_makes_that_jobs_parts() {
    let mut s = Session::without_outputs(job(0, None)).unwrap();
    let fresh = Session::without_outputs(job(3, Some(2..6))).unwrap();
    assert_ne!(s.hash, fresh.hash);
    s.set_job(job(3, Some(2..6))).unwrap();
    assert_eq!(s.hash, fresh.hash);
    assert_eq!(s.settings.passes, Some(2..6));
    let (a, b) = (part(&s, "a"), part(&fresh, "b"));
    assert_eq!(
        a.checkpoint.state.film.pixels,
        b.checkpoint.state.film.pixels
    );
    // A range the render does not have is refused.
    assert!(s.set_job(job(3, Some(4..9))).is_err());
}

#[test]
fn parts_merged_into_a_part_merge_like_any_part() {
    let whole = Session::without_outputs(job(1, None)).unwrap();
    let expected = whole.scaled(&render_session(&whole, None).film);
    let part_of = |r: std::ops::Range<u32>| {
        let s = Session::without_outputs(job(1, Some(r.clone()))).unwrap();
        part(&s, &format!("{r:?}"))
    };
    // 1..3 and 0..1 into 0..3, then with 3..6.
    let mut m = Merger::default();
    m.add(&part_of(1..3)).unwrap();
    m.add(&part_of(0..1)).unwrap();
    let left = m.finish_part().unwrap();
    assert_eq!(left.job.passes, Some(0..3));
    let left = Part::decode(&left.checkpoint.encode(), "left").unwrap();
    let mut m = Merger::default();
    m.add(&part_of(3..6)).unwrap();
    m.add(&left).unwrap();
    let (session, out) = m.finish(None).unwrap();
    let got = session.scaled(&out.film);
    assert!(got
        .iter()
        .zip(&expected)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    // A gap inside the range is refused.
    let mut m = Merger::default();
    m.add(&part_of(0..1)).unwrap();
    m.add(&part_of(2..4)).unwrap();
    let e = m.finish_part().expect_err("a gap").to_string();
    assert!(e.contains("passes 1..2 are missing"), "{e}");
}
