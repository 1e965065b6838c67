//! The robustness matrix (`twoball stress`): many extreme scenes, each run as a child `twoball run`
//! process under a wall-time cap, classified as completed (energy error under tolerance),
//! completed but flagged, stopped with a clear reason, or failed silently (NaN/inf in the
//! output, panic, timeout, or a physically impossible result without a stop).
//!
//! The matrix file (TOML):
//! ```toml
//! [stress]
//! timeout_s = 120                 # per-case wall-time cap, s
//! energy_tolerance = 0.01         # relative energy error of a clean run
//! size_per_diameter = 0.3         # coarse bulk mesh, fraction of each ball's diameter
//! pole_size_per_diameter = 0.15   # pole mesh, fraction of each ball's diameter
//! quick = ["speed-v1"]            # case ids of the --quick subset
//! [axis]                          # named axes: lists of labelled `--set` override lists
//! speed = [{ label = "v1", set = ["ball1.velocity=[0.5,0,0]", "ball2.velocity=[-0.5,0,0]"] }]
//! [[group]]                       # each group is the cartesian product of its axes
//! axes = ["speed"]
//! base = "default"                # or "wall": ball 1 on a rigid wall (scene::WALL_SCENE)
//! ```
//! Per-case records go to `DIR/cases/ID.json` (atomic; finished cases are skipped on
//! restart, as in the sweep), the summary to `DIR/summary.md`.

use crate::atomic::{ensure_dir, remove_stale_temporaries, write_atomic};
use crate::error::{Error, Result};
use crate::study::records::case_cache::{CaseCache, Layout};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// One labelled value of an axis: the overrides it applies.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisValue {
    /// Short label used in case ids (letters, digits, `.`, `-`, `+`).
    pub label: String,
    /// `--set PATH=VALUE` overrides.
    pub set: Vec<String>,
}

/// A product of axes.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Group {
    /// Axis names (keys of `[axis]`).
    pub axes: Vec<String>,
    /// The built-in scene its overrides apply to (default: the two-ball default scene).
    #[serde(default)]
    pub base: Base,
}

/// The built-in scene a case's overrides apply to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Base {
    /// The default scene: two copper-fe balls, ±1 m/s head-on.
    #[default]
    Default,
    /// Ball 1 of the default scene against a rigid wall ([`crate::scene::WALL_SCENE`]).
    Wall,
}

impl Base {
    /// The scene text.
    pub fn text(self) -> &'static str {
        match self {
            Base::Default => crate::scene::DEFAULT_SCENE,
            Base::Wall => crate::scene::WALL_SCENE,
        }
    }

    /// The balls meshed by the scene (a wall scene's ball2 is ball 1's image).
    fn balls(self) -> &'static [&'static str] {
        match self {
            Base::Default => &["ball1", "ball2"],
            Base::Wall => &["ball1"],
        }
    }
}

/// Global settings of the matrix.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StressSettings {
    /// Per-case wall-time cap, s.
    pub timeout_s: f64,
    /// Relative energy error below which a completed run is clean.
    pub energy_tolerance: f64,
    /// Default bulk element size, fraction of the ball's diameter.
    pub size_per_diameter: f64,
    /// Default pole element size, fraction of the ball's diameter.
    pub pole_size_per_diameter: f64,
    /// Ids of the `--quick` subset.
    #[serde(default)]
    pub quick: Vec<String>,
}

/// A parsed matrix file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StressSpec {
    /// Settings.
    pub stress: StressSettings,
    /// Named axes.
    pub axis: BTreeMap<String, Vec<AxisValue>>,
    /// Groups (products of axes).
    pub group: Vec<Group>,
}

/// One case: id and the overrides on the default scene (mesh sizes added).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StressCase {
    /// Id, e.g. `speed-material-v20-rubber` (`wall-…` on the wall scene).
    pub id: String,
    /// The scene the overrides apply to.
    #[serde(default)]
    pub base: Base,
    /// `--set` overrides in order.
    pub sets: Vec<String>,
}

/// How a case ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Class {
    /// Completed with energy error under the tolerance (or no impact).
    Clean,
    /// Completed with a larger energy error (reported, flagged).
    Flagged,
    /// Stopped with a one-line error message.
    Stopped,
    /// NaN/inf in the output, panic, timeout or an impossible result without a stop.
    Silent,
}

/// The record of one case.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StressRecord {
    /// Case id.
    pub id: String,
    /// Overrides run.
    pub sets: Vec<String>,
    /// Classification.
    pub class: Class,
    /// Completed (`completed`, `no_impact`) or `stopped`/`panic`/`timeout`/`killed`.
    pub status: String,
    /// Why it stopped, or the FE stop reason.
    pub reason: String,
    /// Relative energy error (completed runs).
    pub energy_error: Option<f64>,
    /// Coefficient of restitution (completed runs).
    pub e: Option<f64>,
    /// Rigid-body kinetic energy after / before.
    pub kinetic_ratio: Option<f64>,
    /// A NaN/inf/null number was found in results.json or history.csv.
    pub non_finite: bool,
    /// Wall time of the case, s.
    pub wall_time_s: f64,
}

fn valid_label(s: &str) -> bool {
    !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '+'))
}

impl StressSpec {
    /// Reads a matrix file.
    pub fn from_file(path: &Path) -> Result<StressSpec> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Self::from_toml(&text, &path.display().to_string())
    }

    /// Parses matrix text; `origin` names it in errors.
    pub fn from_toml(text: &str, origin: &str) -> Result<StressSpec> {
        let spec: StressSpec =
            toml::from_str(text).map_err(|e| Error::Parse(format!("{origin}: {e}")))?;
        let s = &spec.stress;
        if !(s.timeout_s > 0.0 && s.timeout_s <= 86_400.0) {
            return Err(Error::invalid(
                "stress.timeout_s",
                s.timeout_s,
                "0 < t <= 86400 s",
            ));
        }
        if !(s.energy_tolerance > 0.0 && s.energy_tolerance < 1.0) {
            return Err(Error::invalid(
                "stress.energy_tolerance",
                s.energy_tolerance,
                "0 < tolerance < 1",
            ));
        }
        for (k, v) in [
            ("stress.size_per_diameter", s.size_per_diameter),
            ("stress.pole_size_per_diameter", s.pole_size_per_diameter),
        ] {
            if !(v > 0.0 && v <= 1.0) {
                return Err(Error::invalid(k, v, "0 < fraction <= 1"));
            }
        }
        for (name, values) in &spec.axis {
            if values.is_empty() {
                return Err(Error::invalid(
                    format!("axis.{name}"),
                    "[]",
                    "a non-empty list",
                ));
            }
            for v in values {
                if !valid_label(&v.label) {
                    return Err(Error::invalid(
                        format!("axis.{name} label"),
                        &v.label,
                        "letters, digits, '.', '-', '+'",
                    ));
                }
            }
        }
        for (i, g) in spec.group.iter().enumerate() {
            if g.axes.is_empty() {
                return Err(Error::invalid(
                    format!("group[{i}].axes"),
                    "[]",
                    "at least one axis",
                ));
            }
            for a in &g.axes {
                if !spec.axis.contains_key(a) {
                    return Err(Error::invalid(
                        format!("group[{i}].axes"),
                        a,
                        "names of [axis] entries",
                    ));
                }
            }
        }
        let cases = spec.cases()?;
        for q in &spec.stress.quick {
            if !cases.iter().any(|c| &c.id == q) {
                return Err(Error::invalid("stress.quick", q, "ids of matrix cases"));
            }
        }
        Ok(spec)
    }

    /// Every case, group by group; ids are unique (a repeated id is an error).
    pub fn cases(&self) -> Result<Vec<StressCase>> {
        let mut out: Vec<StressCase> = Vec::new();
        for g in &self.group {
            let mut partial: Vec<(Vec<String>, Vec<String>)> = vec![(vec![], vec![])];
            for a in &g.axes {
                let mut next = Vec::new();
                for (labels, sets) in &partial {
                    for v in &self.axis[a] {
                        let mut l = labels.clone();
                        l.push(v.label.clone());
                        let mut s = sets.clone();
                        s.extend(v.set.iter().cloned());
                        next.push((l, s));
                    }
                }
                partial = next;
            }
            for (labels, sets) in partial {
                let prefix = if g.base == Base::Wall { "wall-" } else { "" };
                let id = format!("{prefix}{}_{}", g.axes.join("-"), labels.join("_"));
                let sets = self.with_mesh(&id, g.base, sets)?;
                if out.iter().any(|c| c.id == id) {
                    return Err(Error::invalid("group", &id, "unique case ids"));
                }
                out.push(StressCase {
                    id,
                    base: g.base,
                    sets,
                });
            }
        }
        Ok(out)
    }

    /// Adds the default coarse mesh (sizes relative to each ball's diameter) unless the case
    /// sets a ball's mesh itself; checks that the case is a valid scene.
    fn with_mesh(&self, id: &str, base: Base, mut sets: Vec<String>) -> Result<Vec<String>> {
        use crate::scene::{Override, Scene};
        let parse = |sets: &[String]| -> Result<Scene> {
            let ov = sets
                .iter()
                .map(|s| Override::parse(s))
                .collect::<Result<Vec<_>>>()?;
            Scene::from_toml(base.text(), Path::new("."), &ov)
                .map_err(|e| Error::Parse(format!("stress case {id}: {e}")))
        };
        let scene = parse(&sets)?;
        for (b, d) in [
            ("ball1", scene.ball1.diameter),
            ("ball2", scene.ball2.diameter),
        ]
        .into_iter()
        .filter(|(b, _)| base.balls().contains(b))
        {
            if !sets.iter().any(|s| s.starts_with(&format!("{b}.mesh"))) {
                let size = self.stress.size_per_diameter * d;
                let pole = (self.stress.pole_size_per_diameter * d).min(size);
                sets.push(format!("{b}.mesh.size={size:e}"));
                sets.push(format!("{b}.mesh.pole_size={pole:e}"));
            }
        }
        parse(&sets)?;
        Ok(sets)
    }
}

/// Options of a stress run.
#[derive(Debug, Clone)]
pub struct StressOptions {
    /// Output folder.
    pub out: PathBuf,
    /// Concurrent cases.
    pub jobs: usize,
    /// Only the `stress.quick` cases.
    pub quick: bool,
    /// The `twoball` executable to run each case with.
    pub exe: PathBuf,
    /// Report progress on stderr (a bar on a terminal, plain lines elsewhere).
    pub verbose: bool,
}

/// Counts of a finished matrix.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct StressCounts {
    /// Cases.
    pub total: usize,
    /// Completed with energy error under tolerance.
    pub clean: usize,
    /// Completed, energy error above tolerance.
    pub flagged: usize,
    /// Stopped with a clear message.
    pub stopped: usize,
    /// Silent failures.
    pub silent: usize,
}

/// The cache of finished case records in `out` (`out/cases/ID.json`).
fn records(out: &Path) -> CaseCache {
    CaseCache::new(out.join("cases"))
}

fn read_record(out: &Path, id: &str) -> Option<StressRecord> {
    records(out).read(id, |r: &StressRecord| r.id == id)
}

/// Whether a CSV text holds a non-finite number (`NaN`, `inf`).
pub fn csv_has_non_finite(text: &str) -> bool {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '+' || c == '-'))
        .any(|tok| {
            let t = tok.trim_start_matches(['+', '-']).to_ascii_lowercase();
            t == "nan" || t == "inf" || t == "infinity"
        })
}

/// Keys of results.json that may legitimately be `null` (unset options). JSON writes a
/// non-finite number as `null`, so a `null` anywhere else is a NaN or infinity.
const OPTIONAL_KEYS: [&str; 12] = [
    "position",
    "end_time",
    "hold_time",
    "history_interval",
    "fe",
    "analytic",
    "relative_difference",
    // `error_estimate`'s documented nulls: no order with two meshes or an oscillating
    // ladder, no relative error of a zero value, no tolerance unless asked.
    "observed_order",
    "order_used",
    "relative_error",
    "tolerance",
    "tolerance_met",
];

/// Whether a results.json value holds a non-finite number (a `null` outside [`OPTIONAL_KEYS`]).
pub fn json_has_non_finite(v: &serde_json::Value) -> bool {
    use serde_json::Value;
    match v {
        Value::Array(a) => a.iter().any(|x| x.is_null() || json_has_non_finite(x)),
        Value::Object(m) => m.iter().any(|(k, x)| {
            (x.is_null() && !OPTIONAL_KEYS.contains(&k.as_str())) || json_has_non_finite(x)
        }),
        Value::Number(n) => n.as_f64().is_none_or(|f| !f.is_finite()),
        _ => false,
    }
}

/// Rigid-body kinetic energy (J) of the two balls (of ball 1 on a wall) from results.json's
/// scene and velocities.
fn kinetic(v: &serde_json::Value, after: bool) -> Option<f64> {
    let mut k = 0.0;
    let balls = if v["scene"]["wall"].is_object() { 1 } else { 2 };
    for (b, vk, wk) in [
        ("ball1", "v1_after", "w1_after"),
        ("ball2", "v2_after", "w2_after"),
    ]
    .into_iter()
    .take(balls)
    {
        let ball = &v["scene"][b];
        let d = ball["diameter"].as_f64()?;
        let rho = ball["material"]["rho"].as_f64()?;
        let m = rho * std::f64::consts::PI * d.powi(3) / 6.0;
        let i = 0.1 * m * d * d;
        let vec3 = |x: &serde_json::Value| -> Option<[f64; 3]> {
            let a = x.as_array()?;
            Some([
                a.first()?.as_f64()?,
                a.get(1)?.as_f64()?,
                a.get(2)?.as_f64()?,
            ])
        };
        let (vel, w) = if after {
            (vec3(&v[vk])?, vec3(&v[wk])?)
        } else {
            (vec3(&ball["velocity"])?, vec3(&ball["angular_velocity"])?)
        };
        k += 0.5 * m * vel.iter().map(|x| x * x).sum::<f64>()
            + 0.5 * i * w.iter().map(|x| x * x).sum::<f64>();
    }
    Some(k)
}

/// Classifies a finished child run: exit status, stderr and the output folder.
#[allow(clippy::too_many_arguments)]
pub fn classify(
    id: &str,
    sets: &[String],
    exit: Option<i32>,
    timed_out: bool,
    stderr: &str,
    run_dir: &Path,
    tol: f64,
    wall: f64,
) -> StressRecord {
    let mut r = StressRecord {
        id: id.into(),
        sets: sets.to_vec(),
        class: Class::Silent,
        status: String::new(),
        reason: String::new(),
        energy_error: None,
        e: None,
        kinetic_ratio: None,
        non_finite: false,
        wall_time_s: wall,
    };
    let last_line = stderr
        .lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .unwrap_or("");
    if timed_out {
        r.status = "timeout".into();
        r.reason = format!("no answer within the wall-time cap ({wall:.0} s)");
        return r;
    }
    match exit {
        Some(0) => {}
        Some(1) if last_line.starts_with("error: ") && last_line.len() > 10 => {
            r.class = Class::Stopped;
            r.status = "stopped".into();
            r.reason = last_line.trim_start_matches("error: ").to_string();
            return r;
        }
        Some(101) => {
            r.status = "panic".into();
            r.reason = last_line.to_string();
            return r;
        }
        other => {
            r.status = "killed".into();
            r.reason = format!("exit {other:?} without a clear message: {last_line}");
            return r;
        }
    }
    let read = |n: &str| std::fs::read_to_string(run_dir.join(n));
    let (Ok(json), Ok(csv)) = (read("results.json"), read("history.csv")) else {
        r.status = "completed".into();
        r.reason = "exit 0 but results.json or history.csv missing".into();
        return r;
    };
    let Ok(v) = serde_json::from_str::<serde_json::Value>(&json) else {
        r.status = "completed".into();
        r.reason = "results.json unreadable".into();
        return r;
    };
    r.non_finite = json_has_non_finite(&v) || csv_has_non_finite(&csv);
    if v["impact"] == serde_json::Value::Bool(false) {
        r.status = "no_impact".into();
        r.reason = v["no_impact_reason"].as_str().unwrap_or("").to_string();
        r.class = if r.non_finite {
            Class::Silent
        } else {
            Class::Clean
        };
        return r;
    }
    r.status = "completed".into();
    r.reason = v["fe"]["stop_reason"].as_str().unwrap_or("").to_string();
    r.energy_error = v["energy_error"].as_f64();
    r.e = v["e"].as_f64();
    r.kinetic_ratio = match (kinetic(&v, false), kinetic(&v, true)) {
        (Some(b), Some(a)) if b > 0.0 => Some(a / b),
        _ => None,
    };
    let err = r.energy_error.unwrap_or(f64::NAN);
    let allowed = tol.max(err);
    // e above 1 is impossible where the normal motion carries all the kinetic energy (a
    // head-on impact without spin); an oblique one (results.json `tangential`) or a spinning
    // one (a twist about the normal has no `tangential`) may pass energy of its sliding or
    // spin into the rebound (its run warns), so there only the kinetic energy is bounded, and
    // e above 1 flags the case.
    let spins = |ball: &str| {
        v["scene"][ball]["angular_velocity"]
            .as_array()
            .is_some_and(|w| w.iter().any(|c| c.as_f64().is_some_and(|c| c != 0.0)))
    };
    let head_on = v["tangential"].is_null() && !spins("ball1") && !spins("ball2");
    let e_above = r.e.is_some_and(|e| e > 1.0 + allowed);
    let impossible = (head_on && e_above) || r.kinetic_ratio.is_some_and(|k| k > 1.0 + allowed);
    r.class = if r.non_finite || !err.is_finite() || r.e.is_none() || r.kinetic_ratio.is_none() {
        r.reason = format!("non-finite or missing number in the output; {}", r.reason);
        Class::Silent
    } else if impossible {
        r.reason = format!(
            "impossible result without a stop (e = {:.4}, KE after/before = {:.4}); {}",
            r.e.unwrap_or(f64::NAN),
            r.kinetic_ratio.unwrap_or(f64::NAN),
            r.reason
        );
        Class::Silent
    } else if e_above {
        r.reason = format!(
            "e = {:.4} above 1 with the kinetic energy at {:.4} of its start: energy of the \
             sliding or spin in the rebound; {}",
            r.e.unwrap_or(f64::NAN),
            r.kinetic_ratio.unwrap_or(f64::NAN),
            r.reason
        );
        Class::Flagged
    } else if err < tol {
        Class::Clean
    } else {
        Class::Flagged
    };
    r
}

/// Runs one case as a child process under the wall-time cap.
fn run_one(case: &StressCase, spec: &StressSpec, opts: &StressOptions) -> Result<StressRecord> {
    let dir = opts.out.join("runs").join(&case.id);
    if dir.exists() {
        std::fs::remove_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    }
    ensure_dir(&dir)?;
    let err_path = dir.join("stderr.txt");
    let out_path = dir.join("stdout.txt");
    let mut cmd = Command::new(&opts.exe);
    cmd.arg("run").arg("--out").arg(&dir);
    if case.base != Base::Default {
        let scene = dir.join("scene.toml");
        write_atomic(&scene, case.base.text().as_bytes())?;
        cmd.arg(&scene);
    }
    for s in &case.sets {
        cmd.arg("--set").arg(s);
    }
    let stdout = std::fs::File::create(&out_path).map_err(|e| Error::io(&out_path, e))?;
    let stderr = std::fs::File::create(&err_path).map_err(|e| Error::io(&err_path, e))?;
    let start = Instant::now();
    let mut child = cmd
        .env("RAYON_NUM_THREADS", "1")
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(stderr)
        .spawn()
        .map_err(|e| Error::External(format!("cannot start {}: {e}", opts.exe.display())))?;
    let cap = Duration::from_secs_f64(spec.stress.timeout_s);
    let (status, timed_out) = loop {
        match child.try_wait() {
            Ok(Some(s)) => break (Some(s), false),
            Ok(None) if crate::study::common::interrupt::requested() => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(Error::Interrupted(String::new()));
            }
            Ok(None) if start.elapsed() > cap => {
                let _ = child.kill();
                let _ = child.wait();
                break (None, true);
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => return Err(Error::External(format!("case {}: {e}", case.id))),
        }
    };
    let wall = start.elapsed().as_secs_f64();
    let stderr_text = std::fs::read_to_string(&err_path).unwrap_or_default();
    Ok(classify(
        &case.id,
        &case.sets,
        status.and_then(|s| s.code()),
        timed_out,
        &stderr_text,
        &dir,
        spec.stress.energy_tolerance,
        wall,
    ))
}

/// Runs the matrix (or its quick subset), skipping finished cases, then writes
/// `DIR/summary.md`; returns the counts and the summary text.
pub fn run_stress(spec: &StressSpec, opts: &StressOptions) -> Result<(StressCounts, String)> {
    if opts.jobs == 0 {
        return Err(Error::invalid("--jobs", 0, "jobs >= 1"));
    }
    let mut cases = spec.cases()?;
    if opts.quick {
        cases.retain(|c| spec.stress.quick.contains(&c.id));
    }
    let dir = opts.out.join("cases");
    ensure_dir(&dir)?;
    remove_stale_temporaries(&dir)?;
    let pending: Vec<&StressCase> = cases
        .iter()
        .filter(|c| read_record(&opts.out, &c.id).is_none())
        .collect();
    let progress = crate::study::common::progress::Cases::new(
        crate::study::common::progress::Mode::detect(opts.verbose),
        "stress",
        pending.len(),
    );
    let next = AtomicUsize::new(0);
    let failure: std::sync::Mutex<Option<Error>> = std::sync::Mutex::new(None);
    std::thread::scope(|s| {
        for _ in 0..opts.jobs.min(pending.len().max(1)) {
            s.spawn(|| loop {
                if crate::study::common::interrupt::requested() {
                    break;
                }
                let k = next.fetch_add(1, Ordering::SeqCst);
                let Some(c) = pending.get(k) else { break };
                let res = run_one(c, spec, opts).and_then(|rec| {
                    if crate::study::common::interrupt::requested() {
                        // Cut short: not recorded, so a resumed matrix reruns it.
                        return Err(Error::Interrupted(String::new()));
                    }
                    records(&opts.out).write(&c.id, &rec, Layout::Pretty)?;
                    progress.case_done(
                        rec.class == Class::Silent,
                        &format!(
                            "{} {:?} ({:.1} s) {}",
                            c.id, rec.class, rec.wall_time_s, rec.reason
                        ),
                    );
                    Ok(())
                });
                if let Err(e) = res {
                    *failure.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                    break;
                }
            });
        }
    });
    let failure = failure.into_inner().unwrap_or_else(|p| p.into_inner());
    match failure {
        _ if crate::study::common::interrupt::requested() => {
            return Err(Error::Interrupted(format!(
                "after {} of {} cases: they are in {} (the same command resumes); summary.md not written",
                progress.counts().0,
                pending.len(),
                dir.display()
            )))
        }
        Some(e) => return Err(e),
        None => progress.finish(),
    }
    let records: Vec<StressRecord> = cases
        .iter()
        .filter_map(|c| read_record(&opts.out, &c.id))
        .collect();
    let (counts, text) = summary(&records, spec.stress.energy_tolerance);
    write_atomic(opts.out.join("summary.md"), text.as_bytes())?;
    Ok((counts, text))
}

fn fmt_opt(x: Option<f64>, prec: usize) -> String {
    match x {
        Some(v) if v.is_finite() => format!("{v:.prec$e}"),
        _ => "-".into(),
    }
}

/// Counts and the markdown summary of finished records.
pub fn summary(records: &[StressRecord], tol: f64) -> (StressCounts, String) {
    let mut c = StressCounts {
        total: records.len(),
        ..Default::default()
    };
    for r in records {
        match r.class {
            Class::Clean => c.clean += 1,
            Class::Flagged => c.flagged += 1,
            Class::Stopped => c.stopped += 1,
            Class::Silent => c.silent += 1,
        }
    }
    let wall: f64 = records.iter().map(|r| r.wall_time_s).sum();
    let mut t = format!(
        "# Stress matrix summary\n\n\
         | cases | completed, energy error < {:.0} % | completed, flagged (larger error) | stopped with a reason | silent failures |\n\
         |---|---|---|---|---|\n| {} | {} | {} | {} | {} |\n\n\
         Sum of case wall times: {wall:.0} s. Silent failure = NaN/inf in the output, panic, \
         timeout, or a physically impossible result (kinetic energy ratio above 1 + tolerance, \
         or e above it in a head-on impact) without a stop. Flagged: an energy error above \
         the tolerance, or e above 1 + tolerance in an oblique or spinning impact whose \
         kinetic energy did not grow.\n\n\
         | case | class | status | energy error | e | KE after/before | NaN | wall [s] | reason |\n\
         |---|---|---|---|---|---|---|---|---|\n",
        tol * 100.0,
        c.total,
        c.clean,
        c.flagged,
        c.stopped,
        c.silent
    );
    for r in records {
        t.push_str(&format!(
            "| {} | {:?} | {} | {} | {} | {} | {} | {:.1} | {} |\n",
            r.id,
            r.class,
            r.status,
            fmt_opt(r.energy_error, 2),
            r.e.map_or("-".into(), |e| format!("{e:.4}")),
            r.kinetic_ratio.map_or("-".into(), |k| format!("{k:.4}")),
            if r.non_finite { "yes" } else { "no" },
            r.wall_time_s,
            r.reason.replace('|', "/")
        ));
    }
    (c, t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn a_null_is_a_non_finite_number_except_where_documented() {
        // An error bar's documented nulls (two meshes: no observed order; no tolerance).
        let bar = json!({"e": 0.3, "error_estimate": {"e": {"finest": 0.3, "error": 0.01,
            "observed_order": null, "order_used": 2.0, "relative_error": 0.03},
            "tolerance": null, "tolerance_met": null}});
        assert!(!json_has_non_finite(&bar));
        // A NaN written as null where a number belongs.
        let nan = json!({"e": null});
        assert!(json_has_non_finite(&nan));
        let nan_bar = json!({"error_estimate": {"e": {"error": null}}});
        assert!(json_has_non_finite(&nan_bar));
        assert!(json_has_non_finite(&json!({"v1_after": [1.0, null, 0.0]})));
        assert!(csv_has_non_finite("t [s],e\n1,NaN\n") && !csv_has_non_finite("t [s]\n1e-3\n"));
    }
}
