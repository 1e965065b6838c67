//! Law parameters: their description (key, unit, range, default from the pair) and the
//! resolved values a law is built from.

use super::pair::ContactPair;
use crate::error::{Error, Result};

/// One parameter of a law.
#[derive(Debug, Clone, Copy)]
pub struct ParamSpec {
    /// Key used by `--param KEY=VALUE`.
    pub key: &'static str,
    /// SI unit, e.g. `Pa`, `N/m`, `-`.
    pub unit: &'static str,
    /// One-line meaning, with the default's origin.
    pub doc: &'static str,
    /// Smallest allowed value (inclusive).
    pub min: f64,
    /// Largest allowed value (inclusive).
    pub max: f64,
    /// Default for a given pair.
    pub default: fn(&ContactPair) -> f64,
}

/// Resolved parameter values of one law, in the order of its [`ParamSpec`] list.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    values: Vec<(&'static str, f64)>,
}

impl Params {
    /// Resolves `specs` for `pair`: defaults, replaced by `overrides` (key, value). Errors
    /// name the law and key: an unknown key (listing the allowed ones), a value that is not
    /// finite or outside [min, max].
    pub fn resolve(
        law: &str,
        specs: &[ParamSpec],
        overrides: &[(String, f64)],
        pair: &ContactPair,
    ) -> Result<Params> {
        for (key, _) in overrides {
            if !specs.iter().any(|s| s.key == key) {
                let allowed: Vec<&str> = specs.iter().map(|s| s.key).collect();
                return Err(Error::invalid(
                    format!("{law} parameter"),
                    key,
                    if allowed.is_empty() {
                        "none (this law has no parameters)".to_string()
                    } else {
                        format!("one of {}", allowed.join(", "))
                    },
                ));
            }
        }
        let mut values = Vec::with_capacity(specs.len());
        for s in specs {
            let v = overrides
                .iter()
                .rev()
                .find(|(k, _)| k == s.key)
                .map_or_else(|| (s.default)(pair), |(_, v)| *v);
            if !(v.is_finite() && v >= s.min && v <= s.max) {
                return Err(Error::invalid(
                    format!("{law}.{}", s.key),
                    v,
                    format!("{} <= {} <= {} {}, finite", s.min, s.key, s.max, s.unit),
                ));
            }
            values.push((s.key, v));
        }
        Ok(Params { values })
    }

    /// The value of `key`; panics only on a key the law itself did not declare (a
    /// programming error inside the law's file, never user input).
    pub fn get(&self, key: &str) -> f64 {
        self.values
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| *v)
            .unwrap_or_else(|| panic!("law parameter {key} is not declared"))
    }

    /// Whether the `tension` parameter ([`TENSION`]) lets the force pull (a value ≥ 0.5);
    /// panics, as [`Params::get`], for a law that does not declare it.
    pub fn tension(&self) -> bool {
        self.get("tension") >= 0.5
    }

    /// (key, value) pairs in declaration order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        self.values.iter().copied()
    }
}

/// Coefficient of restitution a damped law is tuned to, default 0.8.
pub const RESTITUTION: ParamSpec = ParamSpec {
    key: "e",
    unit: "-",
    doc: "coefficient of restitution the damping is set from (default 0.8)",
    min: 0.01,
    max: 1.0,
    default: |_| 0.8,
};

/// 1: the force may pull and the contact ends at δ = 0 (the DEM codes' default); 0: the
/// force is clipped at 0 and the contact ends when it first reaches 0.
pub const TENSION: ParamSpec = ParamSpec {
    key: "tension",
    unit: "-",
    doc: "1: attractive force allowed, contact ends at delta = 0 (default); 0: force >= 0, ends at F = 0",
    min: 0.0,
    max: 1.0,
    default: |_| 1.0,
};

/// Linear stiffness k_n, N/m: by default the secant of a Hertz impact at 1 m/s, the
/// characteristic-velocity rule of LIGGGHTS `hooke`:
/// k_n = (16/15) √R* E* (15 m* v_c² / (16 √R* E*))^{1/5}, v_c = 1 m/s.
pub const LINEAR_STIFFNESS: ParamSpec = ParamSpec {
    key: "k",
    unit: "N/m",
    doc: "normal stiffness (default: LIGGGHTS hooke's rule with characteristic velocity 1 m/s)",
    min: 1e-6,
    max: 1e15,
    default: |p| {
        let h = p.hertz;
        let c = h.radius.sqrt() * h.modulus;
        16.0 / 15.0 * c * (15.0 * h.mass / (16.0 * c)).powf(0.2)
    },
};
