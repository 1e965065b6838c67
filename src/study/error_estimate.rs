//! A run's own error bar: the same scene on a ladder of meshes (each level halves the pole and
//! the bulk element size of the one before), and the error estimate of e, δ_max and the
//! contact duration from it ([`super::convergence`]).
//!
//! The ladder is model-agnostic: [`run_ladder`] takes a closure `run(level)` that runs the
//! scene on mesh level `level` (0 the scene's own mesh, −1 the next coarser, +1 the next finer)
//! and returns its [`LevelOutcome`]; the 3D model's closure is [`scene_at_level`] followed by
//! a run, and any other model plugs in the same way.

pub use super::converged_scene::EstimateMethod;
use super::convergence::{estimate, Estimate};
use crate::error::{Error, Result};
use crate::scene::{MeshSettings, Scene};
use serde::Serialize;

/// The refinement ratio of the ladder: each level halves the element sizes.
pub const LADDER_RATIO: f64 = 2.0;
/// The default cap on levels finer than the scene's own mesh with `--tolerance`.
pub const DEFAULT_MAX_REFINEMENTS: u32 = 2;

/// What one mesh level of the ladder produced.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LevelOutcome {
    /// Ladder level: 0 the scene's mesh, negative coarser, positive finer.
    pub level: i32,
    /// Pole element size of ball 1, m.
    pub pole_size: f64,
    /// Bulk element size of ball 1, m.
    pub size: f64,
    /// Coefficient of restitution e, -.
    pub e: f64,
    /// Maximum approach δ_max, m.
    pub delta_max: f64,
    /// Contact duration, s.
    pub contact_duration: f64,
    /// Wall time of the run, s.
    pub wall_time_s: f64,
    /// The section model's phase ensemble behind e, δ_max and the contact duration (means
    /// over its meshes); None for a single run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phase: Option<PhaseSummary>,
}

/// What a level's phase ensemble adds ([`super::phase_ensemble`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseSummary {
    /// Meshes of the ensemble (the scene's own and M − 1 with scaled pole sizes).
    pub meshes: usize,
    /// Ring ratio q: the pole sizes run over q^{j/M}, -.
    pub ring_ratio: f64,
    /// Sampling error of the mean e (even members against all), -.
    pub e_sampling_error: f64,
    /// Smallest e of the members, -.
    pub e_min: f64,
    /// Largest e of the members, -.
    pub e_max: f64,
}

/// Which levels to run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum LadderPlan {
    /// Levels −1 and 0: the order assumed (twice the cost of one run in 3D, less in 2D).
    TwoLevels,
    /// Levels −2, −1 and 0: the observed order.
    ThreeLevels,
    /// Levels −1, 0, then +1, +2, … until the relative estimate of e is at most `tolerance`,
    /// or `max_refinements` levels beyond 0 have run.
    Tolerance {
        /// Target relative error estimate of e, -.
        tolerance: f64,
        /// Cap on levels finer than 0.
        max_refinements: u32,
    },
}

/// The error estimate written as results.json's `error_estimate`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorEstimate {
    /// Refinement ratio between levels, -.
    pub ratio: f64,
    /// Coefficient of restitution e, -.
    pub e: Estimate,
    /// Maximum approach δ_max, m.
    pub delta_max: Estimate,
    /// Contact duration, s.
    pub contact_duration: Estimate,
    /// The runs of the ladder, coarse to fine (the finest is the reported run).
    pub meshes: Vec<LevelOutcome>,
    /// The requested relative tolerance on e, - (with `--tolerance`).
    pub tolerance: Option<f64>,
    /// Whether the estimate of e met the tolerance (with `--tolerance`).
    pub tolerance_met: Option<bool>,
    /// How the estimate was obtained: the scene's own ladder, or the banded family that
    /// `--tolerance` runs on a head-on section scene it covers.
    pub method: EstimateMethod,
}

impl ErrorEstimate {
    /// The estimate from ladder runs (coarse to fine, at least two).
    pub fn from_runs(meshes: Vec<LevelOutcome>, tolerance: Option<f64>) -> Result<ErrorEstimate> {
        let of = |f: fn(&LevelOutcome) -> f64, what: &str| -> Result<Estimate> {
            let v: Vec<f64> = meshes.iter().map(f).collect();
            estimate(&v, LADDER_RATIO).ok_or_else(|| {
                Error::Numerical(format!(
                    "error estimate of {what}: needs two or more finite values, got {v:?}"
                ))
            })
        };
        let mut e = of(|m| m.e, "e")?;
        if let Some(p) = meshes.last().and_then(|m| m.phase) {
            // The ensemble's mean still carries its sampling error.
            e = e.with_error(e.error + p.e_sampling_error);
        }
        let tolerance_met = tolerance.map(|t| meets(&e, t));
        Ok(ErrorEstimate {
            ratio: LADDER_RATIO,
            delta_max: of(|m| m.delta_max, "delta_max")?,
            contact_duration: of(|m| m.contact_duration, "contact_duration")?,
            e,
            meshes,
            tolerance,
            tolerance_met,
            method: EstimateMethod::SceneLadder {
                why_not_banded: None,
            },
        })
    }

    /// One line for the terminal: each quantity with its bar and the ladder's flag.
    pub fn summary(&self) -> String {
        let levels: Vec<String> = self.meshes.iter().map(|m| m.level.to_string()).collect();
        let one = |name: &str, unit: &str, q: &Estimate| {
            let rel = q
                .relative_error
                .map_or("-".into(), |r| format!("{:.2}%", 100.0 * r));
            let order = match (q.observed_order, q.order_used) {
                (Some(p), _) => format!("p = {p:.2}"),
                (None, Some(p)) => format!("p = {p} assumed"),
                _ => "no order".into(),
            };
            format!(
                "{name} {:.6e}{unit} ± {:.2e} ({rel}; {order}; {})",
                q.extrapolated,
                q.error,
                q.behaviour.name()
            )
        };
        let family = match &self.method {
            EstimateMethod::SceneLadder { .. } => "mesh levels".to_string(),
            EstimateMethod::BandedFamily {
                band_split,
                band_edge_m,
                mass_scaling,
                ..
            } => format!(
                "banded family, rings at {:.0} µm split {band_split}-fold, mass scaling {mass_scaling:.1e}, levels",
                band_edge_m * 1e6
            ),
        };
        let mut s = format!(
            "error estimate ({family} {}): {}; {}; {}",
            levels.join(", "),
            one("e", "", &self.e),
            one("delta_max", " m", &self.delta_max),
            one("contact duration", " s", &self.contact_duration)
        );
        if let (Some(t), Some(met)) = (self.tolerance, self.tolerance_met) {
            s.push_str(&format!(
                "; tolerance {:.3}% on e {}",
                100.0 * t,
                if met { "met" } else { "NOT met" }
            ));
        }
        if let EstimateMethod::SceneLadder {
            why_not_banded: Some(why),
        } = &self.method
        {
            s.push_str(&format!("; the scene's own ladder ran: {why}"));
        }
        s
    }
}

/// True when the relative estimate of `e` is at most `tolerance`.
fn meets(e: &Estimate, tolerance: f64) -> bool {
    e.relative_error.is_some_and(|r| r <= tolerance)
}

/// Runs the ladder `plan` with `run(level)` and returns the estimate; the last run is the
/// finest. Errors of `run` pass through (with the level named).
pub fn run_ladder(
    plan: LadderPlan,
    mut run: impl FnMut(i32) -> Result<LevelOutcome>,
) -> Result<ErrorEstimate> {
    let mut at = |level: i32| run(level).map_err(|e| at_level(e, level));
    match plan {
        LadderPlan::TwoLevels => ErrorEstimate::from_runs(vec![at(-1)?, at(0)?], None),
        LadderPlan::ThreeLevels => ErrorEstimate::from_runs(vec![at(-2)?, at(-1)?, at(0)?], None),
        LadderPlan::Tolerance {
            tolerance,
            max_refinements,
        } => {
            let mut runs = vec![at(-1)?, at(0)?];
            loop {
                let est = ErrorEstimate::from_runs(runs.clone(), Some(tolerance))?;
                let finest = runs.last().map_or(0, |r| r.level);
                if est.tolerance_met == Some(true) || finest >= max_refinements as i32 {
                    return Ok(est);
                }
                runs.push(at(finest + 1)?);
            }
        }
    }
}

/// `e` with its message prefixed by the ladder level (field errors already name theirs).
pub(crate) fn at_level(e: Error, level: i32) -> Error {
    let tag = |m: String| format!("mesh level {level}: {m}");
    match e {
        Error::Numerical(m) => Error::Numerical(tag(m)),
        Error::Parse(m) => Error::Parse(tag(m)),
        Error::External(m) => Error::External(tag(m)),
        other => other,
    }
}

/// The scene with every built-in mesh scaled to ladder level `level`: pole and bulk sizes
/// times 2^−level. Fails for a mesh read from a file, or when a coarser level's bulk size
/// would exceed the ball's radius (the mesher's limit).
pub fn scene_at_level(scene: &Scene, level: i32) -> Result<Scene> {
    let scale = LADDER_RATIO.powi(-level);
    let mut s = scene.clone();
    for (name, ball) in [("ball1", &mut s.ball1), ("ball2", &mut s.ball2)] {
        match &mut ball.mesh {
            MeshSettings::File { .. } => {
                return Err(Error::Parse(format!(
                    "{name}.mesh.file is set: an error estimate needs the built-in mesher, \
                     whose sizes the mesh ladder scales"
                )))
            }
            MeshSettings::Builtin { size, pole_size } => {
                *size *= scale;
                *pole_size *= scale;
                if *size > ball.diameter / 2.0 {
                    return Err(Error::invalid(
                        format!("{name}.mesh.size at mesh level {level}"),
                        *size,
                        format!(
                            "<= radius {} m: this mesh has no coarser level; use a finer \
                             ball mesh or --tolerance (which refines)",
                            ball.diameter / 2.0
                        ),
                    ));
                }
            }
        }
    }
    Ok(s)
}

/// Ball 1's (pole, bulk) sizes of a scene's built-in mesh, m (zeros for a mesh file).
pub fn mesh_sizes(scene: &Scene) -> (f64, f64) {
    match scene.ball1.mesh {
        MeshSettings::Builtin { size, pole_size } => (pole_size, size),
        MeshSettings::File { .. } => (0.0, 0.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A manufactured model: f(h) = f0 (1 + c h²) with h = 2^−level.
    fn model(level: i32) -> Result<LevelOutcome> {
        let h = 2f64.powi(-level);
        let f = |f0: f64, c: f64| f0 * (1.0 + c * h * h);
        Ok(LevelOutcome {
            level,
            pole_size: 1e-4 * h,
            size: 3e-3 * h,
            e: f(0.3190, 0.02),
            delta_max: f(1.74e-5, -0.03),
            contact_duration: f(5.9e-5, 0.01),
            wall_time_s: 0.0,
            phase: None,
        })
    }

    #[test]
    fn two_levels_run_the_scene_mesh_and_the_next_coarser() {
        let mut asked = Vec::new();
        let est = run_ladder(LadderPlan::TwoLevels, |l| {
            asked.push(l);
            model(l)
        })
        .unwrap();
        assert_eq!(asked, [-1, 0]);
        // Order 2 assumed and true: the extrapolation is exact.
        assert!((est.e.extrapolated - 0.3190).abs() < 1e-14);
        assert!((est.delta_max.extrapolated - 1.74e-5).abs() < 1e-19);
        assert_eq!(est.meshes.len(), 2);
        assert!(est.summary().contains("p = 2 assumed"));
    }

    #[test]
    fn three_levels_observe_the_order() {
        let est = run_ladder(LadderPlan::ThreeLevels, model).unwrap();
        for q in [&est.e, &est.delta_max, &est.contact_duration] {
            assert!((q.observed_order.unwrap() - 2.0).abs() < 1e-6, "{q:?}");
        }
    }

    #[test]
    fn a_tolerance_refines_until_met_or_capped() {
        // e = f0 (1 + 0.02·4^−l): the GCI of levels (l−2, l−1, l) is 1.25·0.015·4^{1−l}/3 of
        // f0, 0.625 %, 0.156 %, 0.039 % for l = 1, 2, 3: 0.1 % is met at level 3.
        let plan = |tolerance, max_refinements| LadderPlan::Tolerance {
            tolerance,
            max_refinements,
        };
        let est = run_ladder(plan(1e-3, 5), model).unwrap();
        let levels: Vec<i32> = est.meshes.iter().map(|m| m.level).collect();
        assert_eq!(levels, [-1, 0, 1, 2, 3]);
        assert_eq!(est.tolerance_met, Some(true));
        assert!(est.e.relative_error.unwrap() <= 1e-3);
        let est = run_ladder(plan(1e-5, 1), model).unwrap();
        assert_eq!(est.meshes.last().unwrap().level, 1);
        assert_eq!(est.tolerance_met, Some(false));
        assert!(est.summary().contains("NOT met"));
    }

    #[test]
    fn a_failing_level_is_named() {
        let err = run_ladder(LadderPlan::TwoLevels, |l| {
            if l < 0 {
                Err(Error::Numerical("boom".into()))
            } else {
                model(l)
            }
        })
        .unwrap_err();
        assert!(err.to_string().contains("mesh level -1"), "{err}");
    }

    #[test]
    fn levels_scale_both_sizes_and_stop_at_the_radius() {
        let s = Scene::default();
        let (p0, h0) = mesh_sizes(&s);
        let (p, h) = mesh_sizes(&scene_at_level(&s, 1).unwrap());
        assert_eq!((p, h), (p0 / 2.0, h0 / 2.0));
        let (p, h) = mesh_sizes(&scene_at_level(&s, -1).unwrap());
        assert_eq!((p, h), (p0 * 2.0, h0 * 2.0));
        let err = scene_at_level(&s, -2).unwrap_err().to_string();
        assert!(err.contains("ball1.mesh.size at mesh level -2"), "{err}");
    }
}
