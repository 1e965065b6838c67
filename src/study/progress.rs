//! A one-line progress bar on stderr, drawn only when asked (the CLI asks when stderr is a
//! terminal, so pipes and logs stay quiet).

use std::io::Write;
use std::time::{Duration, Instant};

/// Progress of a simulated time interval.
pub struct Bar {
    on: bool,
    end: f64,
    last: Option<Instant>,
    started: Instant,
}

impl Bar {
    /// A bar for simulated times 0..`end` (s); draws nothing unless `on`.
    pub fn new(on: bool, end: f64) -> Self {
        Bar {
            on,
            end,
            last: None,
            started: Instant::now(),
        }
    }

    /// Shows simulated time `t` (s); redraws at most ten times a second.
    pub fn update(&mut self, t: f64) {
        if !self.on
            || self
                .last
                .is_some_and(|l| l.elapsed() < Duration::from_millis(100))
        {
            return;
        }
        self.last = Some(Instant::now());
        let frac = if self.end > 0.0 {
            (t / self.end).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let width = 40;
        let filled = (frac * width as f64).round() as usize;
        let mut err = std::io::stderr().lock();
        let _ = write!(
            err,
            "\r[{}{}] t = {:.3e} s  {:.1} s wall ",
            "#".repeat(filled),
            ".".repeat(width - filled),
            t,
            self.started.elapsed().as_secs_f64()
        );
        let _ = err.flush();
    }

    /// Clears the bar's line.
    pub fn finish(&mut self) {
        if self.on && self.last.is_some() {
            let _ = write!(std::io::stderr().lock(), "\r{}\r", " ".repeat(72));
        }
    }
}
