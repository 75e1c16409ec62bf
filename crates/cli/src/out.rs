//! Printing to stdout for the commands that report there (`compare`,
//! `bench`): a reader that stops early (`lumis compare a b | head -3`) ends
//! the program quietly with success, as other command-line tools do,
//! instead of the panic of `println!`.

use std::io::Write;

/// `println!` to stdout; a closed stdout ends the program quietly.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::out::line(format_args!($($arg)*))
    };
}

/// Writes one line; on a broken pipe exits with status 0, on another
/// error says so and exits with status 1.
pub fn line(args: std::fmt::Arguments) {
    let mut out = std::io::stdout().lock();
    let written = out
        .write_fmt(args)
        .and_then(|()| out.write_all(b"\n"))
        .and_then(|()| out.flush());
    match written {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => std::process::exit(0),
        Err(e) => {
            eprintln!("lumis: cannot write to stdout: {e}");
            std::process::exit(1)
        }
    }
}
