//! The `twoball` command: parses arguments and hands over to [`twoball::cli`].

fn main() {
    restore_default_sigpipe();
    std::process::exit(twoball::cli::main());
}

/// Lets a closed reader end the process quietly, as it ends any Unix filter: Rust ignores
/// SIGPIPE, so `twoball materials | head -1` would otherwise panic in `println!` when `head`
/// exits. Nothing is lost by dying there: result files are written to a temporary name and
/// renamed when complete, and sweeps resume from their finished cases.
fn restore_default_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called first thing in main, before any thread exists; SIG_DFL is a valid
    // disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}
