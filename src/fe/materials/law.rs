//! The dispatch from a stored hardening law ([`Law`], a constant of the material layer) to
//! kernel code compiled for that law's type ([`LawDispatch::with`]), what the kernels say of
//! a law through it, and whether a material's response has a time scale.
//!
//! Registering a law: its parameters, its name and keys in [`crate::material::hardening`],
//! its kernel (a [`Hardening`] implementation) in a file of its own here, and its arm in
//! [`LawDispatch::with`].

use super::hardening::Hardening;
pub use crate::material::hardening::{Law, LAW_NAMES};
use crate::material::Material;

/// Code generic over the hardening law, run by [`LawDispatch::with`] for the stored law's type.
pub trait LawVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the concrete law.
    fn visit<H: Hardening>(self, law: &H) -> Self::Output;
}

/// The kernel side of a stored [`Law`]: the one match from the enum to its concrete type,
/// and what the law's [`Hardening`] implementation says of it.
pub trait LawDispatch {
    /// Runs `v` with this law's concrete type (one match, here, for every generic caller).
    fn with<V: LawVisitor>(&self, v: V) -> V::Output;

    /// The initial yield strength σ_y(0) at the reference rate, Pa.
    fn initial_yield(&self) -> f64;

    /// True when the law's flow stress does not depend on the strain rate
    /// ([`Hardening::rate_independent`]).
    fn rate_independent(&self) -> bool;

    /// History values the law keeps per integration point ([`Hardening::HISTORY`]).
    fn history_per_point(&self) -> usize;
}

impl LawDispatch for Law {
    #[inline(always)]
    fn with<V: LawVisitor>(&self, v: V) -> V::Output {
        match self {
            Law::Bilinear(h) => v.visit(h),
            Law::Power(h) => v.visit(h),
            Law::JohnsonCook(h) => v.visit(h),
            #[cfg(test)]
            Law::Counting(h) => v.visit(h),
        }
    }

    fn initial_yield(&self) -> f64 {
        self.with(InitialYield)
    }

    fn rate_independent(&self) -> bool {
        self.with(RateIndependent)
    }

    fn history_per_point(&self) -> usize {
        self.with(HistoryPerPoint)
    }
}

/// Whether `material`'s response has no time scale: no hardening law, or one without a
/// strain-rate term ([`LawDispatch::rate_independent`]).
pub fn rate_independent(material: &Material) -> bool {
    material.hardening.is_none_or(|law| law.rate_independent())
}

/// [`LawDispatch::initial_yield`] as a visitor.
struct InitialYield;

impl LawVisitor for InitialYield {
    type Output = f64;
    fn visit<H: Hardening>(self, law: &H) -> f64 {
        law.static_yield(0.0)
    }
}

/// [`LawDispatch::rate_independent`] as a visitor.
struct RateIndependent;

impl LawVisitor for RateIndependent {
    type Output = bool;
    fn visit<H: Hardening>(self, law: &H) -> bool {
        law.rate_independent()
    }
}

/// [`LawDispatch::history_per_point`] as a visitor.
struct HistoryPerPoint;

impl LawVisitor for HistoryPerPoint {
    type Output = usize;
    fn visit<H: Hardening>(self, _law: &H) -> usize {
        H::HISTORY
    }
}
