//! The public entry point: two bodies, their velocities before impact, everything after.
//!
//! Axes: the normal n points from ball 1 to ball 2 (ball 1 on the left, +x); the tangential t
//! is one fixed direction in the contact plane. Velocities are [normal, tangential] in m/s;
//! spins are about n × t, rad/s. No initial spin.

use super::body::Body;
use super::exchange::{exchange, Exchange};
use super::friction::{
    kinetic, normal_energy_loss, revised_eta, tangential_energy_loss, tangential_impact,
    zhang_energy_loss, TangentialImpact,
};
use super::hertz::HertzPair;
use super::three_phase::NormalImpact;
use crate::error::{Error, Result};

/// Everything the analytical model says about one collision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Collision {
    /// Whether the bodies hit (v_r = v_n1 − v_n2 > 0). If not, velocities are unchanged,
    /// `normal` and `tangential` are `None` and both η are 0.
    pub impact: bool,
    /// Effective quantities of the pair.
    pub pair: HertzPair,
    /// Friction coefficient used, μ.
    pub mu: f64,
    /// The three-phase normal impact.
    pub normal: Option<NormalImpact>,
    /// The Coulomb stick/slip tangential impulse and Figure 4's exit.
    pub tangential: Option<TangentialImpact>,
    /// Velocities before, [normal, tangential], m/s.
    pub v1_before: [f64; 2],
    /// Velocities before, [normal, tangential], m/s.
    pub v2_before: [f64; 2],
    /// The state after: velocities [normal, tangential] (m/s; eq. 32 and the Coulomb
    /// impulse), spins about n × t (rad/s; 0 for a wall) and kinetic energy (translation and
    /// spin, J). Without impact the velocities before, no spin and `energy_before`.
    pub after: Exchange,
    /// Energy dissipation factor of the normal impact, eq. 33.
    pub eta: f64,
    /// Revised factor with friction, eq. 43 (the paper's definition).
    pub eta_friction: f64,
    /// (Kinetic energy lost, translation and spin, under the Coulomb impulse) / (2π KE before):
    /// eq. 33's definition applied to this model's after-impact state.
    pub eta_impulse: f64,
    /// Zhang's energy loss, eq. 42, J.
    pub zhang_loss: f64,
    /// Kinetic energy before (translation only; no initial spin), J.
    pub energy_before: f64,
}

/// Pair friction coefficient: the mean of the two materials' dynamic μ (a rigid wall takes the
/// ball's).
pub fn pair_friction(b1: &Body, b2: &Body) -> f64 {
    match (b1.material(), b2.material()) {
        (Some(a), Some(b)) => 0.5 * (a.mu + b.mu),
        (Some(a), None) | (None, Some(a)) => a.mu,
        (None, None) => 0.0,
    }
}

/// Collides body 1 (a ball) with body 2 (a ball or a wall at rest) using the pair friction
/// coefficient [`pair_friction`]. See [`collide_with_mu`].
pub fn collide(b1: &Body, b2: &Body, v1: [f64; 2], v2: [f64; 2]) -> Result<Collision> {
    collide_with_mu(b1, b2, v1, v2, pair_friction(b1, b2))
}

/// Collides body 1 (must be a ball) with body 2 (ball or wall) with friction coefficient μ.
///
/// Errors: body 1 a wall; a wall with non-zero velocity; non-finite velocities; μ negative or
/// not finite. No impact (v_n1 ≤ v_n2) is not an error: `impact = false`.
pub fn collide_with_mu(
    b1: &Body,
    b2: &Body,
    v1: [f64; 2],
    v2: [f64; 2],
    mu: f64,
) -> Result<Collision> {
    if b1.is_wall() {
        return Err(Error::invalid("ball1", "a wall", "body 1 must be a ball"));
    }
    let names = ["v1", "v1t", "v2", "v2t"];
    for (name, v) in names.iter().zip([v1[0], v1[1], v2[0], v2[1]]) {
        if !v.is_finite() {
            return Err(Error::invalid(*name, v, "a finite speed in m/s"));
        }
    }
    if b2.is_wall() && (v2[0] != 0.0 || v2[1] != 0.0) {
        return Err(Error::invalid(
            "v2",
            format!("[{}, {}]", v2[0], v2[1]),
            "0 for a wall (a half-space does not move)",
        ));
    }
    if !(mu.is_finite() && mu >= 0.0) {
        return Err(Error::invalid("mu", mu, "mu >= 0, finite"));
    }
    let pair = HertzPair::between(b1, b2);
    let (m1, m2) = (b1.mass(), b2.mass());
    let sigma_p = b1.yield_pressure().min(b2.yield_pressure());
    let energy_before =
        kinetic(m1, v1[0]) + kinetic(m1, v1[1]) + kinetic(m2, v2[0]) + kinetic(m2, v2[1]);
    let Some(normal) = NormalImpact::solve(pair, sigma_p, v1[0] - v2[0]) else {
        return Ok(Collision {
            impact: false,
            pair,
            mu,
            normal: None,
            tangential: None,
            v1_before: v1,
            v2_before: v2,
            after: Exchange {
                v1_after: v1,
                v2_after: v2,
                spin_after: [0.0; 2],
                energy_after: energy_before,
            },
            eta: 0.0,
            eta_friction: 0.0,
            eta_impulse: 0.0,
            zhang_loss: 0.0,
            energy_before,
        });
    };
    let e = normal.e;
    let vr = normal.approach_speed;
    // Eq. 32 in impulse form (finite for a wall: m*/m₂ = 0, m*/m₁ = 1).
    let jn = (1.0 + e) * pair.mass * vr;
    let tang = tangential_impact(&normal, mu, v1[1] - v2[1]);
    let jt = tang.impulse;
    let after = exchange(b1, b2, v1, v2, jn, jt);
    let two_pi = 2.0 * std::f64::consts::PI;
    let ke_n_before = kinetic(m1, v1[0]) + kinetic(m2, v2[0]);
    let eta = normal_energy_loss(pair.mass, e, vr) / (two_pi * ke_n_before);
    let eta_friction = revised_eta(m1, m2, v1, v2, e, mu);
    let lost =
        normal_energy_loss(pair.mass, e, vr) + tangential_energy_loss(pair.mass, jt, v1[1] - v2[1]);
    let eta_impulse = lost / (two_pi * energy_before);
    Ok(Collision {
        impact: true,
        pair,
        mu,
        normal: Some(normal),
        tangential: Some(tang),
        v1_before: v1,
        v2_before: v2,
        after,
        eta,
        eta_friction,
        eta_impulse,
        zhang_loss: zhang_energy_loss(pair.mass, e, mu, vr, v1[1] - v2[1]),
        energy_before,
    })
}
