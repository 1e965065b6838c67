//! What one FE run returns and takes: the [`Simulation`] record (outcome, savings, cost,
//! history), the [`RunOptions`], the automatic [`Savings`] and the pair's kinematics at touch.

use crate::error::Error;
use crate::fe::profile::Totals;
use crate::study::records::outcome::Outcome;
use crate::study::run::history::HistoryRow;
use crate::study::run::reduction::Reduction;
use crate::study::run::smoothed_force::ForceSummary;
use serde::Serialize;

/// Contact-frame state of the pair in its centre-of-mass frame.
pub(super) struct CentreOfMassFrame {
    /// Centre-of-mass velocity of the pair (contact frame), m/s.
    pub v_cm: [f64; 3],
    /// Ball velocities relative to v_cm (contact frame), m/s.
    pub u: [[f64; 3]; 2],
}

/// What the automatic savings decided (issue 6 item 3), for results.json.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Savings {
    /// Symmetry reduction used.
    pub reduction: Reduction,
    /// Why.
    pub reduction_reason: String,
    /// Free flight solved in closed form (the run starts at first touch).
    pub start_at_touch: bool,
    /// Free-flight time skipped (or simulated when `start_at_touch` is false), s.
    pub free_flight_time: f64,
    /// `separation` (stopped once apart and force-free for `hold_time`) or `end_time`.
    pub stop_rule: String,
    /// Multi-time-step integration: used or not and why, levels, element updates.
    pub subcycling: crate::fe::subcycle::SubcycleReport,
    /// Hold time of the separation rule, s.
    pub hold_time: f64,
    /// Per ball: plasticity skipped (the Hertz peak pressure stays below yield by a margin).
    pub elastic_only: [bool; 2],
    /// Friction computed (μ > 0 and not the frictionless symmetry plane).
    pub friction: bool,
}

/// One FE run's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Simulation {
    /// Results in the scene frame.
    pub outcome: Outcome,
    /// Largest relative energy error over the run: the drift of the total energy (kinetic +
    /// elastic + plastic + hourglass + contact stored + dissipated) from its start value, or
    /// the solver's work balance error, whichever is larger.
    pub energy_error: f64,
    /// Automatic savings used.
    pub savings: Savings,
    /// Elements simulated.
    pub elements: usize,
    /// Nodes simulated.
    pub nodes: usize,
    /// Time steps taken.
    pub steps: u64,
    /// Element updates actually taken (elements × steps without subcycling).
    pub element_cycles: u64,
    /// Initial stable time step, s.
    pub dt: f64,
    /// Why the run stopped.
    pub stop_reason: String,
    /// Wall time, s.
    pub wall_time_s: f64,
    /// Largest contact penetration over the run (simulated model), m.
    pub max_penetration: f64,
    /// Largest contact radius over the run, m (the section model; None for the 3D models).
    #[serde(skip)]
    pub contact_radius: Option<f64>,
    /// Ball 1's rotational inertia about the contact frame's z axis through its centre of
    /// mass, over m R² (-): the lumped mesh's, on the half and full models (None otherwise;
    /// a solid sphere's is 0.4).
    #[serde(skip)]
    pub spin1_inertia_ratio: Option<f64>,
    /// The contact force: raw and smoothed peaks, residual noise, the filter
    /// (results.json `fe.force`).
    pub force: ForceSummary,
    /// History rows.
    #[serde(skip)]
    pub history: Vec<HistoryRow>,
    /// Seconds per phase of the solver's steps (`RunOptions::profile` runs only).
    #[serde(skip)]
    pub phases: Option<Totals>,
}

/// Options of a single FE run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// History rows wanted over the expected contact (≥ 2).
    pub history_rows: usize,
    /// Report progress on stderr (a bar on a terminal, plain lines elsewhere).
    pub progress: bool,
    /// Write the `.vtu` snapshots as ASCII instead of compressed binary.
    pub vtu_ascii: bool,
    /// Folder for the scene's `.vtu` snapshots (`output.vtu_snapshots` of them); none
    /// written without it.
    pub snapshot_dir: Option<std::path::PathBuf>,
    /// Time the solver's phases (`fe::profile`; the totals are [`Simulation::phases`]).
    pub profile: bool,
    /// The 3D model's subcycling level rule and whether it holds the contact nodes' element
    /// neighbours at level 0 (`None`: the model's own; for studies of the rule).
    pub level_rule: Option<(crate::fe::subcycle::levels::LevelRule, bool)>,
}

/// A solver error in the scene's terms: the energy-growth stop gets the scene keys that
/// cure it; other errors pass unchanged.
pub fn advice(e: Error) -> Error {
    match e {
        Error::EnergyGrowth(g) => Error::Numerical(format!(
            "{g}: lower solver.time_step_factor or contact.penalty_factor"
        )),
        other => other,
    }
}

/// Default hold time after separation, as a fraction of the analytical contact duration:
/// long enough to see that the force stays zero (the gap opens by a few µm, more than the
/// pole's residual vibration), short enough not to integrate dead time.
pub const DEFAULT_HOLD_FRACTION: f64 = 0.03;

impl Simulation {
    /// The run as a sweep case: its outcome, figures and δ(t).
    pub fn fe_case(&self) -> crate::study::records::case::FeCase {
        crate::study::records::case::FeCase {
            delta_history: self.history.iter().map(|r| [r.t, r.delta]).collect(),
            summary: crate::study::records::case::FeSummary {
                outcome: self.outcome,
                energy_error: self.energy_error,
                reduction: self.savings.reduction.name().into(),
                elements: self.elements,
                element_cycles: self.element_cycles,
                wall_time_s: self.wall_time_s,
                e_error: None,
                scaled_from: None,
            },
        }
    }
}
