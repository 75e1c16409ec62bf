//! Progress display: a bar on a terminal, plain periodic lines otherwise.

use indicatif::{ProgressBar, ProgressStyle};
use lumis_render::integrator::Progress;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

pub struct Reporter {
    bar: Option<ProgressBar>,
    last_line: Mutex<Option<Instant>>,
    quiet: bool,
}

impl Reporter {
    pub fn new(quiet: bool) -> Reporter {
        let bar = if !quiet && std::io::stderr().is_terminal() {
            let b = ProgressBar::new(1000);
            b.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {wide_bar} {percent}% {msg} (eta {eta})",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            Some(b)
        } else {
            None
        };
        Reporter {
            bar,
            last_line: Mutex::new(None),
            quiet,
        }
    }

    pub fn update(&self, p: &Progress) {
        if self.quiet {
            return;
        }
        if let Some(b) = &self.bar {
            b.set_position((p.fraction * 1000.0) as u64);
            b.set_message(format!("{} spp", p.spp_done));
            return;
        }
        let mut last = self.last_line.lock().unwrap();
        let due = last
            .map(|t| t.elapsed() >= Duration::from_secs(5))
            .unwrap_or(true);
        if due || p.fraction >= 1.0 {
            eprintln!(
                "progress: {:5.1}%  {} spp  {:.1} s",
                p.fraction * 100.0,
                p.spp_done,
                p.elapsed.as_secs_f64()
            );
            *last = Some(Instant::now());
        }
    }

    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}
