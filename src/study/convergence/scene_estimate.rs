//! A scene's run with its error bar: the default ladder of a head-on section scene (levels −1
//! and 0, each a phase ensemble), a ladder plan, or `--tolerance` (the scene's own levels when
//! they meet it, else the banded family of [`crate::study::convergence::converged_scene`]); and a sweep case's FE
//! run the way `twoball run` runs it.

use crate::error::{Error, Result};
use crate::fe::materials;
use crate::scene::{approach, Approach, MeshSettings, Scene};
use crate::study::convergence::bulk_share::{
    bulk_floor, bulk_per_d, finer_pole_helps, in_3d, pole_bulk_breaks, with_bulk_share,
    with_pole_bulk_floor,
};
use crate::study::convergence::converged_scene::{converge_report, family_case};
use crate::study::convergence::ladder::{
    at_level, mesh_sizes, refine, run_ladder_with, scene_at_level, scene_at_pole_level, LadderPlan,
    POLE_LADDER_BULK_PER_D,
};
use crate::study::convergence::phase_ensemble::{ring_ratio, HeadOnCase, PhaseMean};
use crate::study::records::error_estimate::{
    ErrorEstimate, EstimateMethod, LevelOutcome, PhaseSummary,
};
use crate::study::run::force_curve::ForceCurve;
use crate::study::run::scene::{run_scene, take_phase_mean, RunReport};
use crate::study::run::simulate::{choose_reduction, HistoryRow, Reduction, RunOptions};
use std::time::Instant;

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
            .extend(crate::study::records::warnings::single_ring_phase(
                plastic, kinetic,
            ));
    }
    Ok(report)
}

/// The FE runner of a sweep case: a head-on case on the section as `twoball run` runs it
/// (its default ladder, or with `tolerance` as `--tolerance` does; the result the finest
/// level's phase mean, the wall time the whole estimate's, `e_error` its bar), any other
/// case as one run ([`crate::study::run::simulate::sweep_case`]).
///
/// Errors: as [`run_scene_with_estimate`] and [`crate::study::run::simulate::sweep_case`].
pub fn sweep_case_to(
    scene: &Scene,
    tolerance: Option<f64>,
) -> Result<crate::study::records::case::FeCase> {
    let Some(plan) = default_plan(scene)? else {
        return crate::study::run::simulate::sweep_case(scene);
    };
    let plan = match tolerance {
        Some(tolerance) => LadderPlan::Tolerance {
            tolerance,
            max_refinements: crate::study::convergence::ladder::DEFAULT_MAX_REFINEMENTS,
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
pub fn sweep_case(scene: &Scene) -> Result<crate::study::records::case::FeCase> {
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
    let Approach::Impact(touch) = approach(scene)? else {
        return run_scene(scene, opts);
    };
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
    let three_d = in_3d(scene, &touch)?;
    let oblique = crate::study::records::tangential::is_oblique(scene, &touch);
    if let (
        LadderPlan::Tolerance {
            tolerance,
            max_refinements,
        },
        true,
    ) = (plan, three_d && oblique)
    {
        let mut report = run_pole_ladder(scene, opts, tolerance, max_refinements)?;
        report.wall_time_s = start.elapsed().as_secs_f64();
        return Ok(report);
    }
    let (estimate, report) = if matches!(plan, LadderPlan::TwoLevels) {
        match two_levels(scene, opts) {
            Ok((estimate, report)) => (with_bulk_share(scene, three_d, estimate)?, report),
            // The levels' phase ensembles need the contact's edge inside their refined
            // surface; a harder impact (about ±70 m/s on copper) reaches beyond it.
            Err(Error::Invalid { field, value, .. }) if field == "contact_radius" => {
                let mut report = run_scene_alone(scene, opts)?;
                report.warnings.push(crate::study::records::warnings::no_error_estimate(&format!(
                    "its contact radius, {value} m, reaches beyond the refined surface of its mesh levels"
                )));
                report.wall_time_s = start.elapsed().as_secs_f64();
                return Ok(report);
            }
            Err(e) => return Err(e),
        }
    } else {
        let mut finest: Option<RunReport> = None;
        let estimate = run_ladder_with(
            plan,
            |level| {
                let (out, report) = run_level(scene, level, opts)?;
                finest = Some(report);
                Ok(out)
            },
            |est| with_bulk_share(scene, three_d, est),
        )?;
        let report = finest
            .ok_or_else(|| Error::Numerical("error estimate: the ladder ran no mesh".into()))?;
        (estimate, report)
    };
    // Whether the bulk's share set e's bar (the floor equals the bar when it did).
    let raised = bulk_floor(scene, three_d, &estimate)?
        .filter(|(floor, _, _)| *floor > 0.0 && estimate.e.error <= *floor);
    let mut report = with_estimate(
        report,
        ErrorEstimate {
            method: EstimateMethod::SceneLadder { why_not_banded },
            ..estimate
        },
    )?;
    if let Some((_, share, per_d)) = raised {
        report
            .warnings
            .push(crate::study::records::warnings::bulk_share_bar(
                share, per_d,
            ));
    }
    if matches!(plan, LadderPlan::TwoLevels) && !rate_independent(scene) {
        // The default levels' bar on a rate-dependent metal understated their error in 3 of
        // 13 cases: it is at least the floor, and the run says so.
        if let Some(est) = report.error_estimate.as_mut() {
            est.e = est.e.with_relative_floor(RATE_DEPENDENT_FLOOR);
        }
        report
            .warnings
            .push(crate::study::records::warnings::rate_dependent_bar(
                RATE_DEPENDENT_FLOOR,
            ));
    }
    report.wall_time_s = start.elapsed().as_secs_f64();
    Ok(report)
}

/// The relative tolerance on e and the tangential restitution the benches' oblique and
/// spinning points run their pole ladders to ([`run_pole_ladder`]), -.
pub const POLE_LADDER_TOLERANCE: f64 = 0.01;

/// The most pole refinements beyond level 0 of the benches' oblique points (levels −1, 0 and
/// +1 always, +2 while a finer pole lowers a bar that misses the tolerance).
pub const POLE_LADDER_MAX_REFINEMENTS: u32 = 2;

/// `--tolerance` (`tolerance`, -; at most `max_refinements` levels beyond 0) on an oblique
/// 3D scene (its contact points slide at touch, or its centres move apart tangentially:
/// [`crate::study::records::tangential::is_oblique`]): the pole ladder
/// ([`scene_at_pole_level`]: pole halved per level, bulk at most D/8 on all), levels −1, 0,
/// +1, then finer while e's or the tangential restitution's relative bar (observed order)
/// exceeds the tolerance by its pole's part ([`finer_pole_helps`]: the bulk's share, which a
/// finer pole does not lower, below it). The bars then carry that share
/// ([`with_pole_bulk_floor`]); when it alone breaks the tolerance ([`pole_bulk_breaks`]) the
/// run says so.
/// The report is the finest level's.
///
/// Errors: those of the runs, naming the level.
fn run_pole_ladder(
    scene: &Scene,
    opts: &RunOptions,
    tolerance: f64,
    max_refinements: u32,
) -> Result<RunReport> {
    let mut finest: Option<RunReport> = None;
    let mut at = |level: i32| -> Result<LevelOutcome> {
        let (out, report) = run_leveled(scene_at_pole_level(scene, level)?, level, opts)
            .map_err(|e| at_level(e, level))?;
        finest = Some(report);
        Ok(out)
    };
    let pole_part = |runs: &[LevelOutcome]| -> Result<ErrorEstimate> {
        Ok(with_tangential_tolerance(ErrorEstimate::from_runs(
            runs.to_vec(),
            Some(tolerance),
        )?))
    };
    let at_zero = scene_at_pole_level(scene, 0)?;
    let per_d = bulk_per_d(&at_zero).unwrap_or(POLE_LADDER_BULK_PER_D);
    let (mu, _) = scene.friction_coefficients();
    // Three levels at least (the observed order), then refine while a bar misses the
    // tolerance by its pole's part, which a finer pole lowers (the bulk's share it does not).
    let done = |runs: &Vec<LevelOutcome>| -> Result<bool> {
        Ok(runs.len() >= 3 && !finer_pole_helps(&pole_part(runs)?, per_d, mu, tolerance))
    };
    let start = vec![at(-1)?, at(0)?];
    let (runs, _) = refine(start, max_refinements, done, |mut runs| {
        let level = runs.last().map_or(0, |r| r.level) + 1;
        runs.push(at(level)?);
        Ok(runs)
    })?;
    let hopeless = pole_bulk_breaks(&pole_part(&runs)?, per_d, mu, tolerance);
    let estimate = with_tangential_tolerance(with_pole_bulk_floor(
        ErrorEstimate::from_runs(runs, Some(tolerance))?,
        per_d,
        mu,
    ));
    let report =
        finest.ok_or_else(|| Error::Numerical("error estimate: the ladder ran no mesh".into()))?;
    let mut report = with_estimate(
        report,
        ErrorEstimate {
            method: EstimateMethod::PoleLadder {
                bulk_size_m: mesh_sizes(&at_zero).1,
            },
            ..estimate
        },
    )?;
    // The share alone breaks the tolerance (so do the bars): a finer pole cannot meet it.
    if hopeless {
        report
            .warnings
            .push(crate::study::records::warnings::pole_bulk_share(
                tolerance, per_d,
            ));
    }
    Ok(report)
}

/// `est` with its tolerance met only from three levels on (the observed order: the coarsest
/// pole, a/2 of the contact radius, lies before e_t's knee, so two levels can agree by
/// chance) and when the tangential restitution's relative bar is within it too (an impact
/// without slip at touch has none and passes).
fn with_tangential_tolerance(est: ErrorEstimate) -> ErrorEstimate {
    let Some(t) = est.tolerance else {
        return est;
    };
    let restitution = est.tangential.as_ref().and_then(|x| x.restitution.as_ref());
    let tangential_met = restitution.is_none_or(|r| r.relative_error.is_some_and(|x| x <= t));
    let observed = est.meshes.len() >= 3;
    ErrorEstimate {
        tolerance_met: est.tolerance_met.map(|m| m && tangential_met && observed),
        ..est
    }
}

/// `--tolerance` on a head-on section scene whose banded family is `case`, cheapest first:
/// for a tolerance of [`levels_floor`] or looser the scene's default levels −1
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
    let floor = levels_floor(scene);
    if tolerance < floor || !levels {
        let report = run_scene(scene, opts)?;
        return refine_with_progress(case, report, tolerance, max_refinements, opts);
    }
    let (mut estimate, report) = two_levels(scene, opts)?;
    // Their bar may understate their error by chance (below): it is at least the floor.
    estimate.e = estimate.e.with_relative_floor(floor);
    let met = estimate.e.relative_error.is_some_and(|r| r <= tolerance);
    if !met {
        return refine_with_progress(case, report, tolerance, max_refinements, opts);
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

/// [`converge_report`] with its member runs counted on stderr when `opts.progress` (the two
/// first levels' ensembles and the contact-edge run; each refinement adds an ensemble).
fn refine_with_progress(
    case: &HeadOnCase,
    report: RunReport,
    tolerance: f64,
    max_refinements: u32,
    opts: &RunOptions,
) -> Result<RunReport> {
    use crate::study::common::progress::{counting_members, Cases, Mode};
    let meshes = crate::study::convergence::converged_scene::MESHES;
    let cases = std::sync::Arc::new(
        Cases::new(
            Mode::detect(opts.progress),
            "tolerance: banded mesh family, member runs",
            2 * meshes,
        )
        .without_hook(),
    );
    let out = counting_members(Some(&cases), || {
        converge_report(case, report, tolerance, max_refinements)
    });
    cases.finish();
    out
}

/// The tightest relative tolerance on e that the scene's default levels −1 and 0 may answer:
/// their phase means still oscillate by up to about 0.5 % between levels, two means can
/// agree by chance, and their true error reached 1.6 % where the bar said 0.45 %; over 21
/// cases of three metals and 0.05-5 m/s it stayed within 1.65 % (verification/contact-penalty.md,
/// "The default levels against the floor"). So their answer to a tolerance carries a bar
/// of at least this, and below it the banded family answers.
pub const LEVELS_TOLERANCE_FLOOR: f64 = 0.02;

/// The floor of the default levels' bar on e on a rate-dependent (Johnson-Cook) metal,
/// relative: over 13 head-on cases of ofhc-copper and steel-4340 (D = 10-30 mm, 0.05-10 m/s)
/// their true error reached 2.46 % (ofhc-copper ±5 m/s, under a bar of 1.70 %) and missed
/// bars of 0.09-0.12 % by 0.34 % on nearly elastic steel-4340 at ±0.05 m/s
/// (verification/contact-penalty.md, "Johnson-Cook metals"); the floor is the largest error
/// seen with the margin the rate-independent floor has over its own (1.2×), rounded up.
pub const RATE_DEPENDENT_FLOOR: f64 = 0.03;

/// True when both balls' flow stress is independent of the strain rate.
fn rate_independent(scene: &Scene) -> bool {
    materials::rate_independent(&scene.ball1.material)
        && materials::rate_independent(&scene.ball2.material)
}

/// The floor of the default levels' relative bar on e when they answer a tolerance:
/// [`LEVELS_TOLERANCE_FLOOR`], or [`RATE_DEPENDENT_FLOOR`] on a rate-dependent metal.
pub fn levels_floor(scene: &Scene) -> f64 {
    if rate_independent(scene) {
        LEVELS_TOLERANCE_FLOOR
    } else {
        RATE_DEPENDENT_FLOOR
    }
}

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
    let token = crate::study::common::interrupt::current();
    let within = |level: i32, o: &RunOptions| {
        crate::study::common::interrupt::within(token.as_ref(), || run_level(scene, level, o))
            .map_err(|e| at_level(e, level))
    };
    let (coarse, fine) = rayon::join(|| within(-1, &quiet), || within(0, opts));
    let (fine, mut report) = fine?;
    let (coarse, coarse_report) = coarse?;
    if !coarse_report.force_curve.delta.is_empty() {
        report.force_curve =
            std::mem::take(&mut report.force_curve).with_bar(&coarse_report.force_curve);
    }
    Ok((ErrorEstimate::from_runs(vec![coarse, fine], None)?, report))
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

/// Runs `scene` on mesh level `level` of its ladder ([`scene_at_level`]): the level's
/// figures and the full report. Fails for a scene without impact.
pub fn run_level(
    scene: &Scene,
    level: i32,
    opts: &RunOptions,
) -> Result<(LevelOutcome, RunReport)> {
    run_leveled(scene_at_level(scene, level)?, level, opts)
}

/// Runs `s`, a scene already on ladder level `level` (of either ladder): the level's figures
/// and the full report, a section level as its phase ensemble. Fails for a scene without
/// impact.
fn run_leveled(s: Scene, level: i32, opts: &RunOptions) -> Result<(LevelOutcome, RunReport)> {
    let mut report = run_scene(&s, opts)?;
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
        peak_force: report.fe.as_ref().map_or(0.0, |f| f.force.peak_smoothed),
        wall_time_s: report.wall_time_s,
        phase: None,
        tangential: report.tangential.map(|t| t.fe),
    };
    // A section run whose contact never reached the first ring (radius 0: a mesh too coarse
    // for the contact, which its warnings say) has no ring phase to average.
    let section = report.fe.as_ref().and_then(|f| f.contact_radius);
    match section {
        Some(radius) if radius > 0.0 && SCENE_PHASE_MESHES > 1 => {
            let (out, curve) = phase_level(&s, radius, out, &report, opts)?;
            report.force_curve = curve;
            Ok((out, report))
        }
        _ => Ok((out, report)),
    }
}

/// Meshes of the phase ensemble behind each level of a section scene's error estimate.
pub const SCENE_PHASE_MESHES: usize = 4;

/// The section scene `s`'s level `out` (its own run, largest contact radius `radius`, m) as
/// the mean of a phase ensemble ([`crate::study::convergence::phase_ensemble`]): the scene with both balls'
/// pole sizes times q^{j/M}, j = 1..M−1, q the ring ratio at `radius`, run in parallel.
/// Returns the level and the members' mean loading branch F(δ) (`own` the level's own run).
fn phase_level(
    s: &Scene,
    radius: f64,
    out: LevelOutcome,
    own: &RunReport,
    opts: &RunOptions,
) -> Result<(LevelOutcome, ForceCurve)> {
    use rayon::prelude::*;
    let mesh = crate::study::run::section::section_mesh("ball1", &s.ball1)?;
    let q = ring_ratio(&mesh, radius)?;
    let m = SCENE_PHASE_MESHES;
    let quiet = RunOptions {
        history_rows: opts.history_rows,
        ..RunOptions::default()
    };
    let runs: Vec<(LevelOutcome, Vec<HistoryRow>)> = (1..m)
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
            let level = LevelOutcome {
                e: r.e.unwrap_or(f64::NAN),
                delta_max: r.delta_max,
                contact_duration: r.contact_duration,
                peak_force: r.fe.as_ref().map_or(0.0, |f| f.force.peak_smoothed),
                wall_time_s: r.wall_time_s,
                tangential: r.tangential.map(|t| t.fe),
                ..out
            };
            Ok((level, r.fe.map(|f| f.history).unwrap_or_default()))
        })
        .collect::<Result<_>>()?;
    let own_rows: &[HistoryRow] = own.fe.as_ref().map_or(&[], |f| &f.history);
    let histories: Vec<&[HistoryRow]> = std::iter::once(own_rows)
        .chain(runs.iter().map(|(_, h)| h.as_slice()))
        .collect();
    let curve = ForceCurve::phase_mean(&histories);
    let members: Vec<LevelOutcome> = runs.into_iter().map(|(l, _)| l).collect();
    let all: Vec<&LevelOutcome> = std::iter::once(&out).chain(&members).collect();
    let of = |f: fn(&LevelOutcome) -> f64| {
        PhaseMean::of(&all.iter().map(|o| f(o)).collect::<Vec<f64>>())
    };
    let e = of(|o| o.e);
    let peak_force = of(|o| o.peak_force);
    let level = LevelOutcome {
        e: e.mean,
        delta_max: of(|o| o.delta_max).mean,
        contact_duration: of(|o| o.contact_duration).mean,
        peak_force: peak_force.mean,
        wall_time_s: all.iter().map(|o| o.wall_time_s).sum(),
        phase: Some(PhaseSummary {
            meshes: m,
            ring_ratio: q,
            e_sampling_error: e.sampling_error,
            e_min: e.min,
            e_max: e.max,
            peak_force_sampling_error: peak_force.sampling_error,
        }),
        ..out
    };
    Ok((level, curve))
}
