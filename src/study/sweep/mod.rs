//! Parameter sweeps such as the paper's ANSYS study (Section 3): a grid of two-ball scenes,
//! each case run once, its result written atomically to its own JSON file, finished cases
//! skipped on restart, and one CSV of all cases rewritten atomically at the end.
//!
//! The sweep file (TOML):
//! ```toml
//! [study]
//! model = "fe"                                      # "fe" (FE and analytical) or "analytic"
//! diameters = [0.005, 0.010, 0.020, 0.030]          # m, both balls
//! left_velocity = 1.0                               # m/s, ball 1 along the line of centres
//! right_velocities = [-2.5, -1.5, -1.0, 0.0, 0.5, 1.0]
//! tangential = [[0.0, 0.0], [0.1, -0.1], [0.5, -0.5]]  # m/s along y, ball 1 / ball 2
//! [base]                                            # scene keys for every case
//! ball1.material = "copper-fe"
//! ball2.material = "copper-fe"
//! [[mesh]]
//! name = "uniform-2mm"
//! size = 0.002                                      # m, or size_per_diameter = 0.1
//! pole_size = 0.002                                 # m, or pole_size_per_diameter = 0.01
//! penalty_factor = 0.01                             # optional: contact.penalty_factor of its cases
//! ```

pub mod cost;
pub mod similarity;
pub mod slurm;
pub mod status;

use crate::atomic::{
    ensure_dir, remove_stale_temporaries, remove_temporaries_older_than, write_atomic,
};
use crate::error::{Error, Result};
use crate::scene::reader::{parse_table, Reader};
use crate::scene::{approach, Approach, Override, Scene, DEFAULT_SCENE};
use crate::study::records::case::{FeCase, FeSummary};
use crate::study::records::case_cache::{CaseCache, Layout};
use crate::study::records::outcome::{analytic_outcome, Outcome};
use crate::study::sweep::status::{clear_running, mark_running};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use toml::{Table, Value};

/// Which models a sweep runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SweepModel {
    /// FE simulation and the analytical model.
    Fe,
    /// The analytical model only (fast; for parameter studies and for testing the runner).
    Analytic,
}

/// An element size: absolute (m) or relative to the ball diameter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Size {
    /// Metres.
    Absolute(f64),
    /// Fraction of the diameter.
    PerDiameter(f64),
}

impl Size {
    fn metres(self, d: f64) -> f64 {
        match self {
            Size::Absolute(s) => s,
            Size::PerDiameter(f) => f * d,
        }
    }
}

/// One mesh setting of the sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshSetting {
    /// Short name, used in case ids (letters, digits, `-`).
    pub name: String,
    /// Bulk element size.
    pub size: Size,
    /// Pole element size.
    pub pole_size: Size,
    /// Contact penalty multiplier (`contact.penalty_factor` of the cases; None: the scene's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penalty_factor: Option<f64>,
}

/// A parsed sweep file.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepSpec {
    /// Models to run.
    pub model: SweepModel,
    /// Ball diameters, m (both balls).
    pub diameters: Vec<f64>,
    /// Ball 1's velocity along the line of centres, m/s.
    pub left_velocity: f64,
    /// Ball 2's velocities along the line of centres, m/s.
    pub right_velocities: Vec<f64>,
    /// Tangential (y) velocities of ball 1 and ball 2, m/s.
    pub tangential: Vec<[f64; 2]>,
    /// Mesh settings.
    pub meshes: Vec<MeshSetting>,
    /// Scene keys applied to every case, as `--set` overrides over the default scene.
    pub base: Vec<Override>,
    /// Points kept of each δ(t) history in the case files.
    pub history_points: usize,
    /// Relative tolerance on e of the head-on cases on the section (`twoball run
    /// --tolerance`); None: their default two-level bar.
    pub tolerance: Option<f64>,
}

/// One case of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Position in the full (unsharded) case list.
    pub index: usize,
    /// File-name-safe id, e.g. `D20mm_vr-1.0_vt0.1_graded`.
    pub id: String,
    /// Its parameters.
    pub params: CaseParams,
    /// The scene it runs.
    pub scene: Scene,
}

/// The parameters that define a case.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseParams {
    /// Diameter of both balls, m.
    pub diameter: f64,
    /// Ball 1's normal velocity, m/s.
    pub v1n: f64,
    /// Ball 2's normal velocity, m/s.
    pub v2n: f64,
    /// Ball 1's tangential velocity, m/s.
    pub v1t: f64,
    /// Ball 2's tangential velocity, m/s.
    pub v2t: f64,
    /// Mesh setting name.
    pub mesh: String,
}

/// How a case ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Simulated (and/or solved analytically).
    Done,
    /// The balls do not collide: nothing simulated.
    NoImpact,
    /// The run stopped with an error (the message says why).
    Failed,
}

/// What is written for each case (one JSON file per case).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseRecord {
    /// Case id.
    pub id: String,
    /// Position in the full case list.
    pub index: usize,
    /// Parameters.
    pub params: CaseParams,
    /// How it ended.
    pub status: Status,
    /// Why (no impact, failure), else empty.
    pub message: String,
    /// The analytical outcome (absent for no impact).
    pub analytic: Option<Outcome>,
    /// The FE result (absent for no impact, analytic-only sweeps and failures).
    pub fe: Option<FeSummary>,
    /// Analytical δ(t): [t (s), δ (m)] pairs.
    pub analytic_history: Vec<[f64; 2]>,
    /// FE δ(t): [t (s), δ (m)] pairs.
    pub fe_history: Vec<[f64; 2]>,
    /// Wall time of the whole case, s.
    pub wall_time_s: f64,
}

/// The FE solver a sweep calls for each impacting case.
pub type FeRunner<'a> = &'a (dyn Fn(&Scene) -> Result<FeCase> + Sync);

/// `I/N`: this process runs shard I of a plan that deals the sweep's cases to N shards by
/// estimated cost ([`shard_plan`]), so that shards take similar time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 1-based shard number.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// The whole sweep.
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// Parses `I/N` with 1 ≤ I ≤ N.
    pub fn parse(s: &str) -> Result<Shard> {
        let bad = || Error::invalid("--shard", s, "I/N with integers 1 <= I <= N, e.g. 2/8");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (i, n): (usize, usize) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if n == 0 || i == 0 || i > n {
            return Err(bad());
        }
        Ok(Shard { index: i, count: n })
    }
}

/// Name of the copy of the sweep file kept in the sweep folder.
pub const SPEC_COPY: &str = "sweep.toml";

/// Makes `out` the folder of the sweep `spec` (read from `file`): keeps a copy of the file as
/// `out/sweep.toml`, which `twoball sweep status` and `twoball report` read. A folder that
/// already holds a different sweep is refused, so that results of two sweeps never mix.
///
/// Errors: `out` holds another sweep ([`Error::Invalid`] naming `--out`); I/O errors.
pub fn adopt_folder(out: &Path, file: &Path, spec: &SweepSpec) -> Result<()> {
    let copy = out.join(SPEC_COPY);
    if copy.exists() {
        let kept = SweepSpec::from_file(&copy)?;
        if &kept != spec {
            return Err(Error::invalid(
                "--out",
                out.display(),
                format!(
                    "a new folder or one of the same sweep ({} differs from {})",
                    copy.display(),
                    file.display()
                ),
            ));
        }
        return Ok(());
    }
    let text = std::fs::read(file).map_err(|e| Error::io(file, e))?;
    ensure_dir(out)?;
    write_atomic(&copy, &text)
}

/// The sweep file of the folder `out` (its `sweep.toml` copy), parsed.
///
/// Errors: no copy there (not a sweep folder), or the copy does not parse.
pub fn folder_spec(out: &Path) -> Result<SweepSpec> {
    let copy = out.join(SPEC_COPY);
    if !copy.is_file() {
        return Err(Error::Parse(format!(
            "{}: not a sweep folder (no {SPEC_COPY}; run twoball sweep FILE --out {} first, or give --sweep FILE)",
            out.display(),
            out.display()
        )));
    }
    SweepSpec::from_file(&copy)
}

/// The cases of a run: all of `cases`, or those of mesh setting `mesh`.
///
/// Errors: `mesh` names no setting of `spec` ([`Error::Invalid`] naming `--mesh` and listing
/// the names).
pub fn select<'a>(
    spec: &SweepSpec,
    cases: &'a [Case],
    mesh: Option<&str>,
) -> Result<Vec<&'a Case>> {
    if let Some(m) = mesh {
        if !spec.meshes.iter().any(|s| s.name == m) {
            let names: Vec<&str> = spec.meshes.iter().map(|s| s.name.as_str()).collect();
            return Err(Error::invalid(
                "--mesh",
                m,
                format!("one of the sweep's mesh settings: {}", names.join(", ")),
            ));
        }
    }
    Ok(cases
        .iter()
        .filter(|c| mesh.is_none_or(|m| c.params.mesh == m))
        .collect())
}

/// Estimated cost of each case in element-steps ([`crate::study::sweep::cost`]); a case whose estimate
/// fails (it will fail when run, with its reason) costs [`crate::study::sweep::cost::CASE_OVERHEAD`].
pub fn case_costs(spec: &SweepSpec, cases: &[&Case]) -> Vec<f64> {
    let fe = spec.model == SweepModel::Fe;
    let estimator = crate::study::sweep::cost::Estimator::default();
    let twins = twins(spec, cases);
    cases
        .par_iter()
        .zip(&twins)
        .map(|(c, twin)| match twin {
            // Scaled from its twin's run: the analytical model only.
            Some(_) => crate::study::sweep::cost::CASE_OVERHEAD,
            None => estimator
                .estimate_to(&c.scene, fe, spec.tolerance)
                .map_or(crate::study::sweep::cost::CASE_OVERHEAD, |e| {
                    e.element_steps()
                }),
        })
        .collect()
}

/// True when `scene` collides and its FE model is the meridian section.
fn runs_on_section(scene: &Scene) -> bool {
    let Ok(Approach::Impact(touch)) = approach(scene) else {
        return false;
    };
    crate::study::run::simulate::choose_reduction(scene, &touch)
        .is_ok_and(|(r, _)| r == crate::study::run::simulate::Reduction::Axisymmetric)
}

/// For each of `cases`, the earlier case (its position in `cases`) whose FE run it is scaled
/// by the factor k (dimensional similarity, [`crate::study::sweep::similarity::similarity_factor`]): the
/// first similar case that runs its own. None for a case that runs, for a case off the
/// meridian section, and for every case of an analytic-only sweep.
pub fn twins(spec: &SweepSpec, cases: &[&Case]) -> Vec<Option<(usize, f64)>> {
    let mut out: Vec<Option<(usize, f64)>> = vec![None; cases.len()];
    if spec.model != SweepModel::Fe {
        return out;
    }
    // Only the section's runs are scaled: the 3D models' e and contact duration differ from
    // their scaled twins' by up to 1e-4 and 2e-4 (round-off grows through the ringing of
    // their penalty contact), the section's agree to printed precision (docs/design.md,
    // "Similar cases").
    let on_section: Vec<bool> = cases.iter().map(|c| runs_on_section(&c.scene)).collect();
    for i in 0..cases.len() {
        if !on_section[i] {
            continue;
        }
        let (p, scene) = (&cases[i].params, &cases[i].scene);
        out[i] = (0..i)
            .filter(|&j| on_section[j])
            .filter(|&j| out[j].is_none())
            .filter(|&j| {
                let q = &cases[j].params;
                (q.v1n, q.v2n, q.v1t, q.v2t, &q.mesh) == (p.v1n, p.v2n, p.v1t, p.v2t, &p.mesh)
            })
            .find_map(|j| {
                crate::study::sweep::similarity::similarity_factor(&cases[j].scene, scene)
                    .map(|k| (j, k))
            });
    }
    out
}

/// Cases and estimated cost (element-steps) of each shard when `cases` are split `count` ways.
pub fn shard_costs(spec: &SweepSpec, cases: &[&Case], count: usize) -> Vec<(usize, f64)> {
    let costs = case_costs(spec, cases);
    let plan = shard_plan(spec, cases, count);
    let mut out = vec![(0, 0.0); count.max(1)];
    for (c, &s) in costs.iter().zip(&plan) {
        out[s].0 += 1;
        out[s].1 += c;
    }
    out
}

/// The 0-based shard of each of `cases` when the sweep is split `count` ways, balanced by
/// estimated cost; every process computes the same plan from the same sweep file.
pub fn shard_plan(spec: &SweepSpec, cases: &[&Case], count: usize) -> Vec<usize> {
    if count <= 1 {
        return vec![0; cases.len()];
    }
    let mut plan = crate::study::sweep::cost::balance(&case_costs(spec, cases), count);
    // A case scaled from its twin's run goes with the twin (which comes first).
    for (i, twin) in twins(spec, cases).iter().enumerate() {
        if let Some((j, _)) = twin {
            plan[i] = plan[*j];
        }
    }
    plan
}

const STUDY_KEYS: [&str; 8] = [
    "model",
    "diameters",
    "left_velocity",
    "right_velocities",
    "tangential",
    "history_points",
    "tolerance",
    "name",
];
const MESH_KEYS: [&str; 6] = [
    "name",
    "size",
    "pole_size",
    "size_per_diameter",
    "pole_size_per_diameter",
    "penalty_factor",
];

fn list_f64(
    r: &Reader<'_>,
    key: &str,
    ok: impl Fn(f64) -> bool,
    allowed: &str,
) -> Result<Vec<f64>> {
    let v = r
        .raw(key)
        .ok_or_else(|| r.missing(key, "a list of numbers"))?;
    let Value::Array(a) = v else {
        return Err(Error::Parse(format!(
            "{} must be a list of numbers",
            r.key_path(key)
        )));
    };
    if a.is_empty() {
        return Err(Error::invalid(r.key_path(key), "[]", "a non-empty list"));
    }
    a.iter()
        .enumerate()
        .map(|(i, x)| {
            let x = match x {
                Value::Float(f) => *f,
                Value::Integer(n) => *n as f64,
                _ => {
                    return Err(Error::Parse(format!(
                        "{}[{i}] must be a number",
                        r.key_path(key)
                    )))
                }
            };
            if x.is_finite() && ok(x) {
                Ok(x)
            } else {
                Err(Error::invalid(
                    format!("{}[{i}]", r.key_path(key)),
                    x,
                    allowed,
                ))
            }
        })
        .collect()
}

/// Flattens a table of scene keys into `--set` overrides (nested tables become dotted paths).
fn flatten(prefix: &[String], t: &Table, out: &mut Vec<Override>) {
    for (k, v) in t {
        let mut path = prefix.to_vec();
        path.push(k.clone());
        match v {
            Value::Table(sub) => flatten(&path, sub, out),
            other => out.push(Override {
                path,
                value: other.clone(),
            }),
        }
    }
}

impl SweepSpec {
    /// Reads a sweep file.
    pub fn from_file(path: &Path) -> Result<SweepSpec> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Self::from_toml(&text, &path.display().to_string())
    }

    /// Reads sweep text; `origin` names it in syntax errors.
    pub fn from_toml(text: &str, origin: &str) -> Result<SweepSpec> {
        let root = parse_table(text, origin)?;
        let r = Reader::new("", &root);
        r.only(&["study", "base", "mesh"])?;
        let s = r
            .table("study")?
            .ok_or_else(|| r.missing("study", "the sweep's axes"))?;
        s.only(&STUDY_KEYS)?;
        let model = match s.choice("model", &["fe", "analytic"])? {
            Some("analytic") => SweepModel::Analytic,
            _ => SweepModel::Fe,
        };
        let diameters = list_f64(
            &s,
            "diameters",
            |d| (1e-4..=1.0).contains(&d),
            "1e-4 <= diameter <= 1 m",
        )?;
        let left_velocity = s
            .f64("left_velocity", |v| v.abs() <= 1000.0, "|v| <= 1000 m/s")?
            .ok_or_else(|| s.missing("left_velocity", "m/s"))?;
        let right_velocities = list_f64(
            &s,
            "right_velocities",
            |v| v.abs() <= 1000.0,
            "|v| <= 1000 m/s",
        )?;
        let tangential = match s.raw("tangential") {
            None => vec![[0.0, 0.0]],
            Some(Value::Array(pairs)) => pairs
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let bad = || {
                        Error::invalid(
                            format!("study.tangential[{i}]"),
                            p,
                            "a pair [v1t, v2t] of numbers, |v| <= 1000 m/s",
                        )
                    };
                    let Value::Array(a) = p else {
                        return Err(bad());
                    };
                    let num = |v: &Value| match v {
                        Value::Float(f) if f.is_finite() && f.abs() <= 1000.0 => Ok(*f),
                        Value::Integer(n) if n.abs() <= 1000 => Ok(*n as f64),
                        _ => Err(bad()),
                    };
                    match a.as_slice() {
                        [a, b] => Ok([num(a)?, num(b)?]),
                        _ => Err(bad()),
                    }
                })
                .collect::<Result<Vec<_>>>()?,
            Some(other) => {
                return Err(Error::invalid(
                    "study.tangential",
                    other,
                    "a list of pairs [v1t, v2t]",
                ))
            }
        };
        let history_points = s
            .u64(
                "history_points",
                |n| (2..=100_000).contains(&n),
                "2 <= history_points <= 100000",
            )?
            .unwrap_or(200) as usize;
        let tolerance = s.f64(
            "tolerance",
            |t| t > 0.0 && t < 1.0,
            "a fraction 0 < tolerance < 1, e.g. 0.005",
        )?;
        let _ = s.string("name")?;
        let mut base = Vec::new();
        if let Some(b) = r.raw("base") {
            let Value::Table(t) = b else {
                return Err(Error::Parse("base must be a table of scene keys".into()));
            };
            flatten(&[], t, &mut base);
        }
        let meshes = match r.raw("mesh") {
            None => vec![MeshSetting {
                name: "default".into(),
                size: Size::PerDiameter(crate::scene::DEFAULT_SIZE_PER_D),
                pole_size: Size::PerDiameter(crate::scene::DEFAULT_POLE_SIZE_PER_D),
                penalty_factor: None,
            }],
            Some(Value::Array(items)) => {
                let mut out = Vec::new();
                for (i, it) in items.iter().enumerate() {
                    let Value::Table(t) = it else {
                        return Err(Error::Parse(format!(
                            "mesh[{i}] must be a table ([[mesh]])"
                        )));
                    };
                    let m = Reader::new(&format!("mesh[{i}]"), t);
                    m.only(&MESH_KEYS)?;
                    let name = m
                        .string("name")?
                        .ok_or_else(|| m.missing("name", "a short mesh name"))?;
                    if name.is_empty()
                        || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-')
                    {
                        return Err(Error::invalid(
                            m.key_path("name"),
                            name,
                            "letters, digits and '-'",
                        ));
                    }
                    let size_of = |abs: &str, rel: &str| -> Result<Size> {
                        let a = m.f64(abs, |x| x > 0.0 && x <= 1.0, "0 < size <= 1 m")?;
                        let r = m.f64(rel, |x| x > 0.0 && x <= 1.0, "0 < fraction <= 1")?;
                        match (a, r) {
                            (Some(a), None) => Ok(Size::Absolute(a)),
                            (None, Some(r)) => Ok(Size::PerDiameter(r)),
                            _ => Err(Error::Parse(format!(
                                "{}: give exactly one of {abs} and {rel}",
                                m.key_path(abs)
                            ))),
                        }
                    };
                    out.push(MeshSetting {
                        name: name.to_string(),
                        size: size_of("size", "size_per_diameter")?,
                        pole_size: size_of("pole_size", "pole_size_per_diameter")?,
                        penalty_factor: m.f64(
                            "penalty_factor",
                            |x| (1e-3..=1e3).contains(&x),
                            "1e-3 <= penalty_factor <= 1e3",
                        )?,
                    });
                }
                if out.is_empty() {
                    return Err(Error::invalid("mesh", "[]", "at least one [[mesh]]"));
                }
                out
            }
            Some(_) => {
                return Err(Error::Parse(
                    "mesh must be an array of tables ([[mesh]])".into(),
                ))
            }
        };
        let spec = SweepSpec {
            model,
            diameters,
            left_velocity,
            right_velocities,
            tangential,
            meshes,
            base,
            history_points,
            tolerance,
        };
        spec.cases()?; // every case must be a valid scene
        Ok(spec)
    }

    /// All cases, in a fixed order: mesh, diameter, tangential pair, right-ball speed.
    pub fn cases(&self) -> Result<Vec<Case>> {
        let default = parse_table(DEFAULT_SCENE, "default scene")?;
        let mut out = Vec::new();
        for mesh in &self.meshes {
            for &d in &self.diameters {
                for &[v1t, v2t] in &self.tangential {
                    for &v2n in &self.right_velocities {
                        let v1n = self.left_velocity;
                        let id = format!("D{}mm_vr{v2n:+.2}_vt{v1t:.2}_{}", fmt_mm(d), mesh.name);
                        let mut table = default.clone();
                        for o in &self.base {
                            o.apply(&mut table)?;
                        }
                        let (size, pole) = (
                            mesh.size.metres(d),
                            mesh.pole_size.metres(d).min(mesh.size.metres(d)),
                        );
                        let penalty = mesh
                            .penalty_factor
                            .map(|p| format!("contact.penalty_factor={p:e}"));
                        let sets = [
                            format!("ball1.diameter={d}"),
                            format!("ball2.diameter={d}"),
                            format!("ball1.velocity=[{v1n:e},{v1t:e},0]"),
                            format!("ball2.velocity=[{v2n:e},{v2t:e},0]"),
                            format!("ball1.mesh.size={size:e}"),
                            format!("ball2.mesh.size={size:e}"),
                            format!("ball1.mesh.pole_size={pole:e}"),
                            format!("ball2.mesh.pole_size={pole:e}"),
                        ];
                        for s in sets.iter().chain(&penalty) {
                            Override::parse(s)?.apply(&mut table)?;
                        }
                        let scene = Scene::from_table(&table, Path::new("."))
                            .map_err(|e| Error::Parse(format!("sweep case {id}: {e}")))?;
                        let params = CaseParams {
                            diameter: d,
                            v1n,
                            v2n,
                            v1t,
                            v2t,
                            mesh: mesh.name.clone(),
                        };
                        out.push(Case {
                            index: out.len(),
                            id,
                            params,
                            scene,
                        });
                    }
                }
            }
        }
        Ok(out)
    }
}

/// Diameter in mm for ids: `20`, `5`, `2.5`.
fn fmt_mm(d: f64) -> String {
    let mm = d * 1000.0;
    if (mm - mm.round()).abs() < 1e-9 {
        format!("{:02}", mm.round() as i64)
    } else {
        format!("{mm}")
    }
}

/// Runs one case: no impact, or the analytical model and (if given) the FE model.
pub fn run_case(case: &Case, fe: Option<FeRunner<'_>>, history_points: usize) -> CaseRecord {
    let start = Instant::now();
    let mut rec = CaseRecord {
        id: case.id.clone(),
        index: case.index,
        params: case.params.clone(),
        status: Status::Done,
        message: String::new(),
        analytic: None,
        fe: None,
        analytic_history: Vec::new(),
        fe_history: Vec::new(),
        wall_time_s: 0.0,
    };
    let result = (|| -> Result<()> {
        let touch = match approach(&case.scene)? {
            Approach::NoImpact { reason } => {
                rec.status = Status::NoImpact;
                rec.message = reason;
                return Ok(());
            }
            Approach::Impact(t) => t,
        };
        let (outcome, collision) = analytic_outcome(&case.scene, &touch)?;
        rec.analytic = Some(outcome);
        if let Some(n) = &collision.normal {
            rec.analytic_history = crate::analytic::history::history(n, history_points)
                .iter()
                .map(|s| [s.t, s.delta])
                .collect();
        }
        if let Some(fe) = fe {
            let r = fe(&case.scene)?;
            r.summary.outcome.check_finite("FE model")?;
            rec.fe_history = thin(&r.delta_history, history_points);
            rec.fe = Some(r.summary);
        }
        Ok(())
    })();
    if let Err(e) = result {
        rec.status = Status::Failed;
        rec.message = e.to_string();
    }
    rec.analytic_history
        .retain(|p| p.iter().all(|x| x.is_finite()));
    rec.fe_history.retain(|p| p.iter().all(|x| x.is_finite()));
    rec.wall_time_s = start.elapsed().as_secs_f64();
    rec
}

/// At most `n` evenly picked samples of `h` (first and last kept).
fn thin(h: &[[f64; 2]], n: usize) -> Vec<[f64; 2]> {
    if h.len() <= n || n < 2 {
        return h.to_vec();
    }
    (0..n).map(|i| h[i * (h.len() - 1) / (n - 1)]).collect()
}

/// Options of a sweep run.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// Output folder (case files go to `DIR/cases/`).
    pub out: PathBuf,
    /// Worker threads (≥ 1).
    pub jobs: usize,
    /// Which part of the sweep this process runs.
    pub shard: Shard,
    /// Minimum wall time per case (testing aid: makes a fast sweep slow enough to kill).
    pub pace: Duration,
    /// Report progress on stderr: a bar with one line per case on a terminal, a plain line
    /// every few seconds or 10 % elsewhere.
    pub verbose: bool,
    /// Run only the cases of this mesh setting (`None`: every setting).
    pub mesh: Option<String>,
}

/// Age after which a temporary file in a sweep folder shared by several shards is a killed
/// writer's (a live writer renames it within milliseconds).
const STALE_AFTER: Duration = Duration::from_secs(600);

/// What a sweep run did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SweepSummary {
    /// Cases in the whole sweep.
    pub total: usize,
    /// Cases of this shard.
    pub in_shard: usize,
    /// Cases of this shard found finished and skipped.
    pub skipped: usize,
    /// Cases run now.
    pub ran: usize,
    /// Of those, cases whose FE result was scaled from a similar case's run.
    pub scaled: usize,
    /// Cases of the whole sweep finished (all in `DIR/sweep.csv` if `csv_written`).
    pub in_csv: usize,
    /// Cases that failed (of the whole sweep).
    pub failed: usize,
    /// Whether this run rewrote `DIR/sweep.csv` (unsharded runs only: the shards of a job
    /// array share no file).
    pub csv_written: bool,
}

/// The cache of finished cases of the sweep in `out` (`out/cases/ID.json`).
pub fn case_cache(out: &Path) -> CaseCache {
    CaseCache::new(out.join("cases"))
}

/// Path of a case's result file.
pub fn case_path(out: &Path, id: &str) -> PathBuf {
    case_cache(out).path(id)
}

/// Reads a finished case file; `None` if absent or unreadable (then the case is rerun).
pub fn read_case(out: &Path, id: &str) -> Option<CaseRecord> {
    case_cache(out).read(id, |r: &CaseRecord| r.id == id)
}

/// Runs (the shard of) a sweep, skipping finished cases, then rewrites `DIR/sweep.csv` from
/// every finished case of the whole sweep.
pub fn run_sweep(
    spec: &SweepSpec,
    opts: &SweepOptions,
    fe: Option<FeRunner<'_>>,
) -> Result<SweepSummary> {
    if opts.jobs == 0 {
        return Err(Error::invalid("--jobs", 0, "jobs >= 1"));
    }
    let fe = if spec.model == SweepModel::Fe {
        fe
    } else {
        None
    };
    if spec.model == SweepModel::Fe && fe.is_none() {
        return Err(Error::External(
            "this sweep asks for the FE model, which is not available here".into(),
        ));
    }
    let cases = spec.cases()?;
    let selected = select(spec, &cases, opts.mesh.as_deref())?;
    let plan = shard_plan(spec, &selected, opts.shard.count);
    let mine: Vec<&Case> = selected
        .iter()
        .zip(&plan)
        .filter(|(_, &s)| s == opts.shard.index - 1)
        .map(|(c, _)| *c)
        .collect();
    let dir = opts.out.join("cases");
    let made_dir = !dir.exists();
    ensure_dir(&dir)?;
    let twin_of: HashMap<usize, (&Case, f64)> = twins(spec, &selected)
        .iter()
        .enumerate()
        .filter_map(|(i, t)| t.map(|(j, k)| (selected[i].index, (selected[j], k))))
        .collect();
    let result = run_cases(spec, opts, fe, &cases, &mine, &twin_of);
    if result.is_err() && made_dir {
        // A sweep that failed before finishing any case leaves no empty folders behind.
        let _ = std::fs::remove_dir(opts.out.join("running"));
        let _ = std::fs::remove_dir(&dir);
    }
    result
}

/// Runs the unfinished cases of `mine` (this shard's) and sums up: first those that run their
/// own FE model, then those of `twin_of` (case index → the similar case and the factor k),
/// whose FE result is their twin's scaled ([`crate::study::sweep::similarity::scaled_fe_case`]; their own
/// run when the twin has no finished FE result).
fn run_cases(
    spec: &SweepSpec,
    opts: &SweepOptions,
    fe: Option<FeRunner<'_>>,
    cases: &[Case],
    mine: &[&Case],
    twin_of: &HashMap<usize, (&Case, f64)>,
) -> Result<SweepSummary> {
    let dirs = [
        opts.out.join("cases"),
        opts.out.join("running"),
        opts.out.clone(),
    ];
    for d in &dirs {
        if opts.shard.count == 1 {
            remove_stale_temporaries(d)?;
        } else {
            // Other shards may be writing into the same folder right now (other nodes of a
            // job array): only temporaries far older than any write are a killed writer's.
            remove_temporaries_older_than(d, STALE_AFTER)?;
        }
    }
    let mut pending: Vec<&Case> = mine
        .iter()
        .copied()
        .filter(|c| read_case(&opts.out, &c.id).is_none())
        .collect();
    // Longest first, so that no worker is left with one long case at the end: cases with
    // tangential speed run a half model (about four times the work of a quarter model).
    pending.sort_by_key(|c| (c.params.v1t == 0.0 && c.params.v2t == 0.0, c.index));
    let skipped = mine.len() - pending.len();
    let dir = opts.out.join("cases");
    let shard_name = format!("{}/{}", opts.shard.index, opts.shard.count);
    let n_pending = pending.len();
    let progress = crate::study::common::progress::Cases::new(
        crate::study::common::progress::Mode::detect(opts.verbose),
        "sweep",
        n_pending,
    );
    let n_scaled = std::sync::atomic::AtomicUsize::new(0);
    // Workers of the pool stop on the caller's cancel request too (library callers).
    let token = crate::study::common::interrupt::current();
    let run_one = |c: &&Case| -> Result<()> {
        if crate::study::common::interrupt::requested() {
            return Err(Error::Interrupted(String::new()));
        }
        let t0 = Instant::now();
        mark_running(&opts.out, &c.id, &shard_name)?;
        let scaled = twin_of.get(&c.index).and_then(|(twin, k)| {
            let rec = read_case(&opts.out, &twin.id)?;
            let summary = rec.fe.filter(|_| rec.status == Status::Done)?;
            let run = FeCase {
                summary,
                delta_history: rec.fe_history,
            };
            let mut case = crate::study::sweep::similarity::scaled_fe_case(&run, *k);
            case.summary.scaled_from = Some(twin.id.clone());
            Some(case)
        });
        let rec = match (&scaled, fe) {
            (Some(case), Some(_)) => {
                let from = |_: &Scene| -> Result<FeCase> { Ok(case.clone()) };
                run_case(c, Some(&from), spec.history_points)
            }
            _ => run_case(c, fe, spec.history_points),
        };
        let mut rec = rec;
        if let (Some(from), Status::Done) = (
            rec.fe.as_ref().and_then(|f| f.scaled_from.clone()),
            rec.status,
        ) {
            n_scaled.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let k = twin_of.get(&c.index).map_or(1.0, |t| t.1);
            rec.message = format!("FE scaled from case {from} (similar: lengths and times x {k})");
        }
        if let Some(rest) = opts.pace.checked_sub(t0.elapsed()) {
            std::thread::sleep(rest);
        }
        if crate::study::common::interrupt::requested() {
            // The case may have been cut short: not recorded, so a resumed sweep reruns it.
            clear_running(&opts.out, &c.id);
            return Err(Error::Interrupted(String::new()));
        }
        case_cache(&opts.out).write(&c.id, &rec, Layout::Pretty)?;
        clear_running(&opts.out, &c.id);
        progress.case_done(
            rec.status == Status::Failed,
            &format!("{} {:?} ({:.2} s)", c.id, rec.status, rec.wall_time_s),
        );
        Ok(())
    };
    let work = |c: &&Case| -> Result<()> {
        crate::study::common::interrupt::within(token.as_ref(), || run_one(c))
    };
    // The cases that run their own FE model first, then those scaled from them.
    let (derived, own): (Vec<&Case>, Vec<&Case>) =
        pending.iter().partition(|c| twin_of.contains_key(&c.index));
    let run_all = |batch: &[&Case]| -> Result<()> {
        if opts.jobs > 1 && batch.len() > 1 {
            // More cases than one: spread whole cases over the workers (each FE run may
            // still use the pool for its own loops).
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(opts.jobs)
                .build()
                .map_err(|e| Error::External(format!("thread pool: {e}")))?;
            pool.install(|| batch.par_iter().with_max_len(1).try_for_each(work))
        } else {
            batch.iter().try_for_each(work)
        }
    };
    run_all(&own)
        .and_then(|()| run_all(&derived))
    .map_err(|e| match e {
        Error::Interrupted(_) => Error::Interrupted(format!(
            "after {} of {n_pending} cases: they are in {} (the same command resumes); sweep.csv not written",
            progress.counts().0,
            dir.display()
        )),
        other => other,
    })?;
    progress.finish();
    // Markers are gone with their cases: an empty folder of them says nothing (another
    // shard's live markers keep it).
    let _ = std::fs::remove_dir(opts.out.join("running"));
    // One writer only: shards of an array leave the CSV to an unsharded run or the report.
    let (in_csv, failed) = if opts.shard.count == 1 {
        write_csv(&opts.out, cases)?
    } else {
        let recs = read_records(&opts.out, cases);
        let failed = recs.iter().filter(|r| r.status == Status::Failed).count();
        (recs.len(), failed)
    };
    Ok(SweepSummary {
        total: cases.len(),
        in_shard: mine.len(),
        skipped,
        ran: n_pending,
        scaled: n_scaled.load(std::sync::atomic::Ordering::Relaxed),
        in_csv,
        failed,
        csv_written: opts.shard.count == 1,
    })
}

/// The CSV header (units in brackets).
pub const CSV_HEADER: &str = "id,mesh,diameter [m],v1n [m/s],v2n [m/s],v1t [m/s],v2t [m/s],status,\
e_fe [-],e_an [-],e_error_fe [-],v1n_after_fe [m/s],v1n_after_an [m/s],v2n_after_fe [m/s],v2n_after_an [m/s],\
v1t_after_fe [m/s],v1t_after_an [m/s],v2t_after_fe [m/s],v2t_after_an [m/s],\
delta_max_fe [m],delta_max_an [m],contact_duration_fe [s],contact_duration_an [s],\
eta_fe [-],eta_an [-],energy_error_fe [-],reduction,elements,element_cycles,wall_time [s],message";

fn num(x: Option<f64>) -> String {
    match x {
        Some(v) if v.is_finite() => format!("{v:.6e}"),
        _ => String::new(),
    }
}

/// One CSV row of a case record (normal = x, tangential = y of the scene frame).
pub fn csv_row(r: &CaseRecord) -> String {
    let p = &r.params;
    let fe = r.fe.as_ref().map(|f| &f.outcome);
    let an = r.analytic.as_ref();
    let both = |g: &dyn Fn(&Outcome) -> f64| [num(fe.map(g)), num(an.map(g))];
    let status = match r.status {
        Status::Done => "done",
        Status::NoImpact => "no_impact",
        Status::Failed => "failed",
    };
    let mut cols = vec![
        r.id.clone(),
        p.mesh.clone(),
        num(Some(p.diameter)),
        num(Some(p.v1n)),
        num(Some(p.v2n)),
        num(Some(p.v1t)),
        num(Some(p.v2t)),
        status.to_string(),
    ];
    cols.extend(both(&|o| o.e));
    cols.push(num(r.fe.as_ref().and_then(|f| f.e_error)));
    cols.extend(both(&|o| o.v1_after[0]));
    cols.extend(both(&|o| o.v2_after[0]));
    cols.extend(both(&|o| o.v1_after[1]));
    cols.extend(both(&|o| o.v2_after[1]));
    cols.extend(both(&|o| o.delta_max));
    cols.extend(both(&|o| o.contact_duration));
    cols.extend(both(&|o| o.eta));
    let f = r.fe.as_ref();
    cols.push(num(f.map(|f| f.energy_error)));
    cols.push(f.map_or(String::new(), |f| f.reduction.clone()));
    cols.push(f.map_or(String::new(), |f| f.elements.to_string()));
    cols.push(f.map_or(String::new(), |f| f.element_cycles.to_string()));
    cols.push(num(Some(r.wall_time_s)));
    cols.push(format!("\"{}\"", r.message.replace('"', "'")));
    cols.join(",")
}

/// Rewrites `DIR/sweep.csv` (atomically) from the finished case files of `cases`, in case
/// order; returns (rows written, failed rows).
pub fn write_csv(out: &Path, cases: &[Case]) -> Result<(usize, usize)> {
    let (text, rows, failed) = csv_text(out, cases);
    write_atomic(out.join("sweep.csv"), text.as_bytes())?;
    Ok((rows, failed))
}

/// The CSV text of the finished case files of `cases` in `out`, in case order, with the
/// number of rows and of failed rows.
pub fn csv_text(out: &Path, cases: &[Case]) -> (String, usize, usize) {
    let mut text = String::from(CSV_HEADER);
    text.push('\n');
    let (mut rows, mut failed) = (0, 0);
    for c in cases {
        if let Some(r) = read_case(out, &c.id) {
            text.push_str(&csv_row(&r));
            text.push('\n');
            rows += 1;
            failed += usize::from(r.status == Status::Failed);
        }
    }
    (text, rows, failed)
}

/// Reads every finished case record of `cases` from `out`.
pub fn read_records(out: &Path, cases: &[Case]) -> Vec<CaseRecord> {
    cases.iter().filter_map(|c| read_case(out, &c.id)).collect()
}
