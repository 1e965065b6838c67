//! Coulomb friction with regularised stick: an elastic tangential spring and a return mapping
//! onto the friction cone |F_t| ≤ μ F_n.
//!
//! Stick uses the static coefficient μ_s; once a node slides, the limit is the dynamic μ_d until
//! a step ends inside the μ_d cone again. The slip split is the classical elastoplastic one:
//! the trial force F* = F_t^old − k_t Δu_t; when |F*| exceeds the limit the force is returned
//! radially to the cone, and the slip Δu_p = (|F*| − |F_t|)/k_t dissipates |F_t| Δu_p. In gross
//! sliding this is exactly μ_d F_n times the slip.

use crate::error::{Error, Result};
use crate::fe::tensor::{norm, scale, sub};

/// Coulomb coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoulombFriction {
    /// Static coefficient μ_s (≥ μ_d): limit while sticking.
    pub mu_static: f64,
    /// Dynamic coefficient μ_d (≥ 0): limit while sliding.
    pub mu_dynamic: f64,
}

impl CoulombFriction {
    /// Equal static and dynamic coefficients (the paper's single μ).
    pub fn new(mu: f64) -> Self {
        CoulombFriction {
            mu_static: mu,
            mu_dynamic: mu,
        }
    }

    /// Checks 0 ≤ μ_d ≤ μ_s, finite; `field` names the friction in messages.
    pub fn validated(self, field: &str) -> Result<Self> {
        if !(self.mu_dynamic.is_finite() && self.mu_dynamic >= 0.0) {
            return Err(Error::invalid(
                format!("{field}.mu"),
                self.mu_dynamic,
                "mu >= 0, finite",
            ));
        }
        if !(self.mu_static.is_finite() && self.mu_static >= self.mu_dynamic) {
            return Err(Error::invalid(
                format!("{field}.mu_static"),
                self.mu_static,
                "mu_static >= mu, finite",
            ));
        }
        Ok(self)
    }
}

/// Tangential state of one contact node carried between steps.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StickState {
    /// Tangential force on the node, N (in the current tangent plane).
    pub force: [f64; 3],
    /// Whether the node slid in its last step.
    pub sliding: bool,
}

/// One return-mapping step: new tangential force (N) and the energy (J) it dissipated.
///
/// `state.force` must already lie in the current tangent plane; `slip` (m) is the tangential
/// displacement of the node relative to the opposing surface over the step; `kt` (N/m) the
/// tangential spring; `normal_force` (N, ≥ 0) the current normal force.
pub fn return_map(
    state: &mut StickState,
    slip: [f64; 3],
    kt: f64,
    normal_force: f64,
    c: CoulombFriction,
) -> f64 {
    let trial = sub(state.force, scale(kt, slip));
    let t = norm(trial);
    let limit = if state.sliding {
        c.mu_dynamic
    } else {
        c.mu_static
    } * normal_force;
    if t <= limit {
        state.force = trial;
        state.sliding = false;
        return 0.0;
    }
    let f = c.mu_dynamic * normal_force;
    state.force = if t > 0.0 {
        scale(f / t, trial)
    } else {
        [0.0; 3]
    };
    state.sliding = true;
    f * (t - f) / kt
}

/// Elastic energy stored in the stick spring, J.
pub fn stick_energy(state: &StickState, kt: f64) -> f64 {
    let f = norm(state.force);
    0.5 * f * f / kt
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_slip_sticks_elastically() {
        let mut s = StickState::default();
        let d = return_map(
            &mut s,
            [1e-6, 0.0, 0.0],
            1e6,
            10.0,
            CoulombFriction::new(0.2),
        );
        assert_eq!(d, 0.0);
        assert!(!s.sliding);
        assert!((s.force[0] + 1.0).abs() < 1e-12);
    }

    #[test]
    fn gross_sliding_dissipates_mu_fn_times_slip() {
        // Accumulate a long slide in small increments: dissipation → μ F_n × slip (the elastic
        // pre-slip μ F_n / k_t is stored, not dissipated).
        let (kt, fnorm, mu) = (1e8, 50.0, 0.3);
        let c = CoulombFriction::new(mu);
        let mut s = StickState::default();
        let (du, n) = (1e-6, 1000);
        let mut d = 0.0;
        for _ in 0..n {
            d += return_map(&mut s, [0.0, du, 0.0], kt, fnorm, c);
        }
        let total = du * n as f64;
        let elastic = mu * fnorm / kt;
        let expect = mu * fnorm * (total - elastic);
        assert!(s.sliding);
        assert!((norm(s.force) - mu * fnorm).abs() < 1e-9);
        assert!((d - expect).abs() < 1e-9 * expect, "{d} vs {expect}");
        // Energy identity of the return mapping: dissipated + stored = work of the slip,
        // μ F_n (total − elastic/2).
        let work = mu * fnorm * (total - 0.5 * elastic);
        assert!((d + stick_energy(&s, kt) - work).abs() < 1e-9 * work);
    }

    #[test]
    fn static_threshold_then_dynamic_limit() {
        let c = CoulombFriction {
            mu_static: 0.5,
            mu_dynamic: 0.3,
        };
        let mut s = StickState::default();
        // 0.4 F_n: below μ_s, sticks.
        return_map(&mut s, [4e-7, 0.0, 0.0], 1e6, 1.0, c);
        assert!(!s.sliding);
        // 0.6 F_n: breaks loose and drops to μ_d.
        return_map(&mut s, [2e-7, 0.0, 0.0], 1e6, 1.0, c);
        assert!(s.sliding && (norm(s.force) - 0.3).abs() < 1e-12);
        // Reversing slip unloads elastically inside the μ_d cone: sticks again.
        return_map(&mut s, [-1e-7, 0.0, 0.0], 1e6, 1.0, c);
        assert!(!s.sliding && (norm(s.force) - 0.2).abs() < 1e-12);
    }

    #[test]
    fn invalid_coefficients_are_named() {
        let e = CoulombFriction {
            mu_static: 0.1,
            mu_dynamic: 0.2,
        }
        .validated("contact")
        .unwrap_err();
        assert!(e.to_string().contains("contact.mu_static"));
        assert!(CoulombFriction::new(-0.1).validated("c").is_err());
    }
}
