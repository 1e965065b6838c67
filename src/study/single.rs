//! One scene, both models: the FE run beside the analytical answer, with relative
//! differences, written as results.json and history.csv.

use super::converged_scene::{converge_report, family_case};
use super::error_estimate::{
    at_level, mesh_sizes, run_ladder, scene_at_level, ErrorEstimate, LadderPlan,
};
use super::error_estimate::{EstimateMethod, LevelOutcome, PhaseSummary};
use super::law_compare::{compare_laws, law_table, LawOutcome};
use super::number::sci;
use super::outcome::{
    analytic_outcome, ball_inertia, dissipation_factor, relative_difference, Outcome,
};
use super::phase_ensemble::{ring_ratio, HeadOnCase, PhaseMean};
use super::simulate::{
    choose_reduction, simulate, Reduction, RunOptions, Simulation, HISTORY_HEADER,
};
use super::warnings::{analytic_warnings, fe_warnings, FeFigures, Warning};
use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use crate::scene::{approach, Approach, MeshSettings, Scene};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// Relative differences FE vs analytical, (FE − analytical)/|analytical|.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Differences {
    /// In e.
    pub e: f64,
    /// In ball 1's normal velocity after impact.
    pub v1n_after: f64,
    /// In ball 2's normal velocity after impact.
    pub v2n_after: f64,
    /// In δ_max.
    pub delta_max: f64,
    /// In the contact duration.
    pub contact_duration: f64,
    /// In η.
    pub eta: f64,
}

impl Differences {
    /// FE against analytical; normal components along the contact frame's x.
    pub fn between(fe: &Outcome, an: &Outcome, n: [f64; 3]) -> Differences {
        let dot = |a: [f64; 3]| a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
        Differences {
            e: relative_difference(fe.e, an.e),
            v1n_after: relative_difference(dot(fe.v1_after), dot(an.v1_after)),
            v2n_after: relative_difference(dot(fe.v2_after), dot(an.v2_after)),
            delta_max: relative_difference(fe.delta_max, an.delta_max),
            contact_duration: relative_difference(fe.contact_duration, an.contact_duration),
            eta: relative_difference(fe.eta, an.eta),
        }
    }
}

/// Everything a run produced; serialised as results.json.
#[derive(Debug, Clone, Serialize)]
pub struct RunReport {
    /// Whether the balls collide at all.
    pub impact: bool,
    /// Why not, when they do not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_impact_reason: Option<String>,
    /// FE coefficient of restitution (absent without impact).
    pub e: Option<f64>,
    /// FE centre-of-mass velocity of ball 1 after impact, m/s.
    pub v1_after: [f64; 3],
    /// FE centre-of-mass velocity of ball 2 after impact, m/s.
    pub v2_after: [f64; 3],
    /// FE angular velocity of ball 1 after impact, rad/s.
    pub w1_after: [f64; 3],
    /// FE angular velocity of ball 2 after impact, rad/s.
    pub w2_after: [f64; 3],
    /// FE maximum approach of the mass centres, m.
    pub delta_max: f64,
    /// FE contact duration, s.
    pub contact_duration: f64,
    /// FE energy dissipation factor η (eq. 33, rigid-body kinetic energy).
    pub eta: Option<f64>,
    /// Largest relative energy-balance error of the FE run.
    pub energy_error: f64,
    /// Symmetry reduction used: quarter, half, full (none without impact).
    pub reduction: String,
    /// Wall time of the whole run, s.
    pub wall_time_s: f64,
    /// Element updates (elements × steps).
    pub element_cycles: u64,
    /// FE run details (savings, sizes, steps, stop reason).
    pub fe: Option<Simulation>,
    /// The analytical model's outcome.
    pub analytic: Option<Outcome>,
    /// FE vs analytical.
    pub relative_difference: Option<Differences>,
    /// The scene's `[laws]`, each integrated on the same balls and speeds (absent without).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub laws: Vec<LawOutcome>,
    /// Results not to take at face value, one line each (empty when none).
    pub warnings: Vec<Warning>,
    /// The run's error bar from its mesh ladder (with `--error-estimate` or `--tolerance`);
    /// the other results are those of the ladder's finest mesh.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_estimate: Option<ErrorEstimate>,
    /// The scene as run (presets and overrides resolved).
    pub scene: Scene,
}

/// Runs `scene`: analytical model, then FE (unless there is no impact).
pub fn run_scene(scene: &Scene, opts: &RunOptions) -> Result<RunReport> {
    let start = Instant::now();
    let touch = match approach(scene)? {
        Approach::NoImpact { reason } => {
            return Ok(RunReport {
                impact: false,
                no_impact_reason: Some(reason),
                e: None,
                v1_after: scene.ball1.velocity,
                v2_after: scene.ball2.velocity,
                w1_after: scene.ball1.angular_velocity,
                w2_after: scene.ball2.angular_velocity,
                delta_max: 0.0,
                contact_duration: 0.0,
                eta: None,
                energy_error: 0.0,
                reduction: "none".into(),
                wall_time_s: start.elapsed().as_secs_f64(),
                element_cycles: 0,
                fe: None,
                analytic: None,
                relative_difference: None,
                laws: Vec::new(),
                warnings: Vec::new(),
                error_estimate: None,
                scene: scene.clone(),
            })
        }
        Approach::Impact(t) => t,
    };
    let (an, collision) = analytic_outcome(scene, &touch)?;
    let laws = compare_laws(scene, &touch)?;
    let sim = simulate(scene, &touch, an.contact_duration, opts)?;
    let fe = sim.outcome;
    let r_star = collision.pair.radius;
    let mut warnings = analytic_warnings(an.delta_max, r_star);
    warnings.extend(fe_warnings(&fe_figures(scene, &sim, r_star)));
    warnings.extend(super::ignored::ignored_settings(
        scene,
        sim.savings.reduction,
    ));
    Ok(RunReport {
        impact: true,
        no_impact_reason: None,
        e: Some(fe.e),
        v1_after: fe.v1_after,
        v2_after: fe.v2_after,
        w1_after: fe.w1_after,
        w2_after: fe.w2_after,
        delta_max: fe.delta_max,
        contact_duration: fe.contact_duration,
        eta: Some(fe.eta),
        energy_error: sim.energy_error,
        reduction: sim.savings.reduction.name().into(),
        wall_time_s: start.elapsed().as_secs_f64(),
        element_cycles: sim.element_cycles,
        relative_difference: Some(Differences::between(&fe, &an, touch.frame.axes[0])),
        fe: Some(sim),
        analytic: Some(an),
        laws,
        warnings,
        error_estimate: None,
        scene: scene.clone(),
    })
}

/// The ladder a run of `scene` gets by default: the axisymmetric model's runs are cheap, so a
/// head-on run also runs the next-coarser mesh ([`LadderPlan::TwoLevels`]) and reports its
/// error bar; a 3D run reports one only when asked (it would double its cost). None for a
/// scene without impact, and for a mesh with no coarser level (bulk size above a quarter
/// of the diameter).
///
/// Errors: as [`approach`] and [`choose_reduction`].
pub fn default_plan(scene: &Scene) -> Result<Option<LadderPlan>> {
    let Approach::Impact(touch) = approach(scene)? else {
        return Ok(None);
    };
    let (reduction, _) = choose_reduction(scene, &touch)?;
    let coarser = scene_at_level(scene, -1).is_ok();
    Ok((reduction == Reduction::Axisymmetric && coarser).then_some(LadderPlan::TwoLevels))
}

/// Runs `scene` with its default ladder ([`default_plan`]): with an error estimate for a
/// head-on scene on the meridian section, a single run otherwise.
pub fn run_scene_default(scene: &Scene, opts: &RunOptions) -> Result<RunReport> {
    match default_plan(scene)? {
        Some(plan) => run_scene_with_estimate(scene, opts, plan),
        None => run_scene_alone(scene, opts),
    }
}

/// [`run_scene`] as a run of its own (no ladder): a plastic impact on the section gets the
/// warning that its e is one phase of the surface rings.
pub fn run_scene_alone(scene: &Scene, opts: &RunOptions) -> Result<RunReport> {
    let mut report = run_scene(scene, opts)?;
    let section = report.reduction == Reduction::Axisymmetric.name();
    let energies = report.fe.as_ref().and_then(|f| {
        let (first, last) = (f.history.first()?, f.history.last()?);
        Some((last.plastic, first.kinetic))
    });
    if let (true, Some((plastic, kinetic))) = (section, energies) {
        report
            .warnings
            .extend(super::warnings::single_ring_phase(plastic, kinetic));
    }
    Ok(report)
}

/// The FE runner of a sweep case: a head-on case on the section as `twoball run` runs it
/// (its default ladder, or with `tolerance` as `--tolerance` does; the result the finest
/// level's phase mean, the wall time the whole estimate's, `e_error` its bar), any other
/// case as one run ([`super::simulate::sweep_case`]).
///
/// Errors: as [`run_scene_with_estimate`] and [`super::simulate::sweep_case`].
pub fn sweep_case_to(scene: &Scene, tolerance: Option<f64>) -> Result<super::sweep::FeCase> {
    let Some(plan) = default_plan(scene)? else {
        return super::simulate::sweep_case(scene);
    };
    let plan = match tolerance {
        Some(tolerance) => LadderPlan::Tolerance {
            tolerance,
            max_refinements: super::error_estimate::DEFAULT_MAX_REFINEMENTS,
        },
        None => plan,
    };
    let opts = RunOptions {
        history_rows: 400,
        ..RunOptions::default()
    };
    let report = run_scene_with_estimate(scene, &opts, plan)?;
    let sim = report
        .fe
        .as_ref()
        .ok_or_else(|| Error::Numerical("sweep case: the run reports no impact".into()))?;
    let mut case = sim.fe_case();
    case.summary.wall_time_s = report.wall_time_s;
    case.summary.e_error = report.error_estimate.as_ref().map(|est| est.e.error);
    Ok(case)
}

/// [`sweep_case_to`] with the default bar (no tolerance).
///
/// Errors: as [`sweep_case_to`].
pub fn sweep_case(scene: &Scene) -> Result<super::sweep::FeCase> {
    sweep_case_to(scene, None)
}

/// Runs `scene` on the mesh ladder `plan` ([`run_ladder`], each level a full run of
/// [`run_scene`] on [`scene_at_level`]): the report of the finest mesh, with its
/// `error_estimate` and `wall_time_s` the total over the ladder. A scene without impact gives
/// its plain report. Snapshots, when asked, are those of the finest mesh (levels run coarse
/// to fine and each overwrites the last). A [`LadderPlan::Tolerance`] on a head-on section
/// scene that the banded family covers runs [`run_to_tolerance`]; the estimate's `method`
/// says which ran.
pub fn run_scene_with_estimate(
    scene: &Scene,
    opts: &RunOptions,
    plan: LadderPlan,
) -> Result<RunReport> {
    if let Approach::NoImpact { .. } = approach(scene)? {
        return run_scene(scene, opts);
    }
    let start = Instant::now();
    let mut why_not_banded = None;
    if let LadderPlan::Tolerance {
        tolerance,
        max_refinements,
    } = plan
    {
        match family_case(scene, tolerance)? {
            Ok(case) => {
                let mut report = run_to_tolerance(scene, opts, &case, tolerance, max_refinements)?;
                report.wall_time_s = start.elapsed().as_secs_f64();
                return Ok(report);
            }
            Err(why) => why_not_banded = Some(why),
        }
    }
    let (estimate, report) = if matches!(plan, LadderPlan::TwoLevels) {
        match two_levels(scene, opts) {
            Ok(levels) => levels,
            // The levels' phase ensembles need the contact's edge inside their refined
            // surface; a harder impact (about ±70 m/s on copper) reaches beyond it.
            Err(Error::Invalid { field, value, .. }) if field == "contact_radius" => {
                let mut report = run_scene_alone(scene, opts)?;
                report.warnings.push(super::warnings::no_error_estimate(&format!(
                    "its contact radius, {value} m, reaches beyond the refined surface of its mesh levels"
                )));
                report.wall_time_s = start.elapsed().as_secs_f64();
                return Ok(report);
            }
            Err(e) => return Err(e),
        }
    } else {
        let mut finest: Option<RunReport> = None;
        let estimate = run_ladder(plan, |level| {
            let (out, report) = run_level(scene, level, opts)?;
            finest = Some(report);
            Ok(out)
        })?;
        let report = finest
            .ok_or_else(|| Error::Numerical("error estimate: the ladder ran no mesh".into()))?;
        (estimate, report)
    };
    let mut report = with_estimate(
        report,
        ErrorEstimate {
            method: EstimateMethod::SceneLadder { why_not_banded },
            ..estimate
        },
    )?;
    report.wall_time_s = start.elapsed().as_secs_f64();
    Ok(report)
}

/// `--tolerance` on a head-on section scene whose banded family is `case`, cheapest first:
/// for a tolerance of [`LEVELS_TOLERANCE_FLOOR`] or looser the scene's default levels −1
/// and 0 ([`two_levels`], a fraction of a second; when its mesh has a coarser level) answer
/// when their bar on e, raised to at least that floor, is within it; otherwise the family
/// converges the scene ([`converge_report`]), the scene's own run its report.
///
/// Errors: those of the runs.
pub fn run_to_tolerance(
    scene: &Scene,
    opts: &RunOptions,
    case: &HeadOnCase,
    tolerance: f64,
    max_refinements: u32,
) -> Result<RunReport> {
    // A mesh with no coarser level (bulk above a quarter of the diameter) has no default levels.
    let levels = default_plan(scene)? == Some(LadderPlan::TwoLevels);
    if tolerance < LEVELS_TOLERANCE_FLOOR || !levels {
        let report = run_scene(scene, opts)?;
        return converge_report(case, report, tolerance, max_refinements);
    }
    let (mut estimate, report) = two_levels(scene, opts)?;
    // Their bar may understate their error by chance (below): it is at least the floor.
    let e = estimate.e;
    estimate.e = e.with_error(e.error.max(LEVELS_TOLERANCE_FLOOR * e.extrapolated.abs()));
    let met = estimate.e.relative_error.is_some_and(|r| r <= tolerance);
    if !met {
        return converge_report(case, report, tolerance, max_refinements);
    }
    with_estimate(
        report,
        ErrorEstimate {
            tolerance: Some(tolerance),
            tolerance_met: Some(true),
            method: EstimateMethod::SceneLadder {
                why_not_banded: Some(LEVELS_MET_TOLERANCE.into()),
            },
            ..estimate
        },
    )
}

/// The tightest relative tolerance on e that the scene's default levels −1 and 0 may answer:
/// their phase means still oscillate by up to about 0.5 % between levels, two means can
/// agree by chance, and their true error reached 1.6 % where the bar said 0.45 %; over 21
/// cases of three metals and 0.05-5 m/s it stayed within 1.65 % (docs/contact-penalty.md,
/// "The default levels against the floor"). So their answer to a tolerance carries a bar
/// of at least this, and below it the banded family answers.
pub const LEVELS_TOLERANCE_FLOOR: f64 = 0.02;

/// `error_estimate.method.why_not_banded` when the scene's own levels −1 and 0 met the
/// tolerance, so the banded family was not needed.
pub const LEVELS_MET_TOLERANCE: &str = "levels -1 and 0 met the tolerance";

/// Levels −1 and 0 of `scene` side by side (independent runs; the coarse one quiet, with no
/// progress and no snapshots, so it costs the wall time its members leave idle): their
/// estimate and the scene's own run (level 0) as its report.
///
/// Errors: those of the runs, naming the level.
fn two_levels(scene: &Scene, opts: &RunOptions) -> Result<(ErrorEstimate, RunReport)> {
    let quiet = RunOptions {
        history_rows: opts.history_rows,
        ..RunOptions::default()
    };
    let token = super::interrupt::current();
    let within = |level: i32, o: &RunOptions| {
        super::interrupt::within(token.as_ref(), || run_level(scene, level, o))
            .map_err(|e| at_level(e, level))
    };
    let (coarse, fine) = rayon::join(|| within(-1, &quiet), || within(0, opts));
    let (fine, report) = fine?;
    Ok((
        ErrorEstimate::from_runs(vec![coarse?.0, fine], None)?,
        report,
    ))
}

/// `report` (the run of a ladder's finest level) with `estimate`: its e, δ_max and contact
/// duration the finest level's phase mean when that level ran an ensemble.
///
/// Errors: as [`take_phase_mean`].
fn with_estimate(mut report: RunReport, estimate: ErrorEstimate) -> Result<RunReport> {
    if let Some(level) = estimate.meshes.last().filter(|m| m.phase.is_some()) {
        take_phase_mean(&mut report, level)?;
    }
    report.error_estimate = Some(estimate);
    Ok(report)
}

/// Makes `report` (the run of a section scene's finest level) that level's answer: e,
/// δ_max and the contact duration become the means of its phase ensemble `level`, since one
/// ring phase alone scatters by about ±2 % in e ([`super::phase_ensemble`]). The after-impact
/// velocities are the run's with their normal parts about the fixed one (the centre of mass,
/// or the wall) scaled to the mean e, which keeps momentum and the head-on direction; η and
/// the differences from the analytical model and `fe.outcome` follow; the rest of `fe`
/// (steps, energy, history) stays the run's.
///
/// Errors: a report without an impact or without its analytical outcome.
pub(super) fn take_phase_mean(report: &mut RunReport, level: &LevelOutcome) -> Result<()> {
    let (Some(e_run), Some(an)) = (report.e, report.analytic.as_ref()) else {
        return Err(Error::Numerical(
            "phase mean: the finest run reports no impact".into(),
        ));
    };
    let scene = &report.scene;
    let Approach::Impact(touch) = approach(scene)? else {
        return Err(Error::Numerical(
            "phase mean: the scene has no impact".into(),
        ));
    };
    let n = touch.frame.axes[0];
    let weight = |b: &crate::scene::BallScene| ball_inertia(b.material.rho, b.diameter).0;
    let (m1, m2) = (weight(&scene.ball1), weight(&scene.ball2));
    // The wall (ball 2's columns) does not move: all the weight is its.
    let share1 = if scene.wall.is_some() {
        0.0
    } else {
        m1 / (m1 + m2)
    };
    let dot = |a: [f64; 3]| a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
    let fixed = share1 * dot(report.v1_after) + (1.0 - share1) * dot(report.v2_after);
    let scale = if e_run != 0.0 { level.e / e_run } else { 1.0 };
    let rescale = |v: [f64; 3]| {
        let shift = (dot(v) - fixed) * (scale - 1.0);
        [
            v[0] + shift * n[0],
            v[1] + shift * n[1],
            v[2] + shift * n[2],
        ]
    };
    report.v1_after = rescale(report.v1_after);
    report.v2_after = rescale(report.v2_after);
    report.e = Some(level.e);
    report.delta_max = level.delta_max;
    report.contact_duration = level.contact_duration;
    let eta = dissipation_factor(
        scene,
        [report.v1_after, report.v2_after],
        [report.w1_after, report.w2_after],
    );
    report.eta = Some(eta);
    let fe = Outcome {
        e: level.e,
        v1_after: report.v1_after,
        v2_after: report.v2_after,
        w1_after: report.w1_after,
        w2_after: report.w2_after,
        delta_max: level.delta_max,
        contact_duration: level.contact_duration,
        eta,
    };
    report.relative_difference = Some(Differences::between(&fe, an, n));
    if let Some(sim) = report.fe.as_mut() {
        sim.outcome = fe;
    }
    Ok(())
}

/// Runs `scene` on mesh level `level` of its ladder ([`scene_at_level`]): the level's
/// figures and the full report. Fails for a scene without impact.
pub fn run_level(
    scene: &Scene,
    level: i32,
    opts: &RunOptions,
) -> Result<(LevelOutcome, RunReport)> {
    let s = scene_at_level(scene, level)?;
    let report = run_scene(&s, opts)?;
    let (pole_size, size) = mesh_sizes(&s);
    let e = report
        .e
        .ok_or_else(|| Error::Numerical("the run reports no impact".into()))?;
    let out = LevelOutcome {
        level,
        pole_size,
        size,
        e,
        delta_max: report.delta_max,
        contact_duration: report.contact_duration,
        wall_time_s: report.wall_time_s,
        phase: None,
    };
    // A section run whose contact never reached the first ring (radius 0: a mesh too coarse
    // for the contact, which its warnings say) has no ring phase to average.
    let section = report.fe.as_ref().and_then(|f| f.contact_radius);
    match section {
        Some(radius) if radius > 0.0 && SCENE_PHASE_MESHES > 1 => {
            Ok((phase_level(&s, radius, out, opts)?, report))
        }
        _ => Ok((out, report)),
    }
}

/// Meshes of the phase ensemble behind each level of a section scene's error estimate.
pub const SCENE_PHASE_MESHES: usize = 4;

/// The section scene `s`'s level `out` (its own run, largest contact radius `radius`, m) as
/// the mean of a phase ensemble ([`super::phase_ensemble`]): the scene with both balls'
/// pole sizes times q^{j/M}, j = 1..M−1, q the ring ratio at `radius`, run in parallel.
fn phase_level(
    s: &Scene,
    radius: f64,
    out: LevelOutcome,
    opts: &RunOptions,
) -> Result<LevelOutcome> {
    use rayon::prelude::*;
    let mesh = super::simulate_section::section_mesh("ball1", &s.ball1)?;
    let q = ring_ratio(&mesh, radius)?;
    let m = SCENE_PHASE_MESHES;
    let quiet = RunOptions {
        history_rows: opts.history_rows,
        ..RunOptions::default()
    };
    let members: Vec<LevelOutcome> = (1..m)
        .into_par_iter()
        .map(|j| {
            let scale = q.powf(j as f64 / m as f64);
            let mut sj = s.clone();
            for b in [&mut sj.ball1, &mut sj.ball2] {
                if let MeshSettings::Builtin { pole_size, .. } = &mut b.mesh {
                    *pole_size *= scale;
                }
            }
            let r = run_scene(&sj, &quiet)?;
            Ok(LevelOutcome {
                e: r.e.unwrap_or(f64::NAN),
                delta_max: r.delta_max,
                contact_duration: r.contact_duration,
                wall_time_s: r.wall_time_s,
                ..out
            })
        })
        .collect::<Result<_>>()?;
    let all: Vec<&LevelOutcome> = std::iter::once(&out).chain(&members).collect();
    let of = |f: fn(&LevelOutcome) -> f64| {
        PhaseMean::of(&all.iter().map(|o| f(o)).collect::<Vec<f64>>())
    };
    let e = of(|o| o.e);
    Ok(LevelOutcome {
        e: e.mean,
        delta_max: of(|o| o.delta_max).mean,
        contact_duration: of(|o| o.contact_duration).mean,
        wall_time_s: all.iter().map(|o| o.wall_time_s).sum(),
        phase: Some(PhaseSummary {
            meshes: m,
            ring_ratio: q,
            e_sampling_error: e.sampling_error,
            e_min: e.min,
            e_max: e.max,
        }),
        ..out
    })
}

/// Element size at the contact pole of the built-in meshes (the coarser ball's), m; None
/// for meshes read from files.
fn pole_size(scene: &Scene) -> Option<f64> {
    let h = |m: &MeshSettings| match m {
        MeshSettings::Builtin { pole_size, .. } => Some(*pole_size),
        MeshSettings::File { .. } => None,
    };
    Some(h(&scene.ball1.mesh)?.max(h(&scene.ball2.mesh)?))
}

/// The figures the FE warnings check, from a finished run.
fn fe_figures(scene: &Scene, sim: &Simulation, r_star: f64) -> FeFigures {
    let peak =
        |f: fn(&super::simulate::HistoryRow) -> f64| sim.history.iter().map(f).fold(0.0, f64::max);
    FeFigures {
        energy_error: sim.energy_error,
        e: sim.outcome.e,
        delta_max: sim.outcome.delta_max,
        max_penetration: sim.max_penetration,
        r_star,
        pole_size: pole_size(scene),
        hourglass: peak(|r| r.hourglass),
        internal: peak(|r| r.elastic + r.plastic + r.hourglass),
    }
}

/// Writes results.json and history.csv into `dir` (created if needed), each atomically.
pub fn write_outputs(report: &RunReport, dir: &Path) -> Result<()> {
    ensure_dir(dir)?;
    let json = serde_json::to_string_pretty(report)
        .map_err(|e| Error::Parse(format!("results.json: {e}")))?;
    if !report.energy_error.is_finite()
        || report.fe.as_ref().is_some_and(|f| !f.outcome.is_finite())
    {
        return Err(Error::Numerical(
            "results contain a non-finite value; nothing written".into(),
        ));
    }
    write_atomic(dir.join("results.json"), json.as_bytes())?;
    let mut csv = String::from(HISTORY_HEADER);
    csv.push('\n');
    if let Some(sim) = &report.fe {
        for r in &sim.history {
            csv.push_str(&r.csv());
            csv.push('\n');
        }
    }
    write_atomic(dir.join("history.csv"), csv.as_bytes())
}

/// The side-by-side table printed by `twoball run`.
pub fn side_by_side(r: &RunReport) -> String {
    let mut s = String::new();
    let sc = &r.scene;
    match &sc.wall {
        None => s.push_str(&format!(
            "scene: ball1 {} D = {} m v = {:?} m/s; ball2 {} D = {} m v = {:?} m/s\n",
            sc.ball1.material_name,
            sc.ball1.diameter,
            sc.ball1.velocity,
            sc.ball2.material_name,
            sc.ball2.diameter,
            sc.ball2.velocity
        )),
        Some(w) => {
            let kind = match (w.material, w.size) {
                (Some(m), Some(size)) => format!(
                    "elastic wall (E = {:.4e} Pa, block W x H = {} x {} m)",
                    m.youngs, size[0], size[1]
                ),
                _ => "rigid wall".to_string(),
            };
            s.push_str(&format!(
                "scene: ball1 {} D = {} m v = {:?} m/s; {kind} through {:?} m, normal {:?}\n",
                sc.ball1.material_name, sc.ball1.diameter, sc.ball1.velocity, w.position, w.normal
            ))
        }
    }
    if !r.impact {
        s.push_str(&format!(
            "no impact: {}\n",
            r.no_impact_reason.as_deref().unwrap_or("")
        ));
        return s;
    }
    let (Some(sim), Some(an), Some(d)) = (&r.fe, &r.analytic, &r.relative_difference) else {
        return s;
    };
    let fe = &sim.outcome;
    let n = |v: [f64; 3]| v[0];
    let t = |v: [f64; 3]| v[1];
    s.push_str(&format!(
        "{:<34}{:>14}{:>14}{:>10}\n",
        "quantity", "FE", "analytical", "diff"
    ));
    let mut row = |name: &str, a: f64, b: f64, diff: Option<f64>| {
        let d = diff.map_or(String::from("-"), |x| format!("{:+.2}%", 100.0 * x));
        s.push_str(&format!(
            "{name:<34}{:>14}{:>14}{d:>10}\n",
            sci(a, 6),
            sci(b, 6)
        ));
    };
    row("e [-]", fe.e, an.e, Some(d.e));
    row(
        "ball 1 normal velocity after [m/s]",
        n(fe.v1_after),
        n(an.v1_after),
        Some(d.v1n_after),
    );
    row(
        "ball 2 normal velocity after [m/s]",
        n(fe.v2_after),
        n(an.v2_after),
        Some(d.v2n_after),
    );
    row(
        "ball 1 tangential velocity [m/s]",
        t(fe.v1_after),
        t(an.v1_after),
        Some(relative_difference(t(fe.v1_after), t(an.v1_after))),
    );
    row(
        "ball 2 tangential velocity [m/s]",
        t(fe.v2_after),
        t(an.v2_after),
        Some(relative_difference(t(fe.v2_after), t(an.v2_after))),
    );
    row(
        "delta_max [m]",
        fe.delta_max,
        an.delta_max,
        Some(d.delta_max),
    );
    row(
        "contact duration [s]",
        fe.contact_duration,
        an.contact_duration,
        Some(d.contact_duration),
    );
    row("eta [-]", fe.eta, an.eta, Some(d.eta));
    s.push_str(&format!(
        "FE: {} model ({}), {} elements, {} steps, dt = {:.3e} s, energy error {:.2e}, {:.2} s wall; {}\n",
        sim.savings.reduction.name(),
        sim.savings.reduction_reason,
        sim.elements,
        sim.steps,
        sim.dt,
        sim.energy_error,
        r.wall_time_s,
        sim.stop_reason
    ));
    if an.e < 1.0 {
        s.push_str(DELTA_MAX_NOTE);
        s.push('\n');
    }
    s.push_str(&law_table(&r.laws));
    s
}

/// Why FE and analytical δ_max differ, printed under every plastic impact's table.
pub const DELTA_MAX_NOTE: &str = "note: the FE delta_max is about 40 % below the analytical one by design: the model's phase-2 contact (Hertz area, pressure capped at 2.57 yield) is softer than a resolved elastic-plastic contact; see verification/NOTES.md";
