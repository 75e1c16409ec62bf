//! The `lumis` binary: thin glue from arguments to a rendered image.

#[macro_use]
mod out;

mod args;
mod bench;
mod bench_rays;
mod bench_scaling;
mod display;
mod interrupt;
mod job;
mod measure;
mod progress;
mod resume;
mod run;
mod stats;
mod study;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = args::Cli::parse();
    match run::run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(1)
        }
    }
}
