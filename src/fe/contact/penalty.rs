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

/// Largest central-difference step (s) allowed by a penalty spring `k` (N/m) on effective mass
/// `m_eff` (kg): Δt ≤ 1/ω = sqrt(m*/k), half the linear stability limit 2/ω of a lone spring.
///
/// Why half: linear stability is not enough for a penalty contact. A node enters and leaves
/// the spring between steps, so each contact event starts at a penetration of order v Δt and
/// creates or destroys energy of order ½ k (v Δt)² = ½ m v² (ω Δt)², comparable to the
/// node's own kinetic energy when ω Δt approaches 2. Loosely restrained surface nodes (the
/// one-point hex's hourglass modes) then rattle and pump energy into the model. Measured on
/// the default scene's graded quarter ball at 0.71× the default mesh density (one-point,
/// FKN = 10): with the former limit √2 sqrt(m*/k) (ω Δt = 1.27 after the 0.9 safety factor)
/// the run created 10 % of the impact energy (e = 0.20 instead of 0.334); at ω Δt ≤ 1.0 the
/// energy error is below 1e-4 and e = 0.3341, 0.3340 at two smaller steps
/// (docs/performance.md, "Stability of the contact step").
pub fn stable_step(k: f64, m_eff: f64) -> f64 {
    (m_eff / k).sqrt()
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
        assert!(stable_step(kt, 2e-3) > 1e-7);
    }

    #[test]
    fn no_force_when_open_and_no_adhesion_when_separating_fast() {
        assert_eq!(normal_force(1e6, 10.0, 1e-6, -1.0), 0.0);
        assert!((normal_force(1e6, 0.0, -1e-6, 0.0) - 1.0).abs() < 1e-12);
        // Fast separation: the dashpot would pull; clamped at zero.
        assert_eq!(normal_force(1e6, 1e3, -1e-6, 10.0), 0.0);
    }

    #[test]
    fn stable_step_is_below_the_lone_spring_limit_and_damps_critically() {
        let (k, m) = (4e6, 1e-2);
        assert!(stable_step(k, m) < 2.0 * (m / k).sqrt());
        // Critical damping of a single oscillator: c = 2 sqrt(k m).
        assert!((damping_constant(1.0, k, m) - 2.0 * (k * m).sqrt()).abs() < 1e-9);
        assert_eq!(effective_mass(3.0, f64::INFINITY), 3.0);
        assert!((effective_mass(2.0, 2.0) - 1.0).abs() < 1e-15);
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
