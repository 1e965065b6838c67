//! The properties of a contact pair that laws read their default parameters from.

use crate::analytic::body::Body;
use crate::analytic::hertz::HertzPair;

/// Effective elastic, plastic and inertial properties of two bodies in contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPair {
    /// Effective modulus E*, radius R* and mass m* (Pa, m, kg).
    pub hertz: HertzPair,
    /// Effective shear modulus G* = 1/((2 − ν₁)/G₁ + (2 − ν₂)/G₂), Pa (Mindlin).
    pub shear_modulus: f64,
    /// Yield strength σ_s of the softer body (lower σ_s), Pa; infinite if neither yields.
    pub yield_strength: f64,
    /// Yield pressure σ_p = (1 + π/2) σ_s of the softer body, Pa (the paper's eq. 9).
    pub yield_pressure: f64,
    /// Young's modulus of the softer body, Pa.
    pub youngs: f64,
    /// Tangent modulus E_t (slope of stress against total strain after yield) of the softer
    /// body, Pa.
    pub tangent: f64,
    /// Poisson's ratio of the softer body.
    pub poisson: f64,
    /// Friction coefficient μ of the pair.
    pub mu: f64,
}

impl ContactPair {
    /// The pair of two bodies (ball–ball or ball–half-space) with friction coefficient μ.
    pub fn between(b1: &Body, b2: &Body, mu: f64) -> Self {
        let shear = |b: &Body| {
            b.material()
                .map_or(0.0, |m| (2.0 - m.nu) / m.shear_modulus())
        };
        let soft = match (b1.material(), b2.material()) {
            (Some(a), Some(b)) if b.yield_strength < a.yield_strength => Some(*b),
            (Some(a), _) => Some(*a),
            (None, m) => m.copied(),
        };
        let (youngs, tangent, poisson, yield_strength) = soft
            .map_or((f64::INFINITY, f64::INFINITY, 0.0, f64::INFINITY), |m| {
                (m.youngs, m.tangent, m.nu, m.yield_strength)
            });
        ContactPair {
            hertz: HertzPair::between(b1, b2),
            shear_modulus: 1.0 / (shear(b1) + shear(b2)),
            yield_strength,
            yield_pressure: b1.yield_pressure().min(b2.yield_pressure()),
            youngs,
            tangent,
            poisson,
            mu,
        }
    }
}
