//! Ball materials: isotropic elasticity, isotropic hardening (bilinear unless a hardening
//! law is given), Coulomb friction.
//!
//! The nine presets of Table 1 of Li, Yang & Shi (2019) and the copper of their ANSYS study
//! (`copper-fe`). The paper never gives a hardening (tangent) modulus; these presets use
//! `tangent = E / 100`, a common bilinear choice for metals, and say so in docs/design.md.
//! Two presets harden by Johnson & Cook's (1983) published laws: `ofhc-copper` and
//! `steel-4340` ([`hardening::OFHC_COPPER`], [`hardening::STEEL_4340`]).
//!
//! The hardening laws' parameters are in [`hardening`]. These are constants and know no
//! solver: `fe::materials` implements the laws' flow stress and return mapping on them.

pub mod hardening;

use crate::error::{Error, Result};
use hardening::{JohnsonCook, Law, OFHC_COPPER, STEEL_4340};
use serde::{Deserialize, Serialize};

/// An elastic-plastic ball material in SI units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Young's modulus E, Pa (> 0).
    #[serde(rename = "E")]
    pub youngs: f64,
    /// Poisson's ratio ν (in (-1, 0.5)).
    pub nu: f64,
    /// Mass density ρ, kg/m³ (> 0).
    pub rho: f64,
    /// Initial (uniaxial) yield strength σ_s, Pa (> 0).
    #[serde(rename = "yield")]
    pub yield_strength: f64,
    /// Tangent modulus E_T of the bilinear stress-strain law, Pa (0 ≤ E_T < E; 0 = perfectly plastic).
    pub tangent: f64,
    /// Dynamic (sliding) friction coefficient μ_d (≥ 0).
    pub mu: f64,
    /// Static friction coefficient μ_s (≥ μ_d); the paper uses one coefficient, so presets set μ_s = μ_d.
    pub mu_static: f64,
    /// Hardening law after first yield; `None`: linear, from `yield` and `tangent`. With a
    /// law, `yield` is its initial yield strength.
    #[serde(default, skip_deserializing, skip_serializing_if = "Option::is_none")]
    pub hardening: Option<Law>,
}

/// Field-by-field overrides of a material; `None` keeps the base value.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialOverrides {
    /// Young's modulus, Pa.
    #[serde(rename = "E")]
    pub youngs: Option<f64>,
    /// Poisson's ratio.
    pub nu: Option<f64>,
    /// Density, kg/m³.
    pub rho: Option<f64>,
    /// Yield strength, Pa.
    #[serde(rename = "yield")]
    pub yield_strength: Option<f64>,
    /// Tangent modulus, Pa.
    pub tangent: Option<f64>,
    /// Dynamic friction coefficient.
    pub mu: Option<f64>,
    /// Static friction coefficient.
    pub mu_static: Option<f64>,
}

/// Names of all presets, in Table 1 order followed by the FE study's copper.
pub const PRESET_NAMES: [&str; 12] = [
    "copper",
    "steel",
    "concrete",
    "cast-iron",
    "alumina",
    "glass",
    "wood",
    "aluminum",
    "rubber",
    "copper-fe",
    "ofhc-copper",
    "steel-4340",
];

/// Sets `field` to `value` when one is given.
fn replace(field: &mut f64, value: Option<f64>) {
    if let Some(v) = value {
        *field = v;
    }
}

impl Material {
    /// Builds a material from engineering units (E in GPa, yield in MPa) with `tangent = E/100`
    /// and μ_s = μ_d; used for the presets.
    const fn table(e_gpa: f64, yield_mpa: f64, rho: f64, mu: f64, nu: f64) -> Material {
        Material {
            youngs: e_gpa * 1e9,
            nu,
            rho,
            yield_strength: yield_mpa * 1e6,
            tangent: e_gpa * 1e9 / 100.0,
            mu,
            mu_static: mu,
            hardening: None,
        }
    }

    /// A Johnson-Cook material: E (GPa), ρ (kg/m³), μ, ν and the law `jc`, whose A is the
    /// yield strength (`tangent = E/100` is then unused by the FE model).
    const fn johnson_cook(e_gpa: f64, rho: f64, mu: f64, nu: f64, jc: JohnsonCook) -> Material {
        let mut m = Self::table(e_gpa, 0.0, rho, mu, nu);
        m.yield_strength = jc.a;
        m.hardening = Some(Law::JohnsonCook(jc));
        m
    }

    /// The `copper-fe` preset: the copper of the ANSYS model in Section 3 of the paper (the
    /// default scene's balls).
    pub const fn copper_fe() -> Material {
        Self::table(120.0, 100.0, 7900.0, 0.20, 0.33)
    }

    /// The named preset (`copper`, `steel`, …, `copper-fe`), or an error listing the names.
    pub fn preset(name: &str) -> Result<Material> {
        // Table 1 of the paper: E (GPa), σ_s (MPa), ρ (kg/m³), μ_s, ν.
        let m = match name {
            "copper" => Self::table(120.0, 100.0, 8500.0, 0.20, 0.34),
            "steel" => Self::table(210.0, 210.0, 7800.0, 0.10, 0.27),
            "concrete" => Self::table(17.0, 25.0, 2400.0, 0.60, 0.20),
            "cast-iron" => Self::table(160.0, 250.0, 7200.0, 0.15, 0.30),
            "alumina" => Self::table(70.0, 100.0, 3100.0, 0.50, 0.25),
            "glass" => Self::table(80.0, 70.0, 2700.0, 0.30, 0.20),
            "wood" => Self::table(14.0, 40.0, 600.0, 0.40, 0.25),
            "aluminum" => Self::table(75.0, 300.0, 2700.0, 0.32, 0.33),
            "rubber" => Self::table(0.0061, 7.0, 1000.0, 0.45, 0.45),
            "copper-fe" => Self::copper_fe(),
            // Johnson & Cook (1983, 1985): OFHC copper and 4340 steel, with their densities;
            // E and ν are handbook values (124 GPa, 0.34; 200 GPa, 0.29), μ Table 1's.
            "ofhc-copper" => Self::johnson_cook(124.0, 8960.0, 0.20, 0.34, OFHC_COPPER),
            "steel-4340" => Self::johnson_cook(200.0, 7830.0, 0.10, 0.29, STEEL_4340),
            _ => {
                return Err(Error::invalid(
                    "material",
                    name,
                    format!("one of {}", PRESET_NAMES.join(", ")),
                ))
            }
        };
        Ok(m)
    }

    /// This material with the given fields replaced, validated.
    pub fn with_overrides(self, o: &MaterialOverrides) -> Result<Material> {
        self.overridden(o).validated("material")
    }

    /// This material with the given fields replaced, not validated (the caller validates it
    /// with a prefix of its own).
    pub fn overridden(mut self, o: &MaterialOverrides) -> Material {
        replace(&mut self.youngs, o.youngs);
        replace(&mut self.nu, o.nu);
        replace(&mut self.rho, o.rho);
        replace(&mut self.yield_strength, o.yield_strength);
        replace(&mut self.tangent, o.tangent);
        if let Some(v) = o.mu {
            self.mu = v;
            // One coefficient given: keep the paper's single-coefficient convention unless
            // the static one is given too.
            if o.mu_static.is_none() {
                self.mu_static = self.mu_static.max(v);
            }
        }
        replace(&mut self.mu_static, o.mu_static);
        self
    }

    /// Checks every field; `prefix` names the material in messages (e.g. `ball1.material`).
    pub fn validated(self, prefix: &str) -> Result<Material> {
        let check = |name: &str, v: f64, ok: bool, allowed: &str| -> Result<()> {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(Error::invalid(format!("{prefix}.{name}"), v, allowed))
            }
        };
        check("E", self.youngs, self.youngs > 0.0, "E > 0 Pa, finite")?;
        check(
            "nu",
            self.nu,
            self.nu > -1.0 && self.nu < 0.5,
            "-1 < nu < 0.5",
        )?;
        check("rho", self.rho, self.rho > 0.0, "rho > 0 kg/m^3, finite")?;
        check(
            "yield",
            self.yield_strength,
            self.yield_strength > 0.0,
            "yield > 0 Pa, finite",
        )?;
        check(
            "tangent",
            self.tangent,
            self.tangent >= 0.0 && self.tangent < self.youngs,
            "0 <= tangent < E (Pa)",
        )?;
        check("mu", self.mu, self.mu >= 0.0, "mu >= 0, finite")?;
        check(
            "mu_static",
            self.mu_static,
            self.mu_static >= self.mu,
            "mu_static >= mu, finite",
        )?;
        Ok(self)
    }

    /// Plane-strain modulus E / (1 − ν²), Pa (the paper's E_ti).
    pub fn plane_strain_modulus(&self) -> f64 {
        self.youngs / (1.0 - self.nu * self.nu)
    }

    /// Shear modulus G = E / (2(1 + ν)), Pa.
    pub fn shear_modulus(&self) -> f64 {
        self.youngs / (2.0 * (1.0 + self.nu))
    }

    /// Bulk modulus K = E / (3(1 − 2ν)), Pa.
    pub fn bulk_modulus(&self) -> f64 {
        self.youngs / (3.0 * (1.0 - 2.0 * self.nu))
    }

    /// Lamé's first parameter λ = E ν / ((1 + ν)(1 − 2ν)), Pa.
    pub fn lame_lambda(&self) -> f64 {
        self.youngs * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu))
    }

    /// Dilatational (P-) wave speed c = sqrt((λ + 2G)/ρ), m/s; sets the explicit stable step.
    pub fn dilatational_wave_speed(&self) -> f64 {
        ((self.lame_lambda() + 2.0 * self.shear_modulus()) / self.rho).sqrt()
    }

    /// Plastic hardening modulus H = E E_T / (E − E_T), Pa: slope of stress against plastic strain.
    pub fn hardening_modulus(&self) -> f64 {
        self.youngs * self.tangent / (self.youngs - self.tangent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_is_valid() {
        for name in PRESET_NAMES {
            Material::preset(name).unwrap().validated(name).unwrap();
        }
    }

    #[test]
    fn copper_fe_matches_the_papers_fe_study() {
        let m = Material::preset("copper-fe").unwrap();
        assert_eq!(m.youngs, 120e9);
        assert_eq!(m.nu, 0.33);
        assert_eq!(m.yield_strength, 100e6);
        assert_eq!(m.rho, 7900.0);
        assert_eq!(m.mu, 0.2);
    }

    #[test]
    fn unknown_preset_names_the_choices() {
        let e = Material::preset("unobtainium").unwrap_err().to_string();
        assert!(e.contains("unobtainium") && e.contains("copper-fe"), "{e}");
    }

    #[test]
    fn bad_values_name_field_value_and_range() {
        let base = Material::preset("copper").unwrap();
        /// Sets one field of the overrides.
        type Set = fn(&mut MaterialOverrides);
        let cases: [(Set, &str); 7] = [
            (|o| o.youngs = Some(-1.0), "E"),
            (|o| o.nu = Some(0.5), "nu"),
            (|o| o.nu = Some(-1.0), "nu"),
            (|o| o.rho = Some(0.0), "rho"),
            (|o| o.yield_strength = Some(f64::NAN), "yield"),
            (|o| o.mu = Some(-0.1), "mu"),
            (|o| o.youngs = Some(f64::INFINITY), "E"),
        ];
        for (set, field) in cases {
            let mut o = MaterialOverrides::default();
            set(&mut o);
            let e = base.with_overrides(&o).unwrap_err().to_string();
            assert!(e.contains(&format!("material.{field} =")), "{e}");
            assert!(e.contains("allowed"), "{e}");
        }
    }

    #[test]
    fn overrides_replace_only_named_fields() {
        let base = Material::preset("copper-fe").unwrap();
        let m = base
            .with_overrides(&MaterialOverrides {
                yield_strength: Some(1e11),
                ..Default::default()
            })
            .unwrap();
        assert_eq!(m.yield_strength, 1e11);
        assert_eq!(m.youngs, base.youngs);
        assert_eq!(m.rho, base.rho);
    }

    #[test]
    fn elastic_constants_are_consistent() {
        let m = Material::preset("steel").unwrap();
        // λ + 2G = K + 4G/3 for any isotropic material.
        let lhs = m.lame_lambda() + 2.0 * m.shear_modulus();
        let rhs = m.bulk_modulus() + 4.0 / 3.0 * m.shear_modulus();
        assert!((lhs - rhs).abs() < 1e-6 * lhs);
    }
}
