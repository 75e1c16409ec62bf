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

#[cfg(test)]
mod tests {
    use super::job_for;
    use lumis_render::session::job_from_flags;

    /// A run's flags make one job whether clap parses them (here) or the
    /// library's parser does (study runs from Python).
    #[test]
    fn clap_and_the_librarys_parser_make_one_job() {
        let sets: &[&[&str]] = &[
            &[
                "--integrator",
                "path",
                "--maxdepth",
                "3",
                "--sampler",
                "independent",
            ],
            &[
                "--integrator",
                "photon",
                "--photons",
                "20000",
                "--caustic-photons",
                "30000",
                "--caustics",
                "mis",
                "--crop",
                "0.25,0.75,0,1",
                "--clamp",
                "4",
            ],
            &[
                "--integrator=photon",
                "--progressive",
                "false",
                "--radiance-photons",
                "--seed",
                "3",
            ],
            &[
                "--integrator",
                "bdpt",
                "--strategy",
                "2,3",
                "--maxdepth",
                "4",
                "--mis",
                "false",
            ],
            &[
                "s.pbrt",
                "--resolution",
                "24x16",
                "--spp",
                "2",
                "--time",
                "1.5",
                "--threads",
                "1",
                "-o",
                "a.pfm",
                "--exposure",
                "-1.5",
                "--accel",
                "bvh",
                "--stats",
            ],
        ];
        for set in sets {
            let args: Vec<String> = set.iter().map(|s| s.to_string()).collect();
            assert_eq!(job_for(&args), job_from_flags(&args), "{set:?}");
        }
    }
}
