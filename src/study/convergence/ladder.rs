//! The mesh ladder of a scene: which levels to run ([`LadderPlan`]), the scene on a level
//! ([`scene_at_level`]: pole and bulk sizes halved per level) and the loop that runs levels
//! until a plan is met ([`run_ladder`]), its estimate an [`ErrorEstimate`].
//!
//! The ladder is model-agnostic: [`run_ladder`] takes a closure `run(level)` that runs the
//! scene on mesh level `level` (0 the scene's own mesh, −1 the next coarser, +1 the next finer)
//! and returns its [`LevelOutcome`]; the 3D model's closure is [`scene_at_level`] followed by
//! a run, and any other model plugs in the same way.

use crate::error::{Error, Result};
use crate::scene::{MeshSettings, Scene};
use crate::study::records::error_estimate::{ErrorEstimate, LevelOutcome, LADDER_RATIO};
use serde::Serialize;

/// The default cap on levels finer than the scene's own mesh with `--tolerance`.
pub const DEFAULT_MAX_REFINEMENTS: u32 = 2;

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

/// Runs the ladder `plan` with `run(level)` and returns the estimate; the last run is the
/// finest. Errors of `run` pass through (with the level named).
pub fn run_ladder(
    plan: LadderPlan,
    run: impl FnMut(i32) -> Result<LevelOutcome>,
) -> Result<ErrorEstimate> {
    run_ladder_with(plan, run, Ok)
}

/// [`run_ladder`] with every estimate passed through `adjust` (a model's floor on a bar)
/// before it is reported or checked against a tolerance.
///
/// Errors: those of `run` (with the level named) and of `adjust`.
pub fn run_ladder_with(
    plan: LadderPlan,
    mut run: impl FnMut(i32) -> Result<LevelOutcome>,
    adjust: impl Fn(ErrorEstimate) -> Result<ErrorEstimate>,
) -> Result<ErrorEstimate> {
    let mut at = |level: i32| run(level).map_err(|e| at_level(e, level));
    let of =
        |runs: Vec<LevelOutcome>, tolerance| adjust(ErrorEstimate::from_runs(runs, tolerance)?);
    match plan {
        LadderPlan::TwoLevels => of(vec![at(-1)?, at(0)?], None),
        LadderPlan::ThreeLevels => of(vec![at(-2)?, at(-1)?, at(0)?], None),
        LadderPlan::Tolerance {
            tolerance,
            max_refinements,
        } => {
            let met = |runs: &Vec<LevelOutcome>| {
                Ok(of(runs.clone(), Some(tolerance))?.tolerance_met == Some(true))
            };
            let start = vec![at(-1)?, at(0)?];
            let finer = |mut runs: Vec<LevelOutcome>| {
                let finest = runs.last().map_or(0, |r| r.level);
                runs.push(at(finest + 1)?);
                Ok(runs)
            };
            let (runs, _) = refine(start, max_refinements, met, finer)?;
            of(runs, Some(tolerance))
        }
    }
}

/// The refine loop of every ladder: while `met(&state)` is false and fewer than `max`
/// refinements have run, `finer(state)` runs the next finer level. Returns the last state and
/// the number of refinements run.
///
/// Errors: those of `met` and `finer`.
pub fn refine<S>(
    mut state: S,
    max: u32,
    mut met: impl FnMut(&S) -> Result<bool>,
    mut finer: impl FnMut(S) -> Result<S>,
) -> Result<(S, u32)> {
    let mut done = 0;
    while done < max && !met(&state)? {
        state = finer(state)?;
        done += 1;
    }
    Ok((state, done))
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

/// Bulk elements per diameter, at least, on every level of a pole ladder: past the knee of e
/// and e_t in the bulk (verification/design-measurements.md, "Error estimates").
pub const POLE_LADDER_BULK_PER_D: f64 = 8.0;

/// The scene on level `level` of its pole ladder: every built-in mesh's pole size times
/// 2^−level, its bulk size at most D/[`POLE_LADDER_BULK_PER_D`] on every level. Fails for a
/// mesh read from a file.
pub fn scene_at_pole_level(scene: &Scene, level: i32) -> Result<Scene> {
    let scale = LADDER_RATIO.powi(-level);
    let mut s = scene.clone();
    for (name, ball) in [("ball1", &mut s.ball1), ("ball2", &mut s.ball2)] {
        let d = ball.diameter;
        match &mut ball.mesh {
            MeshSettings::File { .. } => {
                return Err(Error::Parse(format!(
                    "{name}.mesh.file is set: a pole ladder needs the built-in mesher"
                )))
            }
            MeshSettings::Builtin { size, pole_size } => {
                *size = size.min(d / POLE_LADDER_BULK_PER_D);
                *pole_size *= scale;
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
            peak_force: f(900.0, 0.04),
            wall_time_s: 0.0,
            phase: None,
            tangential: None,
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
        assert!(est.summary().contains("order 2 assumed"));
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
