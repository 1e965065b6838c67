//! The seam between the solid solver and whatever pushes on its nodes from outside the
//! elements: contact pairs, rigid walls, body forces. The explicit loop (Box 6.1, step
//! "external forces") calls every [`Interaction`] once per step; contact laws plug in here.

use crate::error::Result;

/// What an interaction sees at one step of the central-difference loop.
///
/// Nodal arrays are indexed by global node number; vectors are (x, y, z) components.
#[derive(Debug, Clone, Copy)]
pub struct StepContext<'a> {
    /// Time t^n, s.
    pub t: f64,
    /// Time step Δt^{n+1/2} about to be taken, s.
    pub dt: f64,
    /// Current nodal coordinates x^n, m.
    pub x: &'a [[f64; 3]],
    /// Mid-step nodal velocities v^{n-1/2}, m/s.
    pub v: &'a [[f64; 3]],
    /// Lumped nodal masses, kg.
    pub mass: &'a [f64],
}

/// Energy bookkeeping of an interaction, J.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct InteractionEnergy {
    /// Recoverable energy stored now (penalty springs, elastic stick), J.
    pub stored: f64,
    /// Energy dissipated so far (friction, contact damping), J; never decreases.
    pub dissipated: f64,
    /// Work done so far on the nodes by this interaction's forces, J (for the balance check).
    pub work: f64,
}

/// A source of nodal forces that is not an element: contact, walls, loads.
pub trait Interaction: Send {
    /// Short name for reports (e.g. `ball-ball contact`).
    fn name(&self) -> &str;

    /// Adds this interaction's nodal forces (N) at t^n to `f`, indexed like `ctx.x`.
    ///
    /// Fails with [`crate::Error::Numerical`] when the interaction detects an instability
    /// (for example penetration beyond its allowed fraction of the element size).
    fn add_forces(&mut self, ctx: &StepContext<'_>, f: &mut [[f64; 3]]) -> Result<()>;

    /// The largest time step (s) this interaction keeps stable, given the lumped nodal
    /// masses (kg); `None` when it sets no limit.
    fn stable_time_step(&self, mass: &[f64]) -> Option<f64>;

    /// Stored, dissipated and total work so far, J.
    fn energy(&self) -> InteractionEnergy;

    /// The nodes (global numbers) this interaction may ever act on, if it knows them.
    /// Multi-time-step integration keeps the elements around them at the finest level, so
    /// that the interaction's force and the element forces that balance it are evaluated at
    /// the same instants. `None` (the default): unknown, no element is held back.
    fn active_nodes(&self) -> Option<&[u32]> {
        None
    }
}
