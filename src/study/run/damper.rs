//! The damper cases of a command, run with progress through their simulated time (a bar on a
//! terminal, plain lines elsewhere: [`crate::study::common::progress`]) and stopped by Ctrl-C or
//! the caller's cancel request ([`crate::study::common::interrupt`]) at the next report of a running case.

use crate::analytic::laws::Registry;
use crate::damper::file::DamperCase;
use crate::damper::run::{run_cases_observed, CaseOutcome};
use crate::error::{Error, Result};
use crate::study::common::interrupt;
use crate::study::common::progress::{Mode, RunProgress};
use std::sync::Mutex;

/// Runs `cases` in parallel ([`run_cases_observed`]), showing progress as `mode` says over
/// the sum of their durations.
///
/// Errors: those of the cases; [`Error::Interrupted`] naming the case and time reached, when
/// Ctrl-C is pressed or the caller's [`interrupt::CancelToken`] is cancelled.
pub fn run_cases_with_progress(
    cases: &[DamperCase],
    registry: &Registry,
    mode: Mode,
) -> Result<Vec<CaseOutcome>> {
    let total: f64 = cases.iter().map(|c| c.scene.duration).sum();
    let what = format!(
        "{} case{}",
        cases.len(),
        if cases.len() == 1 { "" } else { "s" }
    );
    let shown = Mutex::new((
        RunProgress::for_job(mode, "damper", &what, 0.0, total),
        vec![0.0; cases.len()],
    ));
    // Workers of the pool see the caller's cancel request through this token.
    let token = interrupt::current();
    let at = |k: usize, t: f64| -> Result<()> {
        if interrupt::requested() || token.as_ref().is_some_and(|c| c.is_cancelled()) {
            return Err(Error::Interrupted(format!(
                "in case {} at t = {t:.2} s of {} s",
                cases[k].name, cases[k].scene.duration
            )));
        }
        let mut s = shown.lock().unwrap_or_else(|p| p.into_inner());
        s.1[k] = t;
        let done = s.1.iter().sum();
        s.0.update(done);
        Ok(())
    };
    let outcomes = run_cases_observed(cases, registry, &at);
    let mut s = shown.into_inner().unwrap_or_else(|p| p.into_inner());
    match outcomes {
        Ok(o) => {
            s.0.update(total);
            s.0.finish();
            Ok(o)
        }
        Err(Error::Interrupted(at)) => Err(Error::Interrupted(format!("{at}; nothing written"))),
        Err(e) => Err(e),
    }
}
