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

/// Whether Ctrl-C has been pressed since the process started, or the job this thread works
/// for was cancelled ([`within`] a [`CancelToken`]).
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed) || token_cancelled()
}

/// A request to stop one job (a run or a sweep started by a library caller, e.g. the Python
/// binding): [`requested`] is true on a thread working [`within`] a cancelled token, as it is
/// everywhere after Ctrl-C.
#[derive(Debug, Clone, Default)]
pub struct CancelToken(std::sync::Arc<AtomicBool>);

impl CancelToken {
    /// A token not cancelled yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks the jobs working within this token to stop at their next check.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::SeqCst);
    }

    /// Whether [`CancelToken::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

thread_local! {
    static TOKEN: std::cell::RefCell<Option<CancelToken>> = const { std::cell::RefCell::new(None) };
}

/// Runs `f` on this thread with `token` (None: as is) as the job's cancel request; the
/// previous token is restored afterwards.
pub fn within<R>(token: Option<&CancelToken>, f: impl FnOnce() -> R) -> R {
    crate::study::common::scoped::with_value(&TOKEN, token, f)
}

/// The cancel token this thread works within, if any (to hand on to worker threads).
pub fn current() -> Option<CancelToken> {
    crate::study::common::scoped::current(&TOKEN)
}

fn token_cancelled() -> bool {
    TOKEN.with(|t| t.borrow().as_ref().is_some_and(CancelToken::is_cancelled))
}
