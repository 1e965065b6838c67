//! The scene's `[laws]` table: contact laws `twoball run` integrates beside FE and the
//! three-phase model, on the same balls and speeds.
//!
//! ```toml
//! [laws]
//! compare = ["hertz", "thornton"]    # normal laws (`twoball laws` lists them)
//! tangential = "coulomb"             # optional, default coulomb
//! [laws.params.thornton]             # optional, per law: KEY = value in SI units
//! p_y = 5e8
//! ```

use super::reader::{show, Reader};
use crate::analytic::laws::Registry;
use crate::error::{Error, Result};
use serde::Serialize;
use toml::Value;

pub(crate) const LAWS_KEYS: [&str; 3] = ["compare", "tangential", "params"];

/// One normal law to compare, with its parameter overrides.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComparedLaw {
    /// Registry name of the normal law.
    pub name: String,
    /// Parameter overrides (key, value in the parameter's SI unit), as `laws run --param`.
    pub params: Vec<(String, f64)>,
}

/// The laws a scene compares (empty: none).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LawComparison {
    /// Normal laws, in the scene's order.
    pub laws: Vec<ComparedLaw>,
    /// Tangential law used with each of them.
    pub tangential: String,
}

impl Default for LawComparison {
    fn default() -> Self {
        LawComparison {
            laws: Vec::new(),
            tangential: "coulomb".into(),
        }
    }
}

/// Reads the optional `[laws]` table; names and parameter keys are checked against the
/// built-in registry (values are range-checked when the laws are built for the balls).
pub(crate) fn read_laws(r: Option<Reader>) -> Result<LawComparison> {
    let Some(r) = r else {
        return Ok(LawComparison::default());
    };
    r.only(&LAWS_KEYS)?;
    let registry = Registry::builtin();
    let names: Vec<&str> = registry.normal.iter().map(|s| s.name).collect();
    let compare = match r.raw("compare") {
        None => Vec::new(),
        Some(Value::Array(items)) => items
            .iter()
            .enumerate()
            .map(|(i, v)| match v {
                Value::String(s) if names.contains(&s.as_str()) => Ok(s.clone()),
                other => Err(Error::invalid(
                    format!("{}[{i}]", r.key_path("compare")),
                    show(other),
                    format!("one of {}", names.join(", ")),
                )),
            })
            .collect::<Result<Vec<_>>>()?,
        Some(other) => {
            return Err(Error::invalid(
                r.key_path("compare"),
                show(other),
                "an array of law names",
            ))
        }
    };
    let tangential = r.string("tangential")?.unwrap_or("coulomb").to_string();
    registry.tangential(&tangential).map_err(|_| {
        let t: Vec<&str> = registry.tangential.iter().map(|s| s.name).collect();
        Error::invalid(
            r.key_path("tangential"),
            format!("\"{tangential}\""),
            format!("one of {}", t.join(", ")),
        )
    })?;
    let params = r.table("params")?;
    if let Some(p) = &params {
        let listed: Vec<&str> = compare.iter().map(String::as_str).collect();
        p.only(&listed)?;
    }
    let mut laws = Vec::with_capacity(compare.len());
    for name in compare {
        let spec = registry.normal(&name)?;
        let mut over = Vec::new();
        if let Some(t) = params
            .as_ref()
            .map(|p| p.table(&name))
            .transpose()?
            .flatten()
        {
            let keys: Vec<&str> = spec.params.iter().map(|s| s.key).collect();
            t.only(&keys)?;
            for key in keys {
                if let Some(x) = t.f64(key, |_| true, "a finite number")? {
                    over.push((key.to_string(), x));
                }
            }
        }
        laws.push(ComparedLaw { name, params: over });
    }
    Ok(LawComparison { laws, tangential })
}
