//! One row of history.csv: the state of the whole two-ball system at one instant, and the
//! file's header with its units.

use serde::Serialize;

/// One row of history.csv; every quantity is for the whole two-ball system (for the one ball
/// with a wall, ball 2's columns the wall's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HistoryRow {
    /// Time since first touch, s (negative during simulated free flight).
    pub t: f64,
    /// Approach δ = change of the distance between the mass centres since first touch, m.
    pub delta: f64,
    /// Normal contact force, N.
    pub normal_force: f64,
    /// Tangential (friction) contact force, N.
    pub tangential_force: f64,
    /// Centre-of-mass velocities of ball 1 and 2 (scene frame), m/s.
    pub v: [[f64; 3]; 2],
    /// Angular velocities of ball 1 and 2 (scene frame), rad/s.
    pub w: [[f64; 3]; 2],
    /// Kinetic energy (nodal, includes vibration), J.
    pub kinetic: f64,
    /// Elastic strain energy, J.
    pub elastic: f64,
    /// Plastic work, J.
    pub plastic: f64,
    /// Hourglass energy, J.
    pub hourglass: f64,
    /// Energy stored in the contact penalty springs, J.
    pub contact_stored: f64,
    /// Energy dissipated by friction (and contact damping), J.
    pub contact_dissipated: f64,
    /// Sum of all the above, J.
    pub total: f64,
    /// Normal impulse since the start of the run, ∫F dt accumulated every step, N·s.
    pub impulse: f64,
    /// Normal contact force smoothed by a triangular window of half-width T_c/20 in time,
    /// impulse kept ([`crate::study::run::smoothed_force`]), N.
    pub normal_force_smoothed: f64,
}

/// The header of history.csv, units in brackets.
pub const HISTORY_HEADER: &str = "t [s],delta [m],normal_force [N],tangential_force [N],\
v1x [m/s],v1y [m/s],v1z [m/s],v2x [m/s],v2y [m/s],v2z [m/s],\
w1x [rad/s],w1y [rad/s],w1z [rad/s],w2x [rad/s],w2y [rad/s],w2z [rad/s],\
kinetic [J],elastic [J],plastic [J],hourglass [J],contact_stored [J],contact_dissipated [J],total [J],\
impulse [N s],normal_force_smoothed [N]";

impl HistoryRow {
    /// The row as CSV (all values finite by construction; checked by the caller).
    pub fn csv(&self) -> String {
        self.values()
            .iter()
            .map(|x| format!("{x:.9e}"))
            .collect::<Vec<_>>()
            .join(",")
    }

    /// The row's values in the order of [`HISTORY_HEADER`], in its units.
    pub fn values(&self) -> Vec<f64> {
        let mut v = vec![self.t, self.delta, self.normal_force, self.tangential_force];
        v.extend(self.v.iter().flatten());
        v.extend(self.w.iter().flatten());
        v.extend([
            self.kinetic,
            self.elastic,
            self.plastic,
            self.hourglass,
            self.contact_stored,
            self.contact_dissipated,
            self.total,
            self.impulse,
            self.normal_force_smoothed,
        ]);
        v
    }

    pub(super) fn is_finite(&self) -> bool {
        self.values().iter().all(|x| x.is_finite())
    }
}
