//! Ctrl-C and SIGTERM: the first stops the render after its current pass
//! (the image so far is written), the second exits at once.

use std::sync::atomic::{AtomicBool, Ordering};

/// Exit status of a render stopped by SIGINT/SIGTERM after writing its image (128 + SIGINT).
pub const EXIT_INTERRUPTED: u8 = 130;

/// Set by the first SIGINT/SIGTERM: no further passes start.
pub(crate) static CANCEL: AtomicBool = AtomicBool::new(false);

/// First Ctrl-C (or SIGTERM): finish the current pass, write the image, exit
/// with [`EXIT_INTERRUPTED`]. Second: exit at once.
pub(crate) fn install_interrupt_handler() {
    let _ = ctrlc::set_handler(|| {
        if CANCEL.swap(true, Ordering::SeqCst) {
            eprintln!("\nlumis: interrupted twice: exiting without writing");
            std::process::exit(EXIT_INTERRUPTED as i32);
        }
        eprintln!("\nlumis: interrupt: finishing this pass, then writing the image (Ctrl-C again to quit now)");
    });
}
