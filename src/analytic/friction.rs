//! The friction revision (Section 2.2–2.3, eqs. 34–43, Figure 4) read as a rigid-body Coulomb
//! impulse with stick/slip for solid spheres.
//!
//! Sliding friction μ p opposes the relative tangential slip of the contact points while it
//! lasts. A tangential impulse J_t changes the slip speed by (7/2) J_t/m* (translation plus
//! the spin of two solid spheres, I = (2/5) m R²), so slip stops once μ P_n(t) reaches
//! (2/7) m* |v_rt|, where P_n(t) = m*(v_r − δ̇(t)) is the normal impulse delivered so far.
//! Figure 4's "tangential motion finishes" is that moment; its test δ_t1 ≥ δ₁ compares the
//! approach at which slip stops with the end of phase 1 (see docs/design.md, section 2).

use super::three_phase::{NormalImpact, Phase};

/// How the tangential motion of the contact ended (Figure 4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentialExit {
    /// No relative tangential slip to start with (v_rt = 0) or no friction (μ = 0).
    NoSlip,
    /// Slip stopped ("tangential motion finished") during `phase`, at `time` s after first
    /// touch and normal approach `approach` m; the contact points roll together afterwards.
    Stick {
        /// Phase in which slip stopped.
        phase: Phase,
        /// Time since first touch, s.
        time: f64,
        /// Normal approach δ_t at that moment, m.
        approach: f64,
    },
    /// The normal motion finished first: the balls slid for the whole contact.
    Slip,
}

/// Tangential outcome of an impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialImpact {
    /// Friction coefficient used, μ.
    pub mu: f64,
    /// Relative tangential slip speed before impact v_rt = v_t1 − v_t2, m/s.
    pub slip_speed: f64,
    /// Tangential impulse on ball 2 along +t (ball 1 receives −J_t), N·s; same sign as v_rt.
    pub impulse: f64,
    /// How the tangential motion ended.
    pub exit: TangentialExit,
}

/// Rigid-body Coulomb tangential impulse for a normal impact `n` with friction coefficient μ
/// (≥ 0) and relative tangential slip speed v_rt (m/s) of the contact points, no initial spin.
pub fn tangential_impact(n: &NormalImpact, mu: f64, slip_speed: f64) -> TangentialImpact {
    let m = n.pair.mass;
    let vr = n.approach_speed;
    let needed = 2.0 / 7.0 * m * slip_speed.abs();
    let available = mu * (1.0 + n.e) * m * vr;
    let (impulse, exit) = if needed == 0.0 || mu == 0.0 {
        (0.0, TangentialExit::NoSlip)
    } else if needed <= available {
        // Slip stops when δ̇ has fallen to δ̇_s = v_r − (2/7)|v_rt|/μ.
        let rate = vr - needed / (mu * m);
        let (phase, time, approach) = stop_state(n, rate);
        (
            needed * slip_speed.signum(),
            TangentialExit::Stick {
                phase,
                time,
                approach,
            },
        )
    } else {
        (available * slip_speed.signum(), TangentialExit::Slip)
    };
    TangentialImpact {
        mu,
        slip_speed,
        impulse,
        exit,
    }
}

/// Phase, time (s) and approach (m) at which the approach rate first equals `rate` (m/s,
/// v_r ≥ rate ≥ −v_r⁺).
fn stop_state(n: &NormalImpact, rate: f64) -> (Phase, f64, f64) {
    let p = &n.pair;
    let k = 16.0 * p.modulus * p.radius.sqrt() / (15.0 * p.mass);
    let vr = n.approach_speed;
    if rate >= n.delta1_rate && (rate > 0.0 || !n.yielded) && rate >= 0.0 {
        // Phase 1: energy gives δ from δ̇.
        let d = ((vr * vr - rate * rate) / k)
            .max(0.0)
            .powf(0.4)
            .min(n.delta1);
        return (Phase::ElasticCompression, p.time_to_approach(vr, d), d);
    }
    if rate >= 0.0 {
        // Phase 2: δ − δ_e = A cos(ω(t − t₂)), δ̇ = −Aω sin(ω(t − t₂)).
        let de = super::three_phase::plastic_offset(p, n.yield_pressure);
        let omega = (std::f64::consts::PI * p.radius * n.yield_pressure / p.mass).sqrt();
        let amp = n.delta2 - de;
        let arg = (rate / (amp * omega)).clamp(-1.0, 1.0).asin();
        let t = n.t2 - arg / omega;
        return (Phase::ElastoplasticCompression, t, de + amp * arg.cos());
    }
    // Phase 3: shifted Hertz unloading, δ̇² = k[(δ₂ − δ_p)^{5/2} − (δ − δ_p)^{5/2}].
    let top = n.delta2 - n.delta_p;
    let s = (top.powf(2.5) - rate * rate / k).max(0.0).powf(0.4);
    let vp = n.rebound_speed;
    let t = n.t2 + (p.time_to_approach(vp, top) - p.time_to_approach(vp, s));
    (Phase::ElasticRecovery, t, n.delta_p + s)
}

/// Zhang's kinetic-energy loss (eq. 42), J:
/// ½ m* {[(1 − e²) − (1 + e)² 7μ²/2] v_rn² + 2 (1 + e) μ v_rn |v_rt|}. It is exactly the loss of a Coulomb impact that slides for the
/// whole contact (impulse μ(1 + e) m* v_rn); it overstates the loss when the slip stops.
pub fn zhang_energy_loss(m_eff: f64, e: f64, mu: f64, v_rn: f64, v_rt: f64) -> f64 {
    0.5 * m_eff
        * (((1.0 - e * e) - (1.0 + e).powi(2) * 3.5 * mu * mu) * v_rn * v_rn
            + 2.0 * (1.0 + e) * mu * v_rn * v_rt.abs())
}

/// Kinetic energy ½ m v², J; zero when v = 0 even for an immovable (infinite-mass) body.
pub fn kinetic(m: f64, v: f64) -> f64 {
    if v == 0.0 {
        0.0
    } else {
        0.5 * m * v * v
    }
}

/// Normal kinetic-energy loss of an impact with restitution e, ½ m* v_rn² (1 − e²), J: the
/// difference of eq. 33's numerator evaluated with eq. 32's velocities, in a form that is
/// never negative by round-off.
pub fn normal_energy_loss(m_eff: f64, e: f64, v_rn: f64) -> f64 {
    0.5 * m_eff * v_rn * v_rn * (1.0 - e * e).max(0.0)
}

/// Kinetic energy (translation and spin) lost to friction by a tangential impulse of
/// magnitude |J_t| ≤ (2/7) m* |v_rt| between solid spheres, J_t |v_rt| − (7/4) J_t²/m*, J;
/// (1/7) m* v_rt² when the slip stops.
pub fn tangential_energy_loss(m_eff: f64, impulse: f64, v_rt: f64) -> f64 {
    let j = impulse.abs();
    if j == 0.0 {
        0.0
    } else {
        (j * (v_rt.abs() - 1.75 * j / m_eff)).max(0.0)
    }
}

/// Revised energy dissipation factor (eq. 43):
/// η = {KE_n⁻ − KE_n⁺ + m*(1 + e) μ v_rn |v_rt|} / (2π {½m₁(v_n1² + v_t1²) + ½m₂(v_n2² + v_t2²)}).
///
/// Velocities before (`v1`, `v2` = [normal, tangential], m/s), masses in kg (infinite for a
/// wall at rest), restitution e of the normal impact. KE_n⁻ − KE_n⁺ is taken as
/// [`normal_energy_loss`] (identical to eq. 32's velocities). The printed denominator repeats
/// v_t1 for both balls; the symmetric form is used. |v_rt| keeps the friction term a loss
/// whatever the sign of the tangential slip. Zero if there is no approach or nothing moves.
pub fn revised_eta(m1: f64, m2: f64, v1: [f64; 2], v2: [f64; 2], e: f64, mu: f64) -> f64 {
    let m = super::hertz::effective_mass(m1, m2);
    let v_rn = (v1[0] - v2[0]).max(0.0);
    let loss = normal_energy_loss(m, e, v_rn) + m * (1.0 + e) * mu * v_rn * (v1[1] - v2[1]).abs();
    let total = kinetic(m1, v1[0]) + kinetic(m2, v2[0]) + kinetic(m1, v1[1]) + kinetic(m2, v2[1]);
    if total == 0.0 || v_rn == 0.0 {
        0.0
    } else {
        loss / (2.0 * std::f64::consts::PI * total)
    }
}
