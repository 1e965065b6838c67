//! The benchmark's matrix: which metals, speeds and diameters the head-on FE points cover,
//! and which oblique impacts test the tangential laws. Defaults in code
//! ([`Matrix::default`]); a small TOML file may replace any part ([`Matrix::from_toml`]).

use crate::analytic::three_phase::yield_approach;
use crate::analytic::{Body, HertzPair};
use crate::error::{Error, Result};
use crate::material::{Material, PRESET_NAMES};
use toml::{Table, Value};

/// The metals of the default matrix: three bilinear presets and the Johnson-Cook copper
/// (the section model's material seam takes the Johnson-Cook law).
pub const DEFAULT_METALS: [&str; 4] = ["copper-fe", "steel", "aluminum", "ofhc-copper"];

/// Lowest and highest relative speed of the default matrix, m/s, and the count of
/// log-spaced speeds between them.
pub const DEFAULT_SPEED_RANGE: (f64, f64, usize) = (0.01, 10.0, 8);

/// Ball diameters of the default matrix, m.
pub const DEFAULT_DIAMETERS: [f64; 2] = [0.005, 0.02];

/// Normalised angles of incidence ψ₁ = κ v_t/(μ v_n) of the default oblique impacts (Maw,
/// Barber & Fawcett 1976; κ = 2(1 − ν)/(2 − ν) for one material): from an impact that
/// mostly sticks (ψ₁ = 0.25) to one that slides throughout (ψ₁ = 8; the theory's curve:
/// `twoball laws mbf`).
pub const DEFAULT_ANGLES: [f64; 10] = [0.25, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 8.0];

/// The metals of the default oblique impacts.
pub const DEFAULT_OBLIQUE_METALS: [&str; 3] = ["copper-fe", "steel", "aluminum"];

/// A yield strength no impact of the bench reaches, Pa: an oblique point's elastic twin.
pub const ELASTIC_YIELD: f64 = 1e11;

/// How the oblique impacts' tangential speeds are given.
#[derive(Debug, Clone, PartialEq)]
pub enum Incidence {
    /// Relative tangential over relative normal speed, v_t/v_n.
    Ratios(Vec<f64>),
    /// Maw, Barber & Fawcett's normalised angles ψ₁ = κ v_t/(μ v_n) of the metal's pair.
    Angles(Vec<f64>),
}

/// The oblique impacts (3D half model) for the tangential laws.
#[derive(Debug, Clone, PartialEq)]
pub struct Oblique {
    /// Metal presets.
    pub metals: Vec<String>,
    /// Ball diameter, m.
    pub diameter: f64,
    /// Relative normal speed, m/s.
    pub normal_speed: f64,
    /// The tangential speeds.
    pub incidence: Incidence,
    /// Which responses: `false` the metal as it is, `true` its elastic twin (yield strength
    /// [`ELASTIC_YIELD`]).
    pub elastic: Vec<bool>,
}

/// The whole matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct Matrix {
    /// Metal presets of the head-on points (both balls of a pair are the same metal).
    pub metals: Vec<String>,
    /// Relative approach speeds of the head-on points, m/s, ascending.
    pub speeds: Vec<f64>,
    /// Ball diameters, m.
    pub diameters: Vec<f64>,
    /// The oblique impacts (`None`: no oblique points).
    pub oblique: Option<Oblique>,
    /// Whether the bench runs the quasi-static loops ([`Matrix::loop_points`]).
    pub loops: bool,
}

/// `n` log-spaced values from `lo` to `hi` (both included; `n` ≥ 2).
pub fn log_spaced(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
        .collect()
}

impl Default for Matrix {
    fn default() -> Self {
        let (lo, hi, n) = DEFAULT_SPEED_RANGE;
        Matrix {
            metals: DEFAULT_METALS.iter().map(|s| s.to_string()).collect(),
            speeds: log_spaced(lo, hi, n),
            diameters: DEFAULT_DIAMETERS.to_vec(),
            oblique: Some(Oblique {
                metals: DEFAULT_OBLIQUE_METALS
                    .iter()
                    .map(|s| s.to_string())
                    .collect(),
                diameter: 0.02,
                normal_speed: 1.0,
                incidence: Incidence::Angles(DEFAULT_ANGLES.to_vec()),
                elastic: vec![false, true],
            }),
            loops: true,
        }
    }
}

/// The matrix speeds nearest 0.1, 1 and 10 m/s (distinct, ascending).
pub fn loop_speeds(speeds: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = vec![];
    for target in [0.1f64, 1.0, 10.0] {
        let best = speeds
            .iter()
            .copied()
            .min_by(|a, b| (a / target).ln().abs().total_cmp(&(b / target).ln().abs()));
        if let Some(v) = best {
            if !out.contains(&v) {
                out.push(v);
            }
        }
    }
    out
}

/// One head-on FE point: two identical balls approaching at `speed`.
#[derive(Debug, Clone, PartialEq)]
pub struct HeadOnPoint {
    /// Metal preset name.
    pub metal: String,
    /// The metal.
    pub material: Material,
    /// Ball diameter, m.
    pub diameter: f64,
    /// Relative approach speed, m/s.
    pub speed: f64,
}

/// One oblique FE point: two identical balls, relative normal speed `normal_speed` and
/// relative tangential speed `ratio · normal_speed`.
#[derive(Debug, Clone, PartialEq)]
pub struct ObliquePoint {
    /// Metal preset name.
    pub metal: String,
    /// The metal (its elastic twin's yield strength when `elastic`).
    pub material: Material,
    /// Ball diameter, m.
    pub diameter: f64,
    /// Relative normal speed, m/s.
    pub normal_speed: f64,
    /// Tangential over normal relative speed.
    pub ratio: f64,
    /// Maw, Barber & Fawcett's normalised angle of incidence ψ₁ = κ ratio/μ, -.
    pub angle: f64,
    /// The elastic twin of the metal (yield strength [`ELASTIC_YIELD`]).
    pub elastic: bool,
}

/// κ/μ of two balls of `material`: ψ₁ = (κ/μ) v_t/v_n.
///
/// Errors: a material the ball rejects.
pub fn angle_per_ratio(material: &Material, diameter: f64) -> Result<f64> {
    let b = Body::ball(*material, diameter, "ball")?;
    let pair = crate::analytic::laws::ContactPair::between(&b, &b, material.mu);
    Ok(crate::analytic::maw_barber_fawcett::stiffness_ratio(&pair) / material.mu)
}

/// The relative approach speed v_y (m/s) at which a pair of two identical balls of
/// `material` and diameter `diameter` (m) starts to yield: the Hertz impact whose maximum
/// approach equals the three-phase model's yield approach δ₁ = R*(πσ_p/(2E*))² (Li, Yang &
/// Shi eq. 10, σ_p = (1 + π/2)σ_s, the two-ball E*, R* = R/2 and m* = m/2):
/// v_y = √(16E*√R* δ₁^{5/2}/(15m*)). Independent of the diameter.
///
/// Errors: a diameter or material the ball rejects.
pub fn yield_speed(material: &Material, diameter: f64) -> Result<f64> {
    let b = Body::ball(*material, diameter, "ball")?;
    let pair = HertzPair::between(&b, &b);
    let d1 = yield_approach(&pair, b.yield_pressure());
    Ok((16.0 * pair.modulus * pair.radius.sqrt() * d1.powf(2.5) / (15.0 * pair.mass)).sqrt())
}

impl Matrix {
    /// The head-on points, metal by metal, diameter by diameter, speeds ascending.
    ///
    /// Errors: an unknown metal.
    pub fn head_on_points(&self) -> Result<Vec<HeadOnPoint>> {
        let mut out = vec![];
        for (i, metal) in self.metals.iter().enumerate() {
            let material = preset(metal, &format!("metals[{i}]"))?;
            for &diameter in &self.diameters {
                for &speed in &self.speeds {
                    out.push(HeadOnPoint {
                        metal: metal.clone(),
                        material,
                        diameter,
                        speed,
                    });
                }
            }
        }
        Ok(out)
    }

    /// The largest ball diameter, m (NaN without diameters).
    pub fn largest_diameter(&self) -> f64 {
        self.diameters.iter().copied().fold(f64::NAN, f64::max)
    }

    /// The quasi-static loops' points (none without `loops`): every metal at the largest
    /// diameter and the [`loop_speeds`].
    ///
    /// Errors: an unknown metal.
    pub fn loop_points(&self) -> Result<Vec<HeadOnPoint>> {
        if !self.loops {
            return Ok(vec![]);
        }
        let d = self.largest_diameter();
        let speeds = loop_speeds(&self.speeds);
        Ok(self
            .head_on_points()?
            .into_iter()
            .filter(|p| p.diameter == d && speeds.contains(&p.speed))
            .collect())
    }

    /// The oblique points (none without `oblique`).
    ///
    /// Errors: an unknown metal.
    pub fn oblique_points(&self) -> Result<Vec<ObliquePoint>> {
        let Some(o) = &self.oblique else {
            return Ok(vec![]);
        };
        let mut out = vec![];
        for (i, metal) in o.metals.iter().enumerate() {
            let metal_itself = preset(metal, &format!("oblique.metals[{i}]"))?;
            let per_ratio = angle_per_ratio(&metal_itself, o.diameter)?;
            for &elastic in &o.elastic {
                let material = if elastic {
                    Material {
                        yield_strength: ELASTIC_YIELD,
                        ..metal_itself
                    }
                } else {
                    metal_itself
                };
                let ratios: Vec<f64> = match &o.incidence {
                    Incidence::Ratios(r) => r.clone(),
                    Incidence::Angles(a) => a.iter().map(|a| a / per_ratio).collect(),
                };
                for ratio in ratios {
                    out.push(ObliquePoint {
                        metal: metal.clone(),
                        material,
                        diameter: o.diameter,
                        normal_speed: o.normal_speed,
                        ratio,
                        angle: ratio * per_ratio,
                        elastic,
                    });
                }
            }
        }
        Ok(out)
    }

    /// Reads a matrix from TOML text (`source` names it in errors). Keys, each optional
    /// (default: [`Matrix::default`]'s): `metals` (preset names), `speeds` (relative speeds,
    /// m/s, 1e-3..100), `diameters` (m, 1e-3..0.2), and a table `[oblique]` with `metals`,
    /// `diameter` (m), `normal_speed` (m/s), `angles` (ψ₁, 1e-3..50) or `ratios` (v_t/v_n,
    /// 1e-3..10), `elastic` (a list of booleans: the metal itself, its elastic twin), or
    /// `oblique = false`, and `loops` (a boolean: the quasi-static loops, default true).
    ///
    /// Errors: one line naming the field, its value and the allowed range (an unknown key,
    /// a wrong type, a value out of range, an unknown metal, an empty list).
    pub fn from_toml(text: &str, source: &str) -> Result<Matrix> {
        let root: Table = text.parse().map_err(|e: toml::de::Error| {
            Error::Parse(format!(
                "{source}: not TOML: {}",
                e.message().lines().next().unwrap_or("")
            ))
        })?;
        let mut m = Matrix::default();
        for (key, value) in &root {
            match key.as_str() {
                "metals" => m.metals = metals(value, "metals")?,
                "speeds" => m.speeds = numbers(value, "speeds", 1e-3, 100.0, "m/s")?,
                "diameters" => m.diameters = numbers(value, "diameters", 1e-3, 0.2, "m")?,
                "oblique" => m.oblique = oblique(value, m.oblique.take())?,
                "loops" => {
                    m.loops = value
                        .as_bool()
                        .ok_or_else(|| Error::invalid("loops", value, "true or false"))?
                }
                other => {
                    return Err(Error::invalid(
                        other,
                        value,
                        "keys metals, speeds, diameters, oblique, loops",
                    ))
                }
            }
        }
        m.speeds.sort_by(f64::total_cmp);
        Ok(m)
    }
}

/// The preset `name`, its field `field` named in the error.
fn preset(name: &str, field: &str) -> Result<Material> {
    Material::preset(name)
        .map_err(|_| Error::invalid(field, name, format!("one of {}", PRESET_NAMES.join(", "))))
}

/// A non-empty list of preset names.
fn metals(v: &Value, field: &str) -> Result<Vec<String>> {
    let list = v
        .as_array()
        .filter(|a| !a.is_empty())
        .ok_or_else(|| Error::invalid(field, v, "a non-empty list of material presets"))?;
    list.iter()
        .enumerate()
        .map(|(i, x)| {
            let f = format!("{field}[{i}]");
            let name = x
                .as_str()
                .ok_or_else(|| Error::invalid(&f, x, "a material preset name"))?;
            preset(name, &f).map(|_| name.to_string())
        })
        .collect()
}

/// A number in [lo, hi].
fn number(v: &Value, field: &str, lo: f64, hi: f64, unit: &str) -> Result<f64> {
    let x = v
        .as_float()
        .or_else(|| v.as_integer().map(|i| i as f64))
        .filter(|x| x.is_finite() && (lo..=hi).contains(x))
        .ok_or_else(|| Error::invalid(field, v, format!("a number in {lo}..{hi} {unit}")))?;
    Ok(x)
}

/// A non-empty list of numbers in [lo, hi].
fn numbers(v: &Value, field: &str, lo: f64, hi: f64, unit: &str) -> Result<Vec<f64>> {
    let list = v.as_array().filter(|a| !a.is_empty()).ok_or_else(|| {
        Error::invalid(
            field,
            v,
            format!("a non-empty list of numbers in {lo}..{hi} {unit}"),
        )
    })?;
    list.iter()
        .enumerate()
        .map(|(i, x)| number(x, &format!("{field}[{i}]"), lo, hi, unit))
        .collect()
}

/// A non-empty list of booleans.
fn booleans(v: &Value, field: &str) -> Result<Vec<bool>> {
    v.as_array()
        .filter(|a| !a.is_empty())
        .and_then(|a| a.iter().map(Value::as_bool).collect::<Option<Vec<bool>>>())
        .ok_or_else(|| Error::invalid(field, v, "a non-empty list of booleans, e.g. [false, true]"))
}

/// The `[oblique]` table over `base` (or `oblique = false`).
fn oblique(v: &Value, base: Option<Oblique>) -> Result<Option<Oblique>> {
    if v.as_bool() == Some(false) {
        return Ok(None);
    }
    let t = v
        .as_table()
        .ok_or_else(|| Error::invalid("oblique", v, "a table, or false"))?;
    let mut o = base.unwrap_or(Oblique {
        metals: vec!["copper-fe".into()],
        diameter: 0.02,
        normal_speed: 1.0,
        incidence: Incidence::Angles(DEFAULT_ANGLES.to_vec()),
        elastic: vec![false],
    });
    for (key, value) in t {
        let field = format!("oblique.{key}");
        match key.as_str() {
            "metals" => o.metals = metals(value, &field)?,
            "diameter" => o.diameter = number(value, &field, 1e-3, 0.2, "m")?,
            "normal_speed" => o.normal_speed = number(value, &field, 1e-2, 20.0, "m/s")?,
            "ratios" => o.incidence = Incidence::Ratios(numbers(value, &field, 1e-3, 10.0, "(-)")?),
            "angles" => o.incidence = Incidence::Angles(numbers(value, &field, 1e-3, 50.0, "(-)")?),
            "elastic" => o.elastic = booleans(value, &field)?,
            _ => {
                return Err(Error::invalid(
                    field,
                    value,
                    "keys metals, diameter, normal_speed, angles, ratios, elastic",
                ))
            }
        }
    }
    Ok(Some(o))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_has_eight_log_spaced_speeds() {
        let m = Matrix::default();
        assert_eq!(m.speeds.len(), 8);
        assert!((m.speeds[0] - 0.01).abs() < 1e-15 && (m.speeds[7] - 10.0).abs() < 1e-12);
        let r = m.speeds[1] / m.speeds[0];
        assert!((m.speeds[5] / m.speeds[4] - r).abs() < 1e-12);
        assert_eq!(m.head_on_points().unwrap().len(), 4 * 2 * 8);
    }

    #[test]
    fn toml_replaces_parts_and_names_bad_fields() {
        let m = Matrix::from_toml("metals = [\"steel\"]\nspeeds = [1.0, 0.1]", "m").unwrap();
        assert_eq!(m.metals, vec!["steel"]);
        assert_eq!(m.speeds, vec![0.1, 1.0]);
        assert_eq!(m.diameters, DEFAULT_DIAMETERS.to_vec());
        let e = Matrix::from_toml("speeds = [1.0, -2]", "m")
            .unwrap_err()
            .to_string();
        assert!(e.contains("speeds[1]") && e.contains("-2"), "{e}");
        let e = Matrix::from_toml("metals = [\"gold\"]", "m")
            .unwrap_err()
            .to_string();
        assert!(e.contains("metals[0]") && e.contains("gold"), "{e}");
        let e = Matrix::from_toml("[oblique]\nratio = [1]", "m")
            .unwrap_err()
            .to_string();
        assert!(e.contains("oblique.ratio"), "{e}");
        assert!(Matrix::from_toml("oblique = false", "m")
            .unwrap()
            .oblique
            .is_none());
    }

    /// The default oblique points: ten angles of incidence on three metals and their elastic
    /// twins; each point's ψ₁ is Maw, Barber & Fawcett's normalised angle of its pair at its
    /// speeds, and a twin differs from its metal by the yield strength alone.
    #[test]
    fn default_oblique_points_span_the_angles_on_metals_and_twins() {
        let pts = Matrix::default().oblique_points().unwrap();
        assert_eq!(pts.len(), 3 * 2 * DEFAULT_ANGLES.len());
        for p in &pts {
            let b = Body::ball(p.material, p.diameter, "ball").unwrap();
            let pair = crate::analytic::laws::ContactPair::between(&b, &b, p.material.mu);
            let psi = crate::analytic::maw_barber_fawcett::normalised_angle(
                &pair,
                p.ratio * p.normal_speed,
                p.normal_speed,
            );
            assert!((psi / p.angle - 1.0).abs() < 1e-12, "{p:?}: {psi}");
            assert!(DEFAULT_ANGLES
                .iter()
                .any(|a| (a / p.angle - 1.0).abs() < 1e-12));
            let metal = Material::preset(&p.metal).unwrap();
            let expected = if p.elastic {
                Material {
                    yield_strength: ELASTIC_YIELD,
                    ..metal
                }
            } else {
                metal
            };
            assert_eq!(p.material, expected);
        }
        let m = Matrix::from_toml("[oblique]\nangles = [1.0]\nelastic = [true]", "m").unwrap();
        let pts = m.oblique_points().unwrap();
        assert_eq!(pts.len(), 3);
        assert!(pts
            .iter()
            .all(|p| p.elastic && (p.angle - 1.0).abs() < 1e-12));
        let e = Matrix::from_toml("[oblique]\nelastic = [1]", "m")
            .unwrap_err()
            .to_string();
        assert!(e.contains("oblique.elastic") && !e.contains('\n'), "{e}");
    }

    /// v_y of the paper's copper pair: E* = 67.3 GPa, σ_p = 257 MPa, R* = 5 mm, m* =
    /// 16.5 g: δ₁ = 1.80e-7 m and v_y = 2.05 mm/s; independent of D (δ₁ ∝ R, m* ∝ R³).
    #[test]
    fn yield_speed_of_copper_fe() {
        let m = Material::preset("copper-fe").unwrap();
        let v = yield_speed(&m, 0.02).unwrap();
        assert!((v - 2.05e-3).abs() < 0.02e-3, "{v}");
        assert!((yield_speed(&m, 0.005).unwrap() / v - 1.0).abs() < 1e-12);
    }
}
