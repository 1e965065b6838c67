//! Ctrl-C (SIGINT): the first one asks the running job to stop at its next check (a time
//! step of an FE run, the end of a sweep case), so the command can say what was and was not
//! written and exit with 130; a second one ends the process at once with 130.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Exit code of a command ended by Ctrl-C (128 + SIGINT, as shells report it).
pub const EXIT_CODE: i32 = 130;

/// Installs the SIGINT handler (once per process; later calls do nothing).
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        if REQUESTED.swap(true, Ordering::SeqCst) {
            eprintln!("interrupted again: stopping at once");
            std::process::exit(EXIT_CODE);
        }
    });
}

/// Whether Ctrl-C has been pressed since the process started.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}
