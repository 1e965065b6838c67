//! A finished FE run as the case records of sweeps and benches hold it: the outcome, its cost
//! and error bar, and the δ(t) history.

use crate::study::records::outcome::Outcome;
use serde::{Deserialize, Serialize};

/// The FE part of a case result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FeSummary {
    /// The FE outcome.
    pub outcome: Outcome,
    /// Relative energy-balance error of the run.
    pub energy_error: f64,
    /// Symmetry reduction used (`quarter`, `half`, `full`).
    pub reduction: String,
    /// Number of elements simulated.
    pub elements: usize,
    /// Element updates (elements × steps).
    pub element_cycles: u64,
    /// Wall time of the FE run, s.
    pub wall_time_s: f64,
    /// The run's error estimate of e (absolute, -), when it has one (a head-on case on the
    /// section).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub e_error: Option<f64>,
    /// The case whose FE run this is, scaled by dimensional similarity
    /// ([`crate::study::sweep::similarity`]); None when the case ran its own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scaled_from: Option<String>,
}

/// An FE run as a sweep sees it: the summary and the δ(t) history (t in s, δ in m).
#[derive(Debug, Clone, PartialEq)]
pub struct FeCase {
    /// Summary numbers.
    pub summary: FeSummary,
    /// δ(t) samples.
    pub delta_history: Vec<[f64; 2]>,
}
