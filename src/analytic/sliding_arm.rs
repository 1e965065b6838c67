//! The angular impulse an elastic ball takes about its centre while it slides throughout an
//! impact on a rigid flat. The rigid-body Coulomb exchange gives L = J_t R; a Hertz ball falls
//! short of it on two counts, each first order in the contact's size over R:
//!
//! - The friction acts on the contact plane, R − δ from the centre. Weighted by the Hertz
//!   force over the impact (x = δ/δ_max, F ∝ x^{3/2}, dt ∝ dx/√(1 − x^{5/2})), ⟨δ⟩ = c_δ δ_max
//!   with c_δ = B(7/5, 1/2)/2 = 0.8176.
//! - The normal pressure has a moment against the friction's. A tangential traction q lifts
//!   a half-space's surface antisymmetrically, u_z = −(1 − 2ν)/(4πG) ∫ q (y − y')/ρ² dA'
//!   (Johnson, *Contact Mechanics*, 1985, eq. 3.86), and the pressure changes by p₁ to keep
//!   the flat's contact: (1/π) ∫ p₁/ρ dA' = (β/π) ∫ μ p (y − y')/ρ² dA', β = (1 − 2ν)/(2(1 −
//!   ν)) Dundurs' constant of a ball on a rigid flat. Under Hertz's pressure the right side is
//!   β μ times the radial displacement's shape, (2/3) p₀ a² (y/r²)(1 − (1 − r²/a²)^{3/2}). The
//!   reciprocal theorem with the tilted flat punch (pressure (2/π) y/√(a² − r²) for unit
//!   tilt) gives the moment ∫ y p₁ dA = β μ p₀ a³ = (3/(2π)) β μ a P, first order in βμ; a
//!   shift e of the contact circle adds P e and takes (4/3) E* a³ e/R, which cancel. Weighted
//!   by the force, ⟨a⟩ = a_max B(6/5, 1/2)/2, so c_β = (3/(2π)) B(6/5, 1/2)/2 = 0.4276.
//!
//! L/(J_t R) = 1 − c_δ δ_max/R − c_β β a_max/R, a_max = √(R δ_max) on a flat.

use crate::error::{Error, Result};
use std::f64::consts::PI;

/// Euler's beta function B(a, b) = Γ(a)Γ(b)/Γ(a + b) for a, b > 0.
fn beta_fn(a: f64, b: f64) -> f64 {
    libm::tgamma(a) * libm::tgamma(b) / libm::tgamma(a + b)
}

/// c_δ: the force-weighted mean approach of a Hertz impact over its largest, -.
pub fn arm_depth_coefficient() -> f64 {
    beta_fn(1.4, 0.5) / 2.0
}

/// c_β: the pressure moment's share of L per unit β a_max/R, -.
pub fn pressure_moment_coefficient() -> f64 {
    3.0 / (2.0 * PI) * beta_fn(1.2, 0.5) / 2.0
}

/// Dundurs' β = (1 − 2ν)/(2(1 − ν)) of an elastic body of Poisson's ratio `nu` (-) on a rigid
/// one, -.
pub fn dundurs_beta_on_rigid(nu: f64) -> f64 {
    (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))
}

/// L/(J_t R), -: the angular impulse about its centre of an elastic ball of radius `radius`
/// (m, > 0) and Poisson's ratio `nu` (-, in (−1, 0.5]) that slides throughout an impact on a
/// rigid flat with largest approach `delta_max` (m, ≥ 0), over the rigid-body Coulomb one.
/// First order in δ_max/R and √(δ_max/R) (the Hertz contact), and in μβ.
///
/// Errors: a radius, approach or Poisson's ratio outside its range (one line naming it).
pub fn sliding_arm_ratio(delta_max: f64, radius: f64, nu: f64) -> Result<f64> {
    if !(radius > 0.0 && radius.is_finite()) {
        return Err(Error::invalid("radius", radius, "> 0 m"));
    }
    if !(delta_max >= 0.0 && delta_max < radius) {
        return Err(Error::invalid("delta_max", delta_max, "0 m to the radius"));
    }
    if !(nu > -1.0 && nu <= 0.5) {
        return Err(Error::invalid("nu", nu, "-1 (excluded) to 0.5"));
    }
    let depth = delta_max / radius;
    Ok(1.0
        - arm_depth_coefficient() * depth
        - pressure_moment_coefficient() * dundurs_beta_on_rigid(nu) * depth.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::hertz::HertzPair;
    use crate::analytic::quadrature::integrate;

    /// ∫ F g(δ) dt / ∫ F dt over a Hertz impact, from δ(t) (time quadrature, not the beta
    /// function).
    fn force_weighted(g: impl Fn(f64) -> f64) -> f64 {
        let pair = HertzPair::new(1e11, 0.01, 0.03);
        let v = 1.0;
        let tc = pair.contact_duration(v);
        let num = integrate(
            |t| pair.force(pair.approach_at(v, t)) * g(pair.approach_at(v, t)),
            0.0,
            tc,
            400,
        );
        let den = integrate(|t| pair.force(pair.approach_at(v, t)), 0.0, tc, 400);
        num / den
    }

    #[test]
    fn the_coefficients_are_the_force_weighted_means_of_a_hertz_impact() {
        let pair = HertzPair::new(1e11, 0.01, 0.03);
        let dm = pair.max_approach(1.0);
        let depth = force_weighted(|d| d / dm);
        assert!((depth - arm_depth_coefficient()).abs() < 1e-6, "{depth}");
        assert!((arm_depth_coefficient() - 0.8176).abs() < 1e-4);
        let radius = force_weighted(|d| (d / dm).sqrt());
        let c_beta = 3.0 / (2.0 * PI) * radius;
        assert!(
            (c_beta - pressure_moment_coefficient()).abs() < 1e-6,
            "{c_beta}"
        );
        assert!((pressure_moment_coefficient() - 0.4276).abs() < 1e-4);
    }

    #[test]
    fn the_pressure_moment_is_the_tilted_punch_integral() {
        // ∫ p* w₁ dA with p* = (2/π) y/√(1 − r²), w₁ = (2/3)(y/r²)(1 − (1 − r²)^{3/2}) (a = p₀ =
        // βμ = 1): the angle gives π, the radius 2 ∫ (1 − (1 − r²)^{3/2}) r/√(1 − r²) dr · (2/3)
        // · (2/π) · π / 2 = 1, so M = βμ p₀ a³ and M/P = 3/(2π) with P = (2/3)π.
        let radial = integrate(
            |s: f64| {
                // r = sin θ removes the edge's inverse square root.
                let r = s.sin();
                (1.0 - (1.0 - r * r).powf(1.5)) * r
            },
            0.0,
            PI / 2.0,
            50,
        );
        let moment = (2.0 / PI) * (2.0 / 3.0) * PI * radial;
        assert!((moment - 1.0).abs() < 1e-9, "{moment}");
    }

    #[test]
    fn a_rigid_limit_and_an_incompressible_ball_lose_the_terms() {
        assert_eq!(sliding_arm_ratio(0.0, 0.01, 0.3).unwrap(), 1.0);
        assert_eq!(dundurs_beta_on_rigid(0.5), 0.0);
        let r = sliding_arm_ratio(1e-5, 0.01, 0.5).unwrap();
        assert!((r - (1.0 - arm_depth_coefficient() * 1e-3)).abs() < 1e-15);
        for (d, rad, nu, field) in [
            (1e-5, 0.0, 0.3, "radius"),
            (-1e-5, 0.01, 0.3, "delta_max"),
            (1e-5, 0.01, 0.6, "nu"),
        ] {
            let e = sliding_arm_ratio(d, rad, nu).unwrap_err().to_string();
            assert!(e.contains(field), "{e}");
        }
    }
}
