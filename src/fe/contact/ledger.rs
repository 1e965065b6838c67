//! What a 3D penalty contact keeps besides its springs: the trapezoidal work of its nodal
//! forces, its stored and dissipated energies, and the output and pressures of its last step.

use super::law::NodeResponse;
use super::output::{ContactOutput, ContactProbe, OutputBuilder, PressureSample};
use crate::fe::solver::interaction::InteractionEnergy;
use crate::fe::tensor::dot;

/// The energy and output bookkeeping of one contact over `slots` nodes.
#[derive(Debug, Clone, Default)]
pub struct ContactLedger {
    /// Each slot's force of the previous step, N.
    prev_force: Vec<[f64; 3]>,
    /// The step taken before this one, s (`None` before the first).
    dt_prev: Option<f64>,
    energy: InteractionEnergy,
    friction_energy: f64,
    output: ContactOutput,
    samples: Vec<PressureSample>,
    probe: ContactProbe,
}

impl ContactLedger {
    /// A ledger for `slots` nodes, nothing done yet.
    pub fn new(slots: usize) -> Self {
        ContactLedger {
            prev_force: vec![[0.0; 3]; slots],
            ..Default::default()
        }
    }

    /// The step just taken, x^{n−1} → x^n, s (0 before the first).
    pub fn last_step(&self) -> f64 {
        self.dt_prev.unwrap_or(0.0)
    }

    /// Books one node's dissipation (friction and dashpot), J.
    pub fn dissipate(&mut self, r: &NodeResponse) {
        self.energy.dissipated += r.dissipated;
        self.friction_energy += r.friction;
    }

    /// Books the work of slot `slot`'s force, ½(f^{n−1} + f^n)·v^{n−½} Δt^{n−½} (J, with `force`
    /// f^n in N and `v` the node's velocity in m/s), and keeps f^n for the next step. A slot
    /// without force at either end does no work.
    pub fn work(&mut self, slot: usize, force: [f64; 3], v: [f64; 3]) {
        let fp = self.prev_force[slot];
        if fp != [0.0; 3] || force != [0.0; 3] {
            let avg = [
                0.5 * (fp[0] + force[0]),
                0.5 * (fp[1] + force[1]),
                0.5 * (fp[2] + force[2]),
            ];
            self.energy.work += dot(avg, v) * self.last_step();
        }
        self.prev_force[slot] = force;
    }

    /// Closes the step of length `dt` (s): the springs' stored energy `stored` (J), and the
    /// step's output and pressures from `out`, also handed to the probe.
    pub fn finish(&mut self, out: OutputBuilder, stored: f64, dt: f64) {
        self.energy.stored = stored;
        let (o, s) = out.finish(stored, self.energy.dissipated, self.friction_energy);
        self.probe.update(&o, &s);
        self.output = o;
        self.samples = s;
        self.dt_prev = Some(dt);
    }

    /// Stored, dissipated and work so far, J.
    pub fn energy(&self) -> InteractionEnergy {
        self.energy
    }

    /// A shared handle on the output that stays readable after the contact is boxed and
    /// handed to the solver.
    pub fn probe(&self) -> ContactProbe {
        self.probe.clone()
    }

    /// Output of the last evaluated step.
    pub fn output(&self) -> &ContactOutput {
        &self.output
    }

    /// Pressure at every node in contact at the last evaluated step.
    pub fn pressures(&self) -> &[PressureSample] {
        &self.samples
    }
}
