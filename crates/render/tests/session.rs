//! The library session: a job rendered end to end, its outputs checked
//! before rendering, and an image saved elsewhere (and said where) when its
//! output folder vanished during the render.

use crate::common;

use common::render_session;
use lumis_render::session::{Budget, RenderJob, Session};

fn tiny_job(dir: &std::path::Path) -> RenderJob {
    let mut job = RenderJob::new(None);
    job.dir = dir.to_path_buf();
    job.overrides.resolution(12, 8).integrator("path");
    job.budget = Budget {
        spp: Some(2),
        time: None,
    };
    job
}

#[test]
fn a_job_renders_and_records_how_it_was_made() {
    let dir = std::env::temp_dir().join(format!("lumis-session-{}-a", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut job = tiny_job(&dir);
    job.outputs = vec!["t.pfm".into()];
    let s = Session::new(RenderJob::from_json(&job.to_json()).unwrap()).unwrap();
    assert_eq!(s.outputs, vec![dir.join("t.pfm")]);
    let out = render_session(&s, None);
    assert_eq!(out.spp, 2);
    let img = s.image(&out, None);
    assert_eq!(img.meta("lumis:integrator"), Some("path"));
    assert_eq!(s.write(&img).unwrap(), vec![dir.join("t.pfm")]);
    assert!(dir.join("t.pfm").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn outputs_are_checked_first_and_rescued_when_their_folder_vanishes() {
    let dir = std::env::temp_dir().join(format!("lumis-session-{}-b", std::process::id()));
    let gone = dir.join("gone");
    std::fs::create_dir_all(&gone).unwrap();
    let mut job = tiny_job(&dir);
    job.outputs = vec!["missing/x.exr".into()];
    let e = Session::new(job.clone())
        .err()
        .expect("refused")
        .to_string();
    assert!(e.contains("does not exist"), "{e}");
    job.outputs = vec!["gone/x.exr".into()];
    let s = Session::new(job).unwrap();
    let out = render_session(&s, None);
    std::fs::remove_dir(&gone).unwrap();
    let e = s.write(&s.image(&out, None)).unwrap_err().to_string();
    let rescue = dir.join("x.exr");
    assert!(e.contains(&format!("saved to {}", rescue.display())), "{e}");
    assert!(rescue.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
