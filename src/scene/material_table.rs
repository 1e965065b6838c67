//! A ball's or wall's `material`: a preset name or a table of overrides with an optional
//! hardening law.

use super::reader::{self, Reader};
use crate::error::{Error, Result};
use crate::material::hardening::{Law, LAW_NAMES};
use crate::material::{Material, MaterialOverrides, PRESET_NAMES};
use toml::Value;

/// The keys of a material table.
pub(super) const MATERIAL_KEYS: [&str; 9] = [
    "preset",
    "hardening",
    "E",
    "nu",
    "rho",
    "yield",
    "tangent",
    "mu",
    "mu_static",
];

/// Ball or wall material at `b.material`: the material and its preset name (`custom` for a
/// table without a preset).
pub(super) fn read_material(b: &Reader<'_>) -> Result<(Material, String)> {
    let path = b.key_path("material");
    let presets = format!("one of {}", PRESET_NAMES.join(", "));
    let preset = |name: &str, field: &str| {
        Material::preset(name)
            .map_err(|_| Error::invalid(field, format!("\"{name}\""), presets.clone()))
    };
    match b.raw("material") {
        None => Err(b.missing(
            "material",
            "a preset name or a table { E, nu, rho, yield, mu, ... }",
        )),
        Some(Value::String(name)) => Ok((preset(name, &path)?, name.clone())),
        Some(Value::Table(t)) => {
            let m = Reader::new(&path, t);
            m.only(&MATERIAL_KEYS)?;
            let base = match m.string("preset")? {
                Some(name) => Some((preset(name, &m.key_path("preset"))?, name.to_string())),
                None => None,
            };
            let any = |_: f64| true;
            let o = MaterialOverrides {
                youngs: m.f64("E", any, "finite")?,
                nu: m.f64("nu", any, "finite")?,
                rho: m.f64("rho", any, "finite")?,
                yield_strength: m.f64("yield", any, "finite")?,
                tangent: m.f64("tangent", any, "finite")?,
                mu: m.f64("mu", any, "finite")?,
                mu_static: m.f64("mu_static", any, "finite")?,
            };
            let (base, name) = match base {
                Some(b) => b,
                None => {
                    // No preset: the essential fields are required; E_T = E/100 and μ_s = μ as
                    // for the presets.
                    for (key, v) in [
                        ("E", o.youngs),
                        ("nu", o.nu),
                        ("rho", o.rho),
                        ("yield", o.yield_strength),
                        ("mu", o.mu),
                    ] {
                        if v.is_none() {
                            return Err(Error::Parse(format!(
                                "missing required key {path}.{key} (or give {path}.preset)"
                            )));
                        }
                    }
                    let e = o.youngs.unwrap_or(1.0);
                    let mu = o.mu.unwrap_or(0.0);
                    let base = Material {
                        youngs: e,
                        nu: 0.0,
                        rho: 1.0,
                        yield_strength: 1.0,
                        tangent: if e.is_finite() && e > 0.0 {
                            e / 100.0
                        } else {
                            0.0
                        },
                        mu,
                        mu_static: mu,
                        hardening: None,
                    };
                    (base, "custom".to_string())
                }
            };
            let mut mat = base
                .with_overrides(&o)
                .map_err(|e| e.map_field(|field| field.replacen("material", &path, 1)))?;
            if let Some(h) = m.table("hardening")? {
                let hp = m.key_path("hardening");
                mat.hardening = Some(read_hardening(&h, &hp, mat.yield_strength)?);
            }
            if let Some(Law::JohnsonCook(jc)) = mat.hardening {
                if o.yield_strength.is_some() {
                    return Err(Error::Parse(format!(
                        "{path}.yield is the Johnson-Cook law's A: give {path}.hardening.A instead"
                    )));
                }
                mat.yield_strength = jc.a;
            }
            Ok((mat, name))
        }
        Some(other) => Err(Error::Parse(format!(
            "{path} = {} has the wrong type: expected a preset name or a table",
            reader::show(other)
        ))),
    }
}

/// A hardening table `{ law = "...", keys of the law }` named `path`; `yield0` is the
/// material's yield strength (Pa).
fn read_hardening(h: &Reader<'_>, path: &str, yield0: f64) -> Result<Law> {
    let laws = format!("one of {}", LAW_NAMES.join(", "));
    let name = h.string("law")?.ok_or_else(|| h.missing("law", &laws))?;
    let keys = Law::keys(name)
        .ok_or_else(|| Error::invalid(h.key_path("law"), format!("\"{name}\""), laws.clone()))?;
    let mut allowed = vec!["law"];
    allowed.extend_from_slice(keys);
    h.only(&allowed)?;
    Law::from_keys(name, path, yield0, &mut |key| {
        h.f64(key, |_| true, "finite")
    })
}
