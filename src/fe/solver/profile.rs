//! A cheap phase timer for the explicit loop: where the wall time of a run goes.
//!
//! The solver calls [`Profile::lap`] at each phase boundary of a step; a lap charges the time
//! since the previous lap to the named phase. Time spent between two steps (the caller's
//! history output and stop checks) is charged to [`StepPhase::Outside`] by the lap at the start of
//! the next step. Off by default: then a lap is one predictable branch, no clock read.
//! Switched on per solver by its settings (`Settings::profile`); the totals belong to the
//! solver ([`Profile::totals`]), and a study that builds its solvers internally hands them
//! back with its results.

use std::time::Instant;

/// The phases of an explicit step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepPhase {
    /// Element loop: gather, strain, objective rotation, plasticity, hourglass, force blocks.
    Elements,
    /// Assembly of the element force blocks into nodal internal forces.
    Gather,
    /// Stable time step: element minimum, interactions' limits, step selection.
    StableStep,
    /// Interactions (contact search and contact forces, walls).
    Contact,
    /// Node loops: velocity and position updates, boundary conditions, accelerations, power.
    Nodal,
    /// Energy-balance checks inside the solver.
    Energy,
    /// Between steps, outside the solver: history output, probes, stop checks of the caller.
    Outside,
}

impl StepPhase {
    /// Every phase, in table order.
    pub const ALL: [StepPhase; 7] = [
        StepPhase::Elements,
        StepPhase::Gather,
        StepPhase::StableStep,
        StepPhase::Contact,
        StepPhase::Nodal,
        StepPhase::Energy,
        StepPhase::Outside,
    ];

    /// Row label.
    pub fn name(self) -> &'static str {
        match self {
            StepPhase::Elements => "element forces (strain, plasticity, hourglass)",
            StepPhase::Gather => "node gather of element forces",
            StepPhase::StableStep => "stable time step",
            StepPhase::Contact => "contact (search + forces)",
            StepPhase::Nodal => "nodal updates (v, x, a, BCs, power)",
            StepPhase::Energy => "energy checks",
            StepPhase::Outside => "output/history/stop checks (caller)",
        }
    }
}

/// Accumulated seconds per phase, indexed like [`StepPhase::ALL`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Totals {
    /// Seconds per phase.
    pub seconds: [f64; 7],
    /// Steps timed.
    pub steps: u64,
    /// Element updates timed (elements × steps).
    pub element_cycles: u64,
}

impl Totals {
    /// Seconds of all phases together.
    pub fn sum(&self) -> f64 {
        self.seconds.iter().sum()
    }

    /// Seconds charged to one phase.
    pub fn get(&self, p: StepPhase) -> f64 {
        self.seconds[p as usize]
    }

    /// A text table: phase, seconds, share, ns per element-cycle.
    pub fn table(&self) -> String {
        let total = self.sum();
        let per = |s: f64| {
            if self.element_cycles > 0 {
                s * 1e9 / self.element_cycles as f64
            } else {
                0.0
            }
        };
        let mut out = format!(
            "{:<48} {:>9} {:>7} {:>10}\n",
            "phase", "time [s]", "share", "ns/el-cyc"
        );
        for p in StepPhase::ALL {
            let s = self.get(p);
            let share = if total > 0.0 { 100.0 * s / total } else { 0.0 };
            out += &format!(
                "{:<48} {:>9.3} {:>6.1}% {:>10.1}\n",
                p.name(),
                s,
                share,
                per(s)
            );
        }
        out += &format!(
            "{:<48} {:>9.3} {:>6.1}% {:>10.1}\n",
            "total (timed steps)",
            total,
            100.0,
            per(total)
        );
        out
    }
}

/// One solver's phase timer.
#[derive(Debug)]
pub struct Profile {
    last: Option<Instant>,
    totals: Totals,
    elements: u64,
}

impl Profile {
    /// A timer for a model of `elements` elements, timing if `on`.
    pub fn new(elements: usize, on: bool) -> Self {
        Profile {
            last: on.then(Instant::now),
            totals: Totals::default(),
            elements: elements as u64,
        }
    }

    /// Charges the time since the previous lap to `phase` (nothing when off).
    #[inline]
    pub fn lap(&mut self, phase: StepPhase) {
        if let Some(t0) = self.last {
            let now = Instant::now();
            self.totals.seconds[phase as usize] += (now - t0).as_secs_f64();
            self.last = Some(now);
        }
    }

    /// Counts one finished step; `updates` is the solver's running count of element updates
    /// (with subcycling fewer than elements × steps), `None` for elements × steps.
    #[inline]
    pub fn end_step(&mut self, updates: Option<u64>) {
        if self.last.is_some() {
            self.totals.steps += 1;
            self.totals.element_cycles = match updates {
                Some(u) => u,
                None => self.totals.element_cycles + self.elements,
            };
        }
    }

    /// This solver's totals so far.
    pub fn totals(&self) -> Totals {
        self.totals
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn laps_charge_the_named_phase_and_off_costs_nothing() {
        let mut off = Profile {
            last: None,
            totals: Totals::default(),
            elements: 10,
        };
        off.lap(StepPhase::Elements);
        off.end_step(None);
        assert_eq!(off.totals(), Totals::default());

        let mut on = Profile {
            last: Some(Instant::now()),
            totals: Totals::default(),
            elements: 10,
        };
        std::thread::sleep(std::time::Duration::from_millis(20));
        on.lap(StepPhase::Contact);
        on.lap(StepPhase::Gather);
        on.end_step(None);
        let t = on.totals();
        assert!(t.get(StepPhase::Contact) >= 0.02, "{t:?}");
        assert!(t.get(StepPhase::Gather) < t.get(StepPhase::Contact));
        assert_eq!((t.steps, t.element_cycles), (1, 10));
        assert!(t.table().contains("contact (search + forces)"));
    }
}
