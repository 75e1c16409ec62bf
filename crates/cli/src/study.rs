//! `lumis study CONFIG.toml`: loads the study, says how a run's flags
//! become a job (the same mapping as `lumis render`), runs it in the
//! library and prints where the report is.

use crate::args::{Cli, Command, StudyArgs};
use crate::interrupt::{install_interrupt_handler, CANCEL, EXIT_INTERRUPTED};
use anyhow::Result;
use clap::Parser;
use lumis_render::session::RenderJob;
use lumis_render::study::{self, Config, StudyRun};
use std::process::ExitCode;

/// A run's flags, parsed as `lumis render` parses them, as a job.
fn job_for(args: &[String]) -> Result<RenderJob, String> {
    let argv = ["lumis", "render", "-q"]
        .into_iter()
        .map(String::from)
        .chain(args.iter().cloned());
    let cli = Cli::try_parse_from(argv).map_err(|e| format!("bad flags: {e}"))?;
    let Some(Command::Render(ra)) = cli.command else {
        unreachable!("parsed as render")
    };
    crate::job::job_from_args(&ra).map_err(|e| e.to_string())
}

pub fn run(a: StudyArgs) -> Result<ExitCode> {
    let c = Config::load(&a.config)?;
    install_interrupt_handler();
    let quiet = a.quiet;
    let log = |m: &str| {
        if !quiet || !m.ends_with("skipped") {
            eprintln!("{m}");
        }
    };
    let s = study::run(
        &c,
        &StudyRun {
            out: a
                .out
                .clone()
                .unwrap_or_else(|| study::default_out(&a.config)),
            command: std::env::args().collect::<Vec<_>>().join(" "),
            job_for: &job_for,
            cancel: &CANCEL,
            log: &log,
        },
    )?;
    eprintln!(
        "lumis: study: {} of {} runs finished -> {}",
        s.finished,
        s.planned,
        s.report.display()
    );
    if s.interrupted {
        eprintln!("lumis: interrupted: finished runs are kept; rerun the same command to resume");
        return Ok(ExitCode::from(EXIT_INTERRUPTED));
    }
    Ok(ExitCode::SUCCESS)
}
