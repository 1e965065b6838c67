//! Hardening laws as constants: the one enum a material stores ([`Law`]), the parameters of
//! each law (linear, Ludwik/Swift power law, Johnson-Cook), their checks, the published
//! Johnson-Cook presets and the keys a scene's hardening table gives. The flow stress and
//! the return mapping of each law are the solver's (`fe::materials`), which implements them
//! on these types.
//!
//! Registering a law: a variant of [`Law`], its name in [`LAW_NAMES`], its keys and
//! constructor in [`Law::keys`] and [`Law::from_keys`]; then its kernel in `fe::materials`.

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
    Counting(Counting),
}

/// Linear hardening σ_y = σ_y0 + H ε_p from the initial yield strength and the plastic
/// hardening modulus.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Bilinear {
    /// Initial yield strength σ_y0, Pa.
    pub yield0: f64,
    /// Plastic hardening modulus H, Pa (0 = perfectly plastic).
    pub h: f64,
}

/// [`Bilinear`] hardening that keeps two history values per integration point: plastic
/// steps (a count) and the highest plastic strain rate Δε_p/Δt, 1/s (tests only).
#[cfg(test)]
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Counting(pub Bilinear);

/// Power-law hardening parameters, σ_y = σ_0 + K ε_p^n (Ludwik 1909), rate independent.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Power {
    /// Initial yield strength σ_0, Pa (the material's `yield`).
    pub sigma0: f64,
    /// Strength coefficient K, Pa (≥ 0).
    #[serde(rename = "K")]
    pub k: f64,
    /// Hardening exponent n (0 < n ≤ 1).
    pub n: f64,
}

/// Johnson-Cook parameters (thermal term off), σ_y = (A + B ε_p^n)(1 + C ln ε̇*),
/// ε̇* = max(ε̇_p/ε̇_0, 1) (Johnson & Cook 1983).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct JohnsonCook {
    /// Yield strength A, Pa (> 0).
    #[serde(rename = "A")]
    pub a: f64,
    /// Strain-hardening coefficient B, Pa (≥ 0).
    #[serde(rename = "B")]
    pub b: f64,
    /// Strain-hardening exponent n (0 < n ≤ 1).
    pub n: f64,
    /// Strain-rate coefficient C (≥ 0).
    #[serde(rename = "C")]
    pub c: f64,
    /// Reference plastic strain rate ε̇_0, 1/s (> 0).
    pub rate0: f64,
}

/// OFHC copper, Johnson & Cook (1983), Table 1: A = 90 MPa, B = 292 MPa, n = 0.31,
/// C = 0.025, reference rate 1/s.
pub const OFHC_COPPER: JohnsonCook = JohnsonCook {
    a: 90e6,
    b: 292e6,
    n: 0.31,
    c: 0.025,
    rate0: 1.0,
};

/// 4340 steel (Rockwell C30), Johnson & Cook (1983), Table 1: A = 792 MPa, B = 510 MPa,
/// n = 0.26, C = 0.014, reference rate 1/s.
pub const STEEL_4340: JohnsonCook = JohnsonCook {
    a: 792e6,
    b: 510e6,
    n: 0.26,
    c: 0.014,
    rate0: 1.0,
};

impl Law {
    /// The law at the reference strain rate, for quasi-static loading: Johnson-Cook without
    /// its rate term (C = 0); every other law unchanged (they have no rate term).
    pub fn quasi_static(self) -> Law {
        match self {
            Law::JohnsonCook(jc) => Law::JohnsonCook(JohnsonCook { c: 0.0, ..jc }),
            Law::Bilinear(_) | Law::Power(_) => self,
            #[cfg(test)]
            Law::Counting(_) => self,
        }
    }

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
}

impl Power {
    /// Checks the parameters; `path` names the hardening table in messages.
    pub fn validated(self, path: &str) -> Result<Self> {
        if !(self.k >= 0.0 && self.k.is_finite()) {
            return Err(Error::invalid(
                format!("{path}.K"),
                self.k,
                "K >= 0 Pa, finite",
            ));
        }
        if !(self.n > 0.0 && self.n <= 1.0) {
            return Err(Error::invalid(format!("{path}.n"), self.n, "0 < n <= 1"));
        }
        Ok(self)
    }
}

impl JohnsonCook {
    /// Checks the parameters; `path` names the hardening table in messages.
    pub fn validated(self, path: &str) -> Result<Self> {
        let check = |key: &str, v: f64, ok: bool, allowed: &str| {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(Error::invalid(format!("{path}.{key}"), v, allowed))
            }
        };
        check("A", self.a, self.a > 0.0, "A > 0 Pa, finite")?;
        check("B", self.b, self.b >= 0.0, "B >= 0 Pa, finite")?;
        check("n", self.n, self.n > 0.0 && self.n <= 1.0, "0 < n <= 1")?;
        check("C", self.c, self.c >= 0.0, "C >= 0, finite")?;
        check(
            "rate0",
            self.rate0,
            self.rate0 > 0.0,
            "rate0 > 0 1/s, finite",
        )?;
        Ok(self)
    }
}
