//! The seam between the solid solver and whatever pushes on its nodes from outside the
//! elements: contact pairs, rigid planes and walls, body forces. The explicit loop (Box 6.1,
//! step "external forces") calls every [`Interaction`] once per force evaluation; contact
//! laws plug in here. One trait for every dimension: `D` is the number of nodal components,
//! 3 for the hexahedral model (x, y, z), 2 for the meridian section (r, z; forces of whole
//! rings).

use crate::error::Result;

/// What an interaction sees at one force evaluation of the central-difference loop.
///
/// Nodal arrays are indexed by global node number; vectors have `D` components ((x, y, z) in
/// 3D, (r, z) on the meridian section).
#[derive(Debug, Clone, Copy)]
pub struct StepContext<'a, const D: usize = 3> {
    /// Time t^n, s.
    pub t: f64,
    /// Time step Δt^{n+1/2} about to be taken, s.
    pub dt: f64,
    /// Current nodal coordinates x^n, m.
    pub x: &'a [[f64; D]],
    /// Mid-step nodal velocities v^{n-1/2}, m/s.
    pub v: &'a [[f64; D]],
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

/// What a contact reports for its last force evaluation (the meridian loop's history reads
/// it; a contact with a richer output of its own may keep the default).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactState {
    /// Total normal force (of the whole ring on the section), N.
    pub normal_force: f64,
    /// Energy stored in the penalty springs, J.
    pub stored: f64,
    /// Nodes in contact.
    pub active_nodes: usize,
    /// Largest penetration, m.
    pub max_penetration: f64,
    /// Largest distance from the axis (current r) of a node in contact (the contact radius on
    /// the section), m.
    pub contact_radius: f64,
}

impl ContactState {
    /// Counts one node in contact: its normal force `force` (N), penalty energy `stored` (J),
    /// penetration `penetration` (m) and current radius `r` (m).
    pub fn add_node(&mut self, force: f64, stored: f64, penetration: f64, r: f64) {
        self.normal_force += force;
        self.stored += stored;
        self.active_nodes += 1;
        self.max_penetration = self.max_penetration.max(penetration);
        self.contact_radius = self.contact_radius.max(r);
    }
}

/// What the loop passes for one node's kick to a kinematic contact: its position x^n (m),
/// half-step velocity v^{n−1/2} (m/s), lumped mass (kg), and the steps closed and opened (s).
#[derive(Debug, Clone, Copy)]
pub struct Kick<const D: usize> {
    /// Position, m.
    pub x: [f64; D],
    /// Half-step velocity of the step just closed, m/s.
    pub v_half: [f64; D],
    /// Lumped mass, kg.
    pub mass: f64,
    /// The step the kick closes, s (0 at the start).
    pub close: f64,
    /// The step the kick opens, s.
    pub open: f64,
}

/// A source of nodal forces that is not an element: contact, walls, loads.
///
/// A penalty contact adds forces ([`Interaction::add_forces`]) and reports its springs' step
/// limits; a kinematic one also claims its nodes ([`Interaction::holds`]) and corrects their
/// accelerations at their kicks ([`Interaction::constrain`]).
pub trait Interaction<const D: usize = 3>: Send {
    /// Short name for reports (e.g. `ball-ball contact`).
    fn name(&self) -> &str;

    /// Adds this interaction's nodal forces (N) at t^n to `f`, indexed like `ctx.x`.
    ///
    /// Fails with [`crate::Error::Numerical`] when the interaction detects an instability
    /// (for example penetration beyond its allowed fraction of the element size).
    fn add_forces(&mut self, ctx: &StepContext<'_, D>, f: &mut [[f64; D]]) -> Result<()>;

    /// The largest time step (s) this interaction keeps stable, given the lumped nodal
    /// masses `mass` (kg) and, where the loop tracks it, the highest frequency `omega` (rad/s)
    /// of the elements at each node (empty otherwise: the interaction then uses its own
    /// estimate); `None` when it sets no limit. The default: the smallest of its
    /// [`Interaction::node_limits`].
    fn stable_time_step(&self, mass: &[f64], omega: &[f64]) -> Option<f64> {
        let limits = self.node_limits(mass, omega);
        limits.into_iter().map(|(_, dt)| dt).reduce(f64::min)
    }

    /// Stored, dissipated and total work so far, J.
    fn energy(&self) -> InteractionEnergy;

    /// The nodes (global numbers) this interaction may ever act on, if it knows them.
    /// Multi-time-step integration keeps the elements around them at the finest level, so
    /// that the interaction's force and the element forces that balance it are evaluated at
    /// the same instants. `None` (the default): unknown, no element is held back.
    fn active_nodes(&self) -> Option<&[u32]> {
        None
    }

    /// Every node the interaction may act on with the largest stable step (s) its springs
    /// allow it, on masses `mass` (kg) and element frequencies `omega` (rad/s) as in
    /// [`Interaction::stable_time_step`]; nodes whose forces are coupled (a node and the
    /// segments it meets) share one step. Empty (the default): no per-node limit.
    fn node_limits(&self, _mass: &[f64], _omega: &[f64]) -> Vec<(usize, f64)> {
        Vec::new()
    }

    /// True for a node the interaction constrains kinematically at its kicks (none for a
    /// penalty contact, the default).
    fn holds(&self, _i: usize) -> bool {
        false
    }

    /// A kinematic contact's correction of the acceleration `a` (m/s²) of node `i` at its
    /// kick `node` (forces already in `a`); returns the work of its force over the kick, J.
    fn constrain(&mut self, _i: usize, _node: Kick<D>, _a: &mut [f64; D]) -> f64 {
        0.0
    }

    /// The contact's state at its last force evaluation (the default: nothing to report).
    fn state(&self) -> ContactState {
        ContactState::default()
    }
}
