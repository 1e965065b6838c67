//! The energy ledger: where every joule of the released frame is at one instant.

/// Energy terms at one instant, J. The mechanical terms are read from the state; the
/// dissipated ones are the work the contacts and the damper took out of the bodies, minus
/// what the open contacts still store.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Ledger {
    /// Frame kinetic energy ½ M v², J.
    pub frame_kinetic: f64,
    /// Frame spring energy ½ k x², J.
    pub frame_spring: f64,
    /// Balls' kinetic energy Σ ½ m v² + ½ I ω², J.
    pub balls_kinetic: f64,
    /// Balls' potential energy Σ m g (z − R) (zero resting on the floor), J.
    pub balls_potential: f64,
    /// Energy stored in open contacts (normal unloading curve and tangential springs), J.
    pub contact_stored: f64,
    /// Energy dissipated by the normal contact laws, J.
    pub contact_dissipated: f64,
    /// Energy dissipated by friction (tangential laws), J.
    pub friction_dissipated: f64,
    /// Energy dissipated by the frame's structural damping ∫ c v² dt, J.
    pub structural_dissipated: f64,
}

impl Ledger {
    /// Mechanical energy (frame, balls and what the contacts store), J.
    pub fn mechanical(&self) -> f64 {
        self.frame_kinetic
            + self.frame_spring
            + self.balls_kinetic
            + self.balls_potential
            + self.contact_stored
    }

    /// Everything dissipated so far, J.
    pub fn dissipated(&self) -> f64 {
        self.contact_dissipated + self.friction_dissipated + self.structural_dissipated
    }

    /// Mechanical plus dissipated energy: constant in time if the balance closes, J.
    pub fn total(&self) -> f64 {
        self.mechanical() + self.dissipated()
    }

    /// (total now − total at start)/total at start: the relative balance residual.
    pub fn residual(&self, start: &Ledger) -> f64 {
        (self.total() - start.total()) / start.total()
    }
}
