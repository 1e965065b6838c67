//! The contact-law seam: a normal law (force from approach, approach rate and the law's own
//! loading/unloading history) and a tangential law (stiffness and friction limit), one file per
//! law, all behind the same two traits so that one integrator ([`super::impact`]) runs them.
//!
//! A law is described by a [`NormalSpec`] or [`TangentialSpec`] (name, source, parameters with
//! units and defaults, the DEM codes that ship it) whose `build` makes the law for one contact
//! pair from resolved parameters. [`Registry::builtin`] lists every law of the crate; a
//! researcher adds one by writing a file that implements [`NormalLaw`] and registering its
//! spec (see `examples/custom_law.rs` and docs/contact-laws.md).

pub mod coulomb;
pub mod hertz;
pub mod hertz_damped;
pub mod hunt_crossley;
pub mod jackson_green;
pub mod kuwabara_kono;
pub mod lankarani_nikravesh;
pub mod li_yang_shi;
pub mod linear_dashpot;
pub mod mindlin;
pub mod mindlin_coulomb;
mod pair;
mod params;
mod quasi_static;
mod registry;
pub mod tabor_hardening;
pub mod thornton;
pub mod thornton_yin;
pub mod validity;
pub mod walton_braun;

pub use pair::ContactPair;
pub use params::{ParamSpec, Params};
pub use registry::{NormalSpec, Registry, TangentialSpec};
pub use validity::Validity;

/// The state of the contact at the last maximum of approach (where loading turned into
/// unloading): the history every hysteretic law needs, with the law's permanent approach
/// computed once per turn (the unloading curve is evaluated every step).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turn {
    /// Maximum approach reached, m.
    pub delta: f64,
    /// Contact force there, N.
    pub force: f64,
    residual: f64,
}

impl Turn {
    /// The turn of `law` at approach `delta` (m) under force `force` (N).
    pub fn new<L: NormalLaw + ?Sized>(law: &L, delta: f64, force: f64) -> Self {
        Turn {
            delta,
            force,
            residual: law.residual(delta, force),
        }
    }

    /// The law's permanent approach δ_p after this turn (m): where its unloading force returns
    /// to zero ([`NormalLaw::residual`]).
    pub fn residual(&self) -> f64 {
        self.residual
    }
}

/// Restitution and maximum approach of a head-on impact from a law's own closed form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedForm {
    /// Coefficient of restitution e = v_r⁺/v_r.
    pub e: f64,
    /// Maximum approach δ_max, m.
    pub delta_max: f64,
}

/// A normal contact law: the force F (N, positive = repulsive) between the two bodies.
///
/// `delta` is the approach (overlap) δ ≥ 0 in m, `rate` the approach rate δ̇ in m/s (positive
/// while the bodies close in), `speed` the approach speed at first touch v_r in m/s (laws such
/// as Hunt-Crossley scale their damping by it; DEM codes store it at first touch).
pub trait NormalLaw: Send + Sync {
    /// Force on first (virgin) loading, N. Must be 0 at δ = 0 for rate-independent laws.
    fn loading(&self, delta: f64, rate: f64, speed: f64) -> f64;

    /// Force after the turn `turn` (unloading, and reloading below the turn), N. The default
    /// is the loading law (no hysteresis).
    fn unloading(&self, delta: f64, rate: f64, speed: f64, turn: &Turn) -> f64 {
        let _ = turn;
        self.loading(delta, rate, speed)
    }

    /// Permanent approach δ_p (m) after unloading from a turn at approach `delta` (m) under
    /// force `force` (N): where the unloading force returns to zero. [`Turn::new`] calls it
    /// once per turn. Default 0 (a law without hysteresis).
    fn residual(&self, delta: f64, force: f64) -> f64 {
        let _ = (delta, force);
        0.0
    }

    /// Approaches (m, ascending) at which the loading law changes its form (yield, a fitted
    /// range's end); the integrator stops exactly on them and counts phases. Default none.
    fn thresholds(&self) -> Vec<f64> {
        Vec::new()
    }

    /// True if the force may pull (negative F): the contact then ends when δ returns to 0.
    /// False (default): F is clipped at 0 and the contact ends when the law's force first
    /// reaches 0 on unloading.
    fn tensile(&self) -> bool {
        false
    }

    /// The law's own closed form (or an independent quadrature) for e and δ_max at approach
    /// speed v_r (m/s) and effective mass m* (kg), if it has one; `None` otherwise.
    fn closed_form(&self, speed: f64, mass: f64) -> Option<ClosedForm> {
        let _ = (speed, mass);
        None
    }
}

/// A tangential contact law: a spring of stiffness k_t(δ) (N/m) on the tangential
/// displacement of the contact points, capped by Coulomb friction μ F_n.
///
/// k_t = 0 is the rigid Coulomb impulse (slip at μ F_n until the slip stops, then roll);
/// μ = ∞ is a spring that never slips.
pub trait TangentialLaw: Send + Sync {
    /// Tangential stiffness k_t (N/m) at normal approach δ (m); 0 for a rigid law.
    fn stiffness(&self, delta: f64) -> f64;

    /// Friction coefficient μ (≥ 0; `f64::INFINITY` for no slip).
    fn friction(&self) -> f64;

    /// True for a law with slip memory (Masing rules): the integrator then integrates the
    /// displacement ξ of the contact points throughout, records a turning point where the
    /// slip reverses, forgets a pair of them when the displacement regains the older one,
    /// and takes the force from [`TangentialLaw::force`] (capped at μF). Default false: a
    /// spring k_t ξ with the integrator's own stick-slip switch.
    fn memory(&self) -> bool {
        false
    }

    /// Tangential force f (N) of a law with memory at displacement ξ (m), approach δ (m) and
    /// normal force F (N, clipped at 0 by the caller), after the turning displacements `turns`
    /// (m, oldest first; the last is where the slip last reversed) while the displacement
    /// moves in `direction` (±1). Default: the spring k_t(δ) ξ.
    fn force(&self, xi: f64, delta: f64, normal: f64, turns: &[f64], direction: f64) -> f64 {
        let _ = (normal, turns, direction);
        self.stiffness(delta) * xi
    }
}
