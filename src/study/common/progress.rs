//! Progress on stderr, when asked: a bar (indicatif) on a terminal; elsewhere (a pipe, CI, a
//! log under nohup) a plain line every few seconds or every 10 %, with an ETA, so a long run
//! is never silent.
//!
//! - [`RunProgress`]: the simulated time of one FE run, scaled to the stop rule's end (refined as the
//!   run learns it);
//! - [`Cases`]: the cases of a sweep or stress matrix, done and failed; also the member runs
//!   of the phase ensembles that `--tolerance` refines through ([`counting_members`]).
//!
//! A library caller (e.g. the Python binding) also receives the progress through a [`Hook`]
//! set with [`reporting`]: the bar or counter made on that thread calls it at each update.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// A plain line is printed at most this often when progress is steady...
pub const PLAIN_MIN_GAP: Duration = Duration::from_secs(2);
/// ...for every further 10 % done...
pub const PLAIN_STEP: f64 = 0.1;
/// ...and at least this often whatever the progress.
pub const PLAIN_HEARTBEAT: Duration = Duration::from_secs(10);

/// Whether a plain progress line is due: `frac` and `last_frac` are the fractions done now
/// and at the last line (0..1), `since` the wall time since the last line.
pub fn plain_line_due(frac: f64, last_frac: f64, since: Duration) -> bool {
    (frac - last_frac >= PLAIN_STEP && since >= PLAIN_MIN_GAP) || since >= PLAIN_HEARTBEAT
}

/// Estimated wall time left (s) after `elapsed` s for a fraction `frac` done (None before
/// any progress).
pub fn eta(elapsed: f64, frac: f64) -> Option<f64> {
    (frac > 1e-9 && frac.is_finite()).then(|| elapsed * (1.0 - frac.min(1.0)) / frac)
}

/// A duration for people: `850 ms`, `12.3 s`, `4.2 min`, `1.5 h`.
pub fn human(s: f64) -> String {
    if s < 1.0 {
        format!("{:.0} ms", 1e3 * s)
    } else if s < 100.0 {
        format!("{s:.1} s")
    } else if s < 6000.0 {
        format!("{:.1} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}

/// How progress is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Nothing (library callers, tests, a sweep's inner runs).
    Off,
    /// An indicatif bar (stderr is a terminal).
    Terminal,
    /// Plain lines (stderr is a pipe or a file).
    Plain,
}

impl Mode {
    /// `Off` unless `on`; then a bar when stderr is a terminal, plain lines otherwise.
    pub fn detect(on: bool) -> Mode {
        match (on, std::io::stderr().is_terminal()) {
            (false, _) => Mode::Off,
            (true, true) => Mode::Terminal,
            (true, false) => Mode::Plain,
        }
    }
}

fn plain(line: &str) {
    let mut err = std::io::stderr().lock();
    let _ = writeln!(err, "{line}");
    let _ = err.flush();
}

fn terminal_bar(len: u64, template: &str) -> ProgressBar {
    let style =
        ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar());
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    bar.set_style(style.progress_chars("#>."));
    bar
}

/// A receiver of progress: `(done, total)`, in simulated seconds for an FE run (time since
/// the run's start and its expected end), in cases for a sweep.
pub type Hook = std::sync::Arc<dyn Fn(f64, f64) + Send + Sync>;

thread_local! {
    static HOOK: std::cell::RefCell<Option<Hook>> = const { std::cell::RefCell::new(None) };
}

/// Runs `f` on this thread with `hook` (None: as is) receiving the progress of the bars and
/// case counters made during `f`; the previous hook is restored afterwards.
pub fn reporting<R>(hook: Option<&Hook>, f: impl FnOnce() -> R) -> R {
    crate::study::common::scoped::with_value(&HOOK, hook, f)
}

/// The progress receiver of this thread, if any (to hand on to worker threads).
pub fn current() -> Option<Hook> {
    crate::study::common::scoped::current(&HOOK)
}

/// Simulated-time units of the terminal bar: nanoseconds.
const BAR_UNITS_PER_S: f64 = 1e9;

/// Progress of one FE run through simulated time.
pub struct RunProgress {
    mode: Mode,
    bar: Option<ProgressBar>,
    /// Expected end of the run on the solver clock, s.
    end: f64,
    /// Start of the run on the solver clock, s.
    start: f64,
    t: f64,
    started: Instant,
    last_line: Instant,
    last_frac: f64,
    hook: Option<Hook>,
    /// What the plain lines name: the job (`run`) and what it simulates (`FE`).
    job: (&'static str, String),
}

impl RunProgress {
    /// Progress of a run from solver time `start` to its expected end `end` (s), shown as
    /// `mode` says.
    pub fn new(mode: Mode, start: f64, end: f64) -> Self {
        Self::worded(
            mode,
            ("run", "FE", " (stop rule's expected end)"),
            start,
            end,
        )
    }

    /// [`RunProgress::new`] for another simulation through time: plain lines begin `job:` and name
    /// `what` it simulates (e.g. `damper`, `7 cases`).
    pub fn for_job(mode: Mode, job: &'static str, what: &str, start: f64, end: f64) -> Self {
        Self::worded(mode, (job, what, ""), start, end)
    }

    /// The bar with its plain lines' words: job, what it simulates, what the end is based on.
    fn worded(mode: Mode, words: (&'static str, &str, &str), start: f64, end: f64) -> Self {
        let (job, what, basis) = words;
        let bar = (mode == Mode::Terminal).then(|| {
            terminal_bar(
                ((end - start).max(0.0) * BAR_UNITS_PER_S) as u64,
                "[{bar:40}] {percent:>3}% simulated, {elapsed} wall, ETA {eta}",
            )
        });
        let b = RunProgress {
            mode,
            bar,
            end,
            start,
            t: start,
            started: Instant::now(),
            last_line: Instant::now(),
            last_frac: 0.0,
            hook: current(),
            job: (job, what.to_string()),
        };
        if mode == Mode::Plain {
            plain(&format!(
                "{job}: {what} started, about {:.3e} s to simulate{basis}",
                end - start
            ));
        }
        b
    }

    /// The expected end of the run (solver clock, s) once the run knows it better.
    pub fn set_end(&mut self, end: f64) {
        if !(end.is_finite() && end > self.start) {
            return;
        }
        self.end = end;
        if let Some(b) = &self.bar {
            b.set_length(((end - self.start) * BAR_UNITS_PER_S) as u64);
        }
    }

    /// Fraction of the expected run done at solver time `t`.
    fn fraction(&self, t: f64) -> f64 {
        let span = self.end - self.start;
        if span > 0.0 {
            ((t - self.start) / span).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }

    /// Shows solver time `t` (s).
    pub fn update(&mut self, t: f64) {
        self.t = t;
        if t > self.end {
            // Past the estimate: the end is at least here.
            self.set_end(t);
        }
        if let Some(h) = &self.hook {
            h(t - self.start, self.end - self.start);
        }
        match self.mode {
            Mode::Off => {}
            Mode::Terminal => {
                if let Some(b) = &self.bar {
                    b.set_position(((t - self.start).max(0.0) * BAR_UNITS_PER_S) as u64);
                }
            }
            Mode::Plain => {
                let frac = self.fraction(t);
                if plain_line_due(frac, self.last_frac, self.last_line.elapsed()) {
                    let wall = self.started.elapsed().as_secs_f64();
                    plain(&format!(
                        "{}: t = {:.3e} of ~{:.3e} s simulated ({:.0} %), {} wall, ETA {}",
                        self.job.0,
                        t - self.start,
                        self.end - self.start,
                        100.0 * frac,
                        human(wall),
                        eta(wall, frac).map_or("-".into(), human)
                    ));
                    self.last_line = Instant::now();
                    self.last_frac = frac;
                }
            }
        }
    }

    /// Simulated time reached so far since the start, s.
    pub fn simulated(&self) -> f64 {
        self.t - self.start
    }

    /// Ends the display: clears the bar, or prints the final plain line.
    pub fn finish(&mut self) {
        if let Some(b) = self.bar.take() {
            b.finish_and_clear();
        }
        if self.mode == Mode::Plain {
            plain(&format!(
                "{}: {} done, {:.3e} s simulated in {} wall",
                self.job.0,
                self.job.1,
                self.t - self.start,
                human(self.started.elapsed().as_secs_f64())
            ));
            self.mode = Mode::Off;
        }
    }
}

impl Drop for RunProgress {
    fn drop(&mut self) {
        if let Some(b) = self.bar.take() {
            b.finish_and_clear();
        }
    }
}

struct PlainState {
    done: usize,
    failed: usize,
    last_line: Instant,
    last_frac: f64,
}

/// Progress over the cases of a sweep or stress matrix (safe to share between workers).
pub struct Cases {
    mode: Mode,
    label: String,
    total: AtomicUsize,
    bar: Option<ProgressBar>,
    started: Instant,
    state: Mutex<PlainState>,
    hook: Option<Hook>,
}

impl Cases {
    /// Progress of `total` cases of the job `label` (e.g. `sweep`), shown as `mode` says.
    pub fn new(mode: Mode, label: &str, total: usize) -> Self {
        let bar = (mode == Mode::Terminal).then(|| {
            terminal_bar(
                total as u64,
                "[{bar:40}] {pos}/{len} cases, {elapsed} wall, ETA {eta}",
            )
        });
        if mode == Mode::Plain {
            plain(&format!("{label}: {total} cases to run"));
        }
        Cases {
            mode,
            label: label.into(),
            total: AtomicUsize::new(total),
            bar,
            started: Instant::now(),
            state: Mutex::new(PlainState {
                done: 0,
                failed: 0,
                last_line: Instant::now(),
                last_frac: 0.0,
            }),
            hook: current(),
        }
    }

    fn line(&self, s: &PlainState) -> String {
        let wall = self.started.elapsed().as_secs_f64();
        let total = self.total();
        let frac = if total > 0 {
            s.done as f64 / total as f64
        } else {
            1.0
        };
        format!(
            "{}: {}/{} cases done ({} failed), {} wall, ETA {}",
            self.label,
            s.done,
            total,
            s.failed,
            human(wall),
            eta(wall, frac).map_or("-".into(), human)
        )
    }

    /// One case finished (`failed` if it failed); `detail` is its one-line description,
    /// shown above the bar on a terminal.
    pub fn case_done(&self, failed: bool, detail: &str) {
        let mut s = self.state.lock().unwrap_or_else(|p| p.into_inner());
        s.done += 1;
        s.failed += usize::from(failed);
        if let Some(h) = &self.hook {
            h(s.done as f64, self.total() as f64);
        }
        match self.mode {
            Mode::Off => {}
            Mode::Terminal => {
                if let Some(b) = &self.bar {
                    b.println(detail);
                    b.inc(1);
                }
            }
            Mode::Plain => {
                let frac = s.done as f64 / self.total().max(1) as f64;
                if plain_line_due(frac, s.last_frac, s.last_line.elapsed()) {
                    plain(&self.line(&s));
                    s.last_line = Instant::now();
                    s.last_frac = frac;
                }
            }
        }
    }

    /// The same counter without the thread's progress receiver: for counts that are not the
    /// receiver's unit (the member runs inside one FE run's progress).
    pub fn without_hook(mut self) -> Self {
        self.hook = None;
        self
    }

    /// Cases expected in all.
    pub fn total(&self) -> usize {
        self.total.load(Ordering::Relaxed)
    }

    /// `n` more cases are expected (a refinement the start could not foresee).
    pub fn add_total(&self, n: usize) {
        let total = self.total.fetch_add(n, Ordering::Relaxed) + n;
        if let Some(b) = &self.bar {
            b.set_length(total as u64);
        }
    }

    /// Cases done and failed so far.
    pub fn counts(&self) -> (usize, usize) {
        let s = self.state.lock().unwrap_or_else(|p| p.into_inner());
        (s.done, s.failed)
    }

    /// Ends the display: clears the bar, or prints the final plain line.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
        if self.mode == Mode::Plain {
            let s = self.state.lock().unwrap_or_else(|p| p.into_inner());
            plain(&self.line(&s));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_lines_every_ten_percent_at_most_every_two_seconds_and_a_heartbeat() {
        let s = Duration::from_secs;
        assert!(!plain_line_due(0.05, 0.0, s(3)));
        assert!(!plain_line_due(0.5, 0.0, Duration::from_millis(500)));
        assert!(plain_line_due(0.1, 0.0, s(2)));
        assert!(plain_line_due(0.01, 0.0, s(10)));
    }

    #[test]
    fn eta_scales_the_elapsed_time_by_what_is_left() {
        assert_eq!(eta(10.0, 0.25), Some(30.0));
        assert_eq!(eta(10.0, 1.0), Some(0.0));
        assert_eq!(eta(10.0, 0.0), None);
        assert_eq!(human(0.25), "250 ms");
        assert_eq!(human(12.34), "12.3 s");
        assert_eq!(human(600.0), "10.0 min");
    }
}

thread_local! {
    static MEMBERS: std::cell::RefCell<Option<Arc<Cases>>> = const { std::cell::RefCell::new(None) };
}

/// Runs `f` with `cases` counting the phase-ensemble member runs that `f` starts on this
/// thread (None: as is): the progress of a `--tolerance` refinement.
pub fn counting_members<R>(cases: Option<&Arc<Cases>>, f: impl FnOnce() -> R) -> R {
    crate::study::common::scoped::with_value(&MEMBERS, cases, f)
}

/// The member counter of this thread, if any (to hand on to worker threads).
pub fn members() -> Option<Arc<Cases>> {
    crate::study::common::scoped::current(&MEMBERS)
}
