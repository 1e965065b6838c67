//! Damper scene files (TOML): one frame, box, law choice and run controls shared by a list of
//! cases, each with its balls (material, diameter, count, laid out in the box) and the
//! measured frequency and damping ratio it is compared with.

use super::claims::{Claim, Relation};
use super::scene::{BoxSpec, DamperBall, DamperScene, FrameSpec, LawChoice};
use crate::error::{Error, Result};
use crate::material::Material;
use serde::Deserialize;
use std::collections::BTreeMap;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct FrameFile {
    mass: f64,
    frequency: f64,
    damping_ratio: f64,
    release: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct BoxFile {
    size: [f64; 3],
    material: String,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct LawsFile {
    normal: Option<String>,
    tangential: Option<String>,
    #[serde(default)]
    normal_params: BTreeMap<String, f64>,
    #[serde(default)]
    tangential_params: BTreeMap<String, f64>,
    mu_ball: Option<f64>,
    mu_wall: Option<f64>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RunFile {
    duration: f64,
    window: [f64; 2],
    #[serde(default = "default_steps")]
    steps_per_period: f64,
    #[serde(default = "default_interval")]
    sample_interval: f64,
    #[serde(default = "default_gravity")]
    gravity: f64,
    #[serde(default = "default_gap")]
    gap: f64,
}

fn default_steps() -> f64 {
    60.0
}
fn default_interval() -> f64 {
    1e-3
}
fn default_gravity() -> f64 {
    9.81
}
fn default_gap() -> f64 {
    2e-4
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct BallsFile {
    material: String,
    diameter: f64,
    count: usize,
}

#[derive(Debug, Clone, Copy, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
/// The frame's frequency and damping ratio a case was measured at.
pub struct Measured {
    /// Damped frequency, Hz.
    pub frequency: f64,
    /// Damping ratio (a fraction).
    pub damping_ratio: f64,
    /// Ratio of the balls' mass to the frame's mass as the paper states it (a fraction),
    /// if given.
    #[serde(default)]
    pub mass_ratio: Option<f64>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseFile {
    name: String,
    balls: Option<BallsFile>,
    measured: Option<Measured>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct ClaimFile {
    says: String,
    cases: [String; 2],
    relation: String,
    within: Option<f64>,
}

/// A damper scene file as read, before the cases are laid out; the fields a command line may
/// override are public.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DamperFile {
    frame: FrameFile,
    #[serde(rename = "box")]
    container: BoxFile,
    #[serde(default)]
    laws: LawsFile,
    run: RunFile,
    case: Vec<CaseFile>,
    #[serde(default)]
    claim: Vec<ClaimFile>,
}

/// One case ready to run.
#[derive(Debug, Clone, PartialEq)]
pub struct DamperCase {
    /// Case name (a file-name-safe word).
    pub name: String,
    /// The scene.
    pub scene: DamperScene,
    /// Window of the logarithmic decrement, [t0, t1] s.
    pub window: (f64, f64),
    /// What the paper measured, if given.
    pub measured: Option<Measured>,
}

/// Changes a command line may make to every case of a file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    /// Normal law name.
    pub normal: Option<String>,
    /// Normal-law parameters (added to the file's, later ones win).
    pub normal_params: Vec<(String, f64)>,
    /// Tangential law name.
    pub tangential: Option<String>,
    /// Tangential-law parameters.
    pub tangential_params: Vec<(String, f64)>,
    /// Ball-ball friction coefficient.
    pub mu_ball: Option<f64>,
    /// Ball-wall friction coefficient.
    pub mu_wall: Option<f64>,
    /// Frame mass, kg.
    pub frame_mass: Option<f64>,
    /// Box inner size, m.
    pub box_size: Option<[f64; 3]>,
    /// Simulated time, s (the window is cut to it).
    pub duration: Option<f64>,
    /// Diameter of every ball of this material, (material, m).
    pub diameter: Option<(String, f64)>,
}

/// Reads a damper scene file. Errors: the file cannot be read; TOML that does not parse or
/// has unknown keys (one line with the line number).
pub fn read(path: &std::path::Path) -> Result<DamperFile> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse(&text, &path.display().to_string())
}

/// Parses the text of a damper scene file; `name` names it in errors.
pub fn parse(text: &str, name: &str) -> Result<DamperFile> {
    toml::from_str(text).map_err(|e| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].matches('\n').count() + 1);
        let msg = e.message().replace('\n', " ");
        Error::Parse(match line {
            Some(l) => format!("{name}: line {l}: {msg}"),
            None => format!("{name}: {msg}"),
        })
    })
}

/// Centres of `count` balls of diameter `d` (m) in a box of inner size `size` (m): staggered
/// rows on the floor, pitch d + `gap`, odd rows shifted half a pitch, further layers above.
/// Errors: more balls than fit (naming `field`).
pub fn lay_out(
    count: usize,
    d: f64,
    size: [f64; 3],
    gap: f64,
    field: &str,
) -> Result<Vec<[f64; 3]>> {
    let p = d + gap;
    let row_pitch = p * 3f64.sqrt() / 2.0;
    let mut out = Vec::with_capacity(count);
    let fits = |x: f64, k: usize| x + 0.5 * d <= size[k] - 0.25 * gap;
    let mut z = 0.5 * d + 0.5 * gap;
    while out.len() < count && fits(z, 2) {
        let mut y = 0.5 * d + 0.5 * gap;
        let mut row = 0;
        while out.len() < count && fits(y, 1) {
            let mut x = 0.5 * d + 0.5 * gap + if row % 2 == 1 { 0.5 * p } else { 0.0 };
            while out.len() < count && fits(x, 0) {
                out.push([x, y, z]);
                x += p;
            }
            y += row_pitch;
            row += 1;
        }
        z += p;
    }
    if out.len() < count {
        return Err(Error::invalid(
            field,
            count,
            format!(
                "at most {} balls of {d} m in the box {:?} m with {gap} m gaps",
                out.len(),
                size
            ),
        ));
    }
    Ok(out)
}

impl DamperFile {
    /// The damping ratio of the empty structure (`frame.damping_ratio`, a fraction).
    pub fn empty_damping_ratio(&self) -> f64 {
        self.frame.damping_ratio
    }

    /// The file's claims (`[[claim]]`: `says`, `cases = [A, B]`, `relation` "greater" or
    /// "similar" with `within`). Errors: a case name not among the file's cases, an unknown
    /// relation (naming `claim[k]` and the field).
    pub fn claims(&self) -> Result<Vec<Claim>> {
        self.claim
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let field = format!("claim[{k}]");
                for name in &c.cases {
                    if !self.case.iter().any(|d| &d.name == name) {
                        let names: Vec<&str> = self.case.iter().map(|d| d.name.as_str()).collect();
                        return Err(Error::invalid(
                            format!("{field}.cases"),
                            name,
                            format!("one of {}", names.join(", ")),
                        ));
                    }
                }
                Ok(Claim {
                    says: c.says.clone(),
                    cases: c.cases.clone(),
                    relation: Relation::parse(&c.relation, c.within, &field)?,
                })
            })
            .collect()
    }

    /// The cases with `o` applied, laid out and validated. Errors name the case and field.
    pub fn cases(&self, o: &Overrides) -> Result<Vec<DamperCase>> {
        let wall = Material::preset(&self.container.material).map_err(|e| e.within("box"))?;
        let size = o.box_size.unwrap_or(self.container.size);
        let mut laws = LawChoice::default();
        (laws.normal, laws.normal_params) = chosen_law(
            &laws.normal,
            (&self.laws.normal, &self.laws.normal_params),
            (&o.normal, &o.normal_params),
        );
        (laws.tangential, laws.tangential_params) = chosen_law(
            &laws.tangential,
            (&self.laws.tangential, &self.laws.tangential_params),
            (&o.tangential, &o.tangential_params),
        );
        laws.mu_ball = o.mu_ball.or(self.laws.mu_ball);
        laws.mu_wall = o.mu_wall.or(self.laws.mu_wall);
        let duration = o.duration.unwrap_or(self.run.duration);
        let window = (self.run.window[0], self.run.window[1].min(duration));
        if !(window.0 >= 0.0 && window.1 > window.0) {
            return Err(Error::invalid(
                "run.window",
                format!("{:?}", self.run.window),
                format!("0 <= t0 < t1 <= duration ({duration} s)"),
            ));
        }
        let gap = self.run.gap;
        if !(gap.is_finite() && gap >= 0.0) {
            return Err(Error::invalid("run.gap", gap, "gap >= 0 m"));
        }
        let mut out = Vec::new();
        for (k, c) in self.case.iter().enumerate() {
            let field = format!("case[{k}]");
            if c.name.is_empty()
                || !c
                    .name
                    .chars()
                    .all(|ch| ch.is_ascii_alphanumeric() || ch == '-' || ch == '_')
            {
                return Err(Error::invalid(
                    format!("{field}.name"),
                    format!("{:?}", c.name),
                    "a non-empty word of letters, digits, - and _",
                ));
            }
            let mut balls = Vec::new();
            if let Some(b) = &c.balls {
                let material = Material::preset(&b.material)
                    .map_err(|e| e.within(&format!("{field}.balls")))?;
                let d = match &o.diameter {
                    Some((m, d)) if *m == b.material => *d,
                    _ => b.diameter,
                };
                let smallest = size.iter().copied().fold(f64::INFINITY, f64::min);
                if !(d.is_finite() && d > 0.0 && d <= smallest) {
                    return Err(Error::invalid(
                        format!("{field}.balls.diameter"),
                        d,
                        format!("0 < diameter <= {smallest} m (the box's smallest inner size)"),
                    ));
                }
                for position in lay_out(b.count, d, size, gap, &format!("{field}.balls.count"))? {
                    balls.push(DamperBall {
                        material,
                        diameter: d,
                        position,
                    });
                }
            }
            let scene = DamperScene {
                frame: FrameSpec {
                    mass: o.frame_mass.unwrap_or(self.frame.mass),
                    frequency: self.frame.frequency,
                    damping_ratio: self.frame.damping_ratio,
                    release: self.frame.release,
                },
                container: BoxSpec {
                    size,
                    material: wall,
                },
                balls,
                laws: laws.clone(),
                gravity: self.run.gravity,
                duration,
                steps_per_period: self.run.steps_per_period,
                impact_speed: None,
                sample_interval: self.run.sample_interval,
            };
            scene.validate().map_err(|e| e.within(&field))?;
            out.push(DamperCase {
                name: c.name.clone(),
                scene,
                window,
                measured: c.measured,
            });
        }
        Ok(out)
    }
}

/// One law of a case (normal or tangential) and its parameter overrides: `default`, replaced
/// by the file's name with the file's parameters, then by the command line's name (which
/// drops the file's parameters), with the command line's parameters appended (later win).
fn chosen_law(
    default: &str,
    file: (&Option<String>, &BTreeMap<String, f64>),
    line: (&Option<String>, &[(String, f64)]),
) -> (String, Vec<(String, f64)>) {
    let mut name = file.0.as_deref().unwrap_or(default).to_string();
    let mut params: Vec<(String, f64)> = file.1.iter().map(|(k, v)| (k.clone(), *v)).collect();
    if let Some(n) = line.0 {
        name.clone_from(n);
        params.clear();
    }
    params.extend(line.1.iter().cloned());
    (name, params)
}
