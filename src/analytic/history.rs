//! Time histories of the normal impact: approach δ(t), approach rate δ̇(t) and contact force
//! p(t) over the whole collision, from the closed forms of each phase.

use super::three_phase::NormalImpact;

/// One sample of the collision history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time since first touch, s.
    pub t: f64,
    /// Relative approach of the centres δ, m.
    pub delta: f64,
    /// Approach rate δ̇, m/s (positive while the balls close in).
    pub delta_dot: f64,
    /// Contact force p, N.
    pub force: f64,
}

/// `count` (≥ 2) samples evenly spaced in time from first touch (t = 0) to separation (t₃),
/// both included. `count` below 2 is raised to 2.
pub fn history(n: &NormalImpact, count: usize) -> Vec<Sample> {
    let count = count.max(2);
    (0..count)
        .map(|i| {
            let t = n.t3 * i as f64 / (count - 1) as f64;
            sample_at(n, t)
        })
        .collect()
}

/// The sample at time t (s); δ, δ̇ and p are zero outside [0, t₃].
pub fn sample_at(n: &NormalImpact, t: f64) -> Sample {
    let (delta, delta_dot) = n.state_at(t);
    let force = n.phase_at(t).map_or(0.0, |ph| n.force(delta, ph));
    Sample {
        t,
        delta,
        delta_dot,
        force,
    }
}
