//! The registry of hardening laws: the one enum a part's material stores, its scene keys,
//! and the dispatch from a stored law to code compiled for that law's type.
//!
//! Registering a law: a variant of [`Law`], its name in [`LAW_NAMES`], its keys and
//! constructor in [`Law::from_keys`], and its arm in [`Law::with`].

use super::{bilinear::Bilinear, hardening::Hardening, johnson_cook::JohnsonCook, power::Power};
use crate::error::{Error, Result};

/// The names of the laws a scene's `hardening = { law = ... }` selects.
pub const LAW_NAMES: [&str; 2] = ["power", "johnson-cook"];

/// A hardening law with its parameters (SI units).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(tag = "law", rename_all = "kebab-case")]
pub enum Law {
    /// Linear hardening (bilinear stress-strain curve), from `yield` and `tangent`.
    Bilinear(Bilinear),
    /// Ludwik/Swift power law.
    Power(Power),
    /// Johnson-Cook with its strain-rate term.
    JohnsonCook(JohnsonCook),
    /// Linear hardening that keeps history (tests of the history seam only).
    #[cfg(test)]
    Counting(super::counting::Counting),
}

/// Code generic over the hardening law, run by [`Law::with`] for the stored law's type.
pub trait LawVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the concrete law.
    fn visit<H: Hardening>(self, law: &H) -> Self::Output;
}

impl Law {
    /// The keys of law `name` in a scene's hardening table (besides `law`), or `None` for an
    /// unknown name.
    pub fn keys(name: &str) -> Option<&'static [&'static str]> {
        match name {
            "power" => Some(&["K", "n"]),
            "johnson-cook" => Some(&["A", "B", "n", "C", "rate0"]),
            _ => None,
        }
    }

    /// The law `name` from its keys: `get(key)` reads one (`None` if absent), `path` names
    /// the table in messages, `yield0` is the material's initial yield strength (Pa; the
    /// power law's σ_0). Every key is required.
    pub fn from_keys(
        name: &str,
        path: &str,
        yield0: f64,
        get: &mut dyn FnMut(&str) -> Result<Option<f64>>,
    ) -> Result<Law> {
        let mut need = |key: &str| -> Result<f64> {
            get(key)?.ok_or_else(|| {
                Error::Parse(format!(
                    "missing required key {path}.{key} (law \"{name}\")"
                ))
            })
        };
        match name {
            "power" => Ok(Law::Power(
                Power {
                    sigma0: yield0,
                    k: need("K")?,
                    n: need("n")?,
                }
                .validated(path)?,
            )),
            "johnson-cook" => Ok(Law::JohnsonCook(
                JohnsonCook {
                    a: need("A")?,
                    b: need("B")?,
                    n: need("n")?,
                    c: need("C")?,
                    rate0: need("rate0")?,
                }
                .validated(path)?,
            )),
            _ => Err(Error::invalid(
                format!("{path}.law"),
                format!("\"{name}\""),
                format!("one of {}", LAW_NAMES.join(", ")),
            )),
        }
    }

    /// The initial yield strength σ_y(0) at the reference rate, Pa.
    pub fn initial_yield(&self) -> f64 {
        self.with(InitialYield)
    }

    /// True when the law's flow stress does not depend on the strain rate
    /// ([`Hardening::rate_independent`]).
    pub fn rate_independent(&self) -> bool {
        self.with(RateIndependent)
    }

    /// History values the law keeps per integration point ([`Hardening::HISTORY`]).
    pub fn history_per_point(&self) -> usize {
        self.with(HistoryPerPoint)
    }

    /// Runs `v` with this law's concrete type (one match, here, for every generic caller).
    #[inline(always)]
    pub fn with<V: LawVisitor>(&self, v: V) -> V::Output {
        match self {
            Law::Bilinear(h) => v.visit(h),
            Law::Power(h) => v.visit(h),
            Law::JohnsonCook(h) => v.visit(h),
            #[cfg(test)]
            Law::Counting(h) => v.visit(h),
        }
    }
}

/// [`Law::initial_yield`] as a visitor.
struct InitialYield;

impl LawVisitor for InitialYield {
    type Output = f64;
    fn visit<H: Hardening>(self, law: &H) -> f64 {
        law.static_yield(0.0)
    }
}

/// [`Law::rate_independent`] as a visitor.
struct RateIndependent;

impl LawVisitor for RateIndependent {
    type Output = bool;
    fn visit<H: Hardening>(self, law: &H) -> bool {
        law.rate_independent()
    }
}

/// [`Law::history_per_point`] as a visitor.
struct HistoryPerPoint;

impl LawVisitor for HistoryPerPoint {
    type Output = usize;
    fn visit<H: Hardening>(self, _law: &H) -> usize {
        H::HISTORY
    }
}
