//! Normal penalty law: how stiff the contact springs are and what force a penetration gives.
//!
//! Two stiffness rules (per contact node i, with tributary area A_i of its surface):
//! - [`PenaltyRule::Fkn`] (ANSYS-style, the paper's "FKN on E"): a pressure per unit
//!   penetration ε_i = FKN · E / h_i, so k_i = FKN · E · A_i / h_i, where h_i is the thickness of
//!   the solid elements under node i (element volume / face area, averaged over the node's
//!   faces) and E the Young's modulus of the body the node belongs to (smaller of the two E for
//!   ball–ball pairs).
//! - [`PenaltyRule::Soft`] (LS-DYNA SOFT=1-style): k_i = max(s K A_i² / V_i, s_dt m_i* / Δt²) with
//!   K the bulk modulus, V_i the element volume under the node, m_i* the effective mass of the
//!   node pair and Δt the step of the first contact evaluation (s = 0.1, s_dt = 0.05 by default).

use crate::error::{Error, Result};

/// How the normal penalty stiffness is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PenaltyRule {
    /// k = FKN · E · A / h (dimensionless factor FKN > 0).
    Fkn {
        /// The penalty factor FKN (> 0).
        factor: f64,
    },
    /// k = max(scale · K A² / V, dt_scale · m* / Δt²).
    Soft {
        /// Scale on the bulk-modulus term (LS-DYNA SLSFAC, 0.1).
        scale: f64,
        /// Scale on the time-step term (0.05).
        dt_scale: f64,
    },
}

impl Default for PenaltyRule {
    /// FKN = 10: stiff enough that the penalty penetration is well under 1 % of the Hertz
    /// approach on the refined ball meshes (docs/contact-penalty.md), while the penalty time
    /// step stays within a factor of about two of the element step.
    fn default() -> Self {
        PenaltyRule::Fkn { factor: 10.0 }
    }
}

impl PenaltyRule {
    /// Checks the factors are positive and finite; `field` names the rule in messages.
    pub fn validated(self, field: &str) -> Result<Self> {
        let ok = |v: f64| v.is_finite() && v > 0.0;
        match self {
            PenaltyRule::Fkn { factor } if !ok(factor) => Err(Error::invalid(
                format!("{field}.fkn"),
                factor,
                "FKN > 0, finite",
            )),
            PenaltyRule::Soft { scale, .. } if !(scale.is_finite() && scale >= 0.0) => Err(
                Error::invalid(format!("{field}.scale"), scale, "scale >= 0, finite"),
            ),
            PenaltyRule::Soft { dt_scale, .. } if !(dt_scale.is_finite() && dt_scale >= 0.0) => {
                Err(Error::invalid(
                    format!("{field}.dt_scale"),
                    dt_scale,
                    "dt_scale >= 0, finite",
                ))
            }
            PenaltyRule::Soft { scale, dt_scale } if scale == 0.0 && dt_scale == 0.0 => Err(
                Error::invalid(format!("{field}.scale"), scale, "scale > 0 or dt_scale > 0"),
            ),
            r => Ok(r),
        }
    }

    /// The geometric (time-step independent) part of the node stiffness, N/m.
    ///
    /// `youngs` E and `bulk` K in Pa, `area` A_i in m², `thickness` h_i in m, `volume` V_i in m³.
    pub fn geometric_stiffness(
        &self,
        youngs: f64,
        bulk: f64,
        area: f64,
        thickness: f64,
        volume: f64,
    ) -> f64 {
        match *self {
            PenaltyRule::Fkn { factor } => factor * youngs * area / thickness,
            PenaltyRule::Soft { scale, .. } => scale * bulk * area * area / volume,
        }
    }

    /// The time-step part of the node stiffness for effective mass `m_eff` (kg) and step `dt`
    /// (s), N/m; zero for [`PenaltyRule::Fkn`].
    pub fn time_step_stiffness(&self, m_eff: f64, dt: f64) -> f64 {
        match *self {
            PenaltyRule::Fkn { .. } => 0.0,
            PenaltyRule::Soft { dt_scale, .. } => dt_scale * m_eff / (dt * dt),
        }
    }
}

/// Normal contact force magnitude (N, ≥ 0) of a penalty spring `k` (N/m) with dashpot `c`
/// (N s/m) at signed gap `gap` (m, negative = penetration) opening at rate `gap_rate` (m/s).
///
/// Returns 0 when the surfaces are apart; the dashpot never pulls the surfaces together
/// (the total is clamped at zero, no adhesion).
#[inline]
pub fn normal_force(k: f64, c: f64, gap: f64, gap_rate: f64) -> f64 {
    if gap >= 0.0 {
        return 0.0;
    }
    (-k * gap - c * gap_rate).max(0.0)
}

/// Dashpot constant (N s/m) for a fraction `zeta` of critical damping of a spring `k` (N/m)
/// between effective mass `m_eff` (kg): c = 2 ζ sqrt(k m*).
#[inline]
pub fn damping_constant(zeta: f64, k: f64, m_eff: f64) -> f64 {
    2.0 * zeta * (k * m_eff).sqrt()
}

/// Largest central-difference step (s) for a penalty spring `k` (N/m) on effective mass
/// `m_eff` (kg) whose node also carries elements of highest frequency `omega_elem` (rad/s, the
/// Courant estimate 2 c / L of the elements under it):
/// Δt = min(2 / (ω_p + ω_e), 1 / ω_p) with ω_p = sqrt(k / m*).
///
/// Two limits, both about energy rather than bare linear stability:
/// - Spring and elements act in parallel on the node. With exact frequencies Weyl's inequality
///   bounds the pair by sqrt(ω_p² + ω_e²), but the Courant estimate is no upper bound on a
///   surface node's element frequency and friction makes the contact stiffness non-symmetric;
///   the sum ω_p + ω_e is the conservative combination (by √2 where ω_p = ω_e).
/// - The spring is one-sided: a node that enters and leaves it within a few steps (chatter at
///   the patch edge, coarse patches) rebounds with a speed that depends on where in a step it
///   touched. Averaged over that phase, a central-difference bounce gains energy once
///   ω_p Δt > 1 (+3 % of the node's kinetic energy per bounce at 1.1, +6.5 % at 1.2, +28 % at
///   1.6, doubling at 1.8) and stays within about 1 % below it; a cap of √2/ω_p would sit at
///   ω_p Δt = 1.27 after the 0.9 safety factor and pump energy.
#[inline]
pub fn stable_step(k: f64, m_eff: f64, omega_elem: f64) -> f64 {
    let wp = (k / m_eff).sqrt();
    (2.0 / (wp + omega_elem)).min(1.0 / wp)
}

/// Effective mass m1 m2 / (m1 + m2) of two nodes, kg (m2 = ∞ for a rigid wall: pass f64::INFINITY).
#[inline]
pub fn effective_mass(m1: f64, m2: f64) -> f64 {
    if m2.is_infinite() {
        m1
    } else {
        m1 * m2 / (m1 + m2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fkn_stiffness_is_pressure_per_penetration_times_area() {
        // ε = FKN E / h; k = ε A.
        let r = PenaltyRule::Fkn { factor: 0.1 };
        let k = r.geometric_stiffness(200e9, 0.0, 4e-6, 2e-3, 0.0);
        assert!((k - 0.1 * 200e9 / 2e-3 * 4e-6).abs() < 1e-6 * k);
    }

    #[test]
    fn soft_rule_takes_the_larger_of_its_two_terms() {
        let r = PenaltyRule::Soft {
            scale: 0.1,
            dt_scale: 0.05,
        };
        let kg = r.geometric_stiffness(0.0, 100e9, 1e-6, 0.0, 1e-9);
        assert!((kg - 0.1 * 100e9 * 1e-12 / 1e-9).abs() < 1e-3);
        let kt = r.time_step_stiffness(2e-3, 1e-7);
        assert!((kt - 0.05 * 2e-3 / 1e-14).abs() < 1e-3 * kt);
        // The time-step term alone is always stable: ω Δt = sqrt(0.05) ≪ 2.
        assert!(stable_step(kt, 2e-3, 0.0) > 1e-7);
    }

    #[test]
    fn no_force_when_open_and_no_adhesion_when_separating_fast() {
        assert_eq!(normal_force(1e6, 10.0, 1e-6, -1.0), 0.0);
        assert!((normal_force(1e6, 0.0, -1e-6, 0.0) - 1.0).abs() < 1e-12);
        // Fast separation: the dashpot would pull; clamped at zero.
        assert_eq!(normal_force(1e6, 1e3, -1e-6, 10.0), 0.0);
    }

    #[test]
    fn stable_step_adds_the_element_frequency_and_damping_is_critical() {
        let (k, m): (f64, f64) = (4e6, 1e-2);
        let wp = (k / m).sqrt();
        // A lone one-sided spring: ω_p Δt = 1, half the linear limit 2/ω_p.
        assert!((stable_step(k, m, 0.0) - 1.0 / wp).abs() < 1e-15 / wp);
        // Elements three times stiffer than the spring: 2/(ω_p + ω_e) controls, below the
        // Weyl bound 2/sqrt(ω_p² + ω_e²) of the two in parallel.
        let both = stable_step(k, m, 3.0 * wp);
        assert!((both - 0.5 / wp).abs() < 1e-15 / wp);
        assert!(both < 2.0 / (10.0f64.sqrt() * wp));
        // Critical damping of a single oscillator: c = 2 sqrt(k m).
        assert!((damping_constant(1.0, k, m) - 2.0 * (k * m).sqrt()).abs() < 1e-9);
        assert_eq!(effective_mass(3.0, f64::INFINITY), 3.0);
        assert!((effective_mass(2.0, 2.0) - 1.0).abs() < 1e-15);
    }

    /// Mean kinetic-energy ratio after / before one central-difference bounce of a mass on
    /// a one-sided spring at ω_p Δt = `w_dt`, over 64 phases of the first touch in a step.
    fn mean_bounce_gain(w_dt: f64) -> f64 {
        let (k, m, v0): (f64, f64, f64) = (1.0, 1.0, -1.0);
        let dt = w_dt / f64::sqrt(k / m);
        let phases = 64;
        let mut sum = 0.0;
        for p in 0..phases {
            // Half-step velocity v, position x at whole steps; touch x = 0 falls within the
            // first step at the phase's share of it.
            let (mut x, mut v) = (-(p as f64 + 0.5) / phases as f64 * v0 * dt, v0);
            let mut touched = false;
            loop {
                x += dt * v;
                let f = if x < 0.0 { -k * x } else { 0.0 };
                touched |= x < 0.0;
                v += dt * f / m;
                if touched && x > 0.0 && v > 0.0 {
                    break;
                }
            }
            sum += (v / v0).powi(2);
        }
        sum / phases as f64
    }

    #[test]
    fn a_one_sided_bounce_gains_energy_only_above_the_cap() {
        let gain = |w: f64| mean_bounce_gain(w) - 1.0;
        // At and below the cap ω_p Δt = 1 a bounce keeps its energy to about 1 %.
        for w in [0.3, 0.6, 0.9, 1.0] {
            assert!(gain(w).abs() < 0.015, "ω_p Δt = {w}: {}", gain(w));
        }
        // Above it the bounce pumps energy: +3 %, +6.5 %, +28 % and doubling at 1.1, 1.2,
        // 1.6 and 1.8 (the figures of `stable_step`'s doc).
        for (w, expected) in [(1.1, 0.03), (1.2, 0.065), (1.6, 0.28), (1.8, 1.0)] {
            let g = gain(w);
            println!("ω_p Δt = {w}: gain {g}");
            assert!((g / expected - 1.0).abs() < 0.2, "ω_p Δt = {w}: {g}");
        }
    }

    #[test]
    fn bad_factors_are_errors_naming_the_field() {
        let e = PenaltyRule::Fkn { factor: -1.0 }
            .validated("contact")
            .unwrap_err()
            .to_string();
        assert!(e.contains("contact.fkn") && e.contains("-1"), "{e}");
        assert!(PenaltyRule::Soft {
            scale: 0.0,
            dt_scale: 0.0
        }
        .validated("c")
        .is_err());
        assert!(PenaltyRule::Fkn { factor: f64::NAN }
            .validated("c")
            .is_err());
    }
}
