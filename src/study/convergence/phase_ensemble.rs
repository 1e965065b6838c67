//! The section model's converged head-on answer: a mean over the phase of its surface rings.
//!
//! On the meridian section every surface node is a ring, so a plastic contact grows ring by
//! ring and e (with t_c and the peak force) is a sawtooth in the mesh's size: it follows
//! where the last ring to land before maximum compression sits (verification/contact-penalty.md, "Why
//! the section's e scatters"). Scaling the mesh near the pole by s moves every ring radius to
//! s·r_k; the outermost ring inside the true contact radius a changes once per factor
//! q = r_{k+1}/r_k (the ratio of the two rings at a), so the sawtooth is periodic in ln s with
//! period ln q. The mean over M meshes at s_j = q^{j/M}, j = 0..M−1, is the trapezoidal rule
//! of a periodic function over one period: it removes the sawtooth whatever its shape, and
//! the mean of the even members against the mean of all of them measures what is left
//! (the sampling error).
//!
//! The ensemble runs the pilot (s = 1) first, reads q at the pilot's largest contact radius
//! ([`ring_ratio`]), then the other M − 1 meshes in parallel (rayon). [`converged_head_on`]
//! runs one ensemble on ladder level L and one on the next coarser mesh and combines them
//! into an error bar (an [`Estimate`]): the two-level Richardson estimate of
//! [`crate::study::records::estimate`] (the coarse-to-fine difference, an honest bound for order ≥ 1)
//! plus the sampling error of the fine mean.

use crate::analytic::hertz::HertzPair;
use crate::error::{Error, Result};
use crate::fe::elements::ring::QuadFormulation;
use crate::fe::subcycle::Integration;
use crate::material::Material;
use crate::mesh::section::{ladder_ball, SectionMesh};
use crate::study::convergence::ladder::refine;
use crate::study::records::estimate::{estimate, Behaviour, Estimate, ASSUMED_ORDER};
use crate::study::run::section_impact::{HeadOn, ImpactResult, PlaneContact, Target};
use rayon::prelude::*;
use serde::Serialize;
use std::f64::consts::PI;

/// Default number of meshes of an ensemble (even, so that the even members form a half-size
/// ensemble for the sampling error).
pub const DEFAULT_PHASE_MESHES: usize = 8;

/// The ladder's refinement ratio between the coarse and the fine ensemble.
const RATIO: f64 = 2.0;

/// Coarsest fine level of a plan (its coarse ensemble is one below).
pub const MIN_LEVEL: i32 = -2;

/// The mesh of family level `level` (see [`PhasePlan::level`]) for a ball of diameter `d`
/// (m) sized from contact radius `a` (m).
///
/// Errors: those of `ladder_ball` (a sizing radius outside its range).
pub fn family_mesh(d: f64, a: f64, level: i32) -> Result<SectionMesh> {
    if level >= 0 {
        ladder_ball(d, a, level as u32)
    } else {
        ladder_ball(d, a * RATIO.powi(-level), 0)
    }
}

/// One member of an ensemble.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseRun {
    /// Scale s of the mesh's sizing length against the pilot's, -.
    pub scale: f64,
    /// Coefficient of restitution, -.
    pub e: f64,
    /// Maximum approach, m.
    pub delta_max: f64,
    /// Contact duration, s.
    pub contact_duration: f64,
    /// Peak normal force, N.
    pub peak_force: f64,
    /// Largest relative energy drift, -.
    pub energy_error: f64,
    /// Largest contact radius, m.
    pub contact_radius: f64,
    /// Wall time of the run, s.
    pub wall_time_s: f64,
}

/// The mean of one quantity over an ensemble, in the quantity's unit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseMean {
    /// Mean over the M members.
    pub mean: f64,
    /// |mean of the even members − mean|: what the M-member mean may still carry of the
    /// sawtooth (≥ 0).
    pub sampling_error: f64,
    /// Smallest member.
    pub min: f64,
    /// Largest member.
    pub max: f64,
}

/// An ensemble of one mesh family over the phase of its surface rings.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PhaseEnsemble {
    /// Ring ratio q = r_{k+1}/r_k at the pilot's contact radius (the period in scale), -.
    pub ring_ratio: f64,
    /// The members, pilot first.
    pub runs: Vec<PhaseRun>,
    /// Coefficient of restitution, -.
    pub e: PhaseMean,
    /// Maximum approach, m.
    pub delta_max: PhaseMean,
    /// Contact duration, s.
    pub contact_duration: PhaseMean,
    /// Peak normal force, N.
    pub peak_force: PhaseMean,
}

/// Bound on the relative bias of a mass-scaled run per unit budget: |q(s) − q(0)| ≤
/// MASS_SCALING_BIAS · budget · |q| for e, δ_max, the contact duration and the peak force.
/// Measured on copper-fe (banded levels 0 and 1, 0.01 to 10 m/s, budgets 1e-5 to 1e-4) and
/// on steel, aluminum and the Johnson-Cook copper at one speed each, budget 1e-4: the
/// largest ratio was 9.1 (e of steel at 1.39 m/s on banded level 0; 4.5 on its level 1;
/// verification/contact-penalty.md, "Mass scaling of the contact region").
pub const MASS_SCALING_BIAS: f64 = 10.0;

/// The two-level estimate of one quantity from the `coarse` and `fine` ensembles' means:
/// the fine mean with the Richardson-extrapolated value (order 2 assumed) and the bar, the
/// two-level estimate plus the fine mean's sampling error plus, for a case mass-scaled
/// within `mass_scaling` (added mass over the section's), the bias bound
/// [`MASS_SCALING_BIAS`] · budget · |mean|. Same unit as the quantity; the relative error is
/// the bar over |extrapolated|, as every [`Estimate`]'s.
///
/// Errors: a non-finite mean.
fn estimate_of(coarse: &PhaseMean, fine: &PhaseMean, mass_scaling: f64) -> Result<Estimate> {
    let est: Estimate = estimate(&[coarse.mean, fine.mean], RATIO).ok_or_else(|| {
        Error::Numerical(format!(
            "phase ensemble: non-finite means {} and {}",
            coarse.mean, fine.mean
        ))
    })?;
    let error =
        est.error + fine.sampling_error + MASS_SCALING_BIAS * mass_scaling * fine.mean.abs();
    Ok(Estimate {
        finest: fine.mean,
        extrapolated: est.extrapolated,
        observed_order: None,
        order_used: Some(ASSUMED_ORDER),
        error: 0.0,
        relative_error: None,
        behaviour: Behaviour::TwoLevels,
    }
    .with_error(error))
}

/// What [`converged_head_on`] returns.
#[derive(Debug, Clone, Serialize)]
pub struct HeadOnAnswer {
    /// Coefficient of restitution, -.
    pub e: Estimate,
    /// Maximum approach, m.
    pub delta_max: Estimate,
    /// Contact duration, s.
    pub contact_duration: Estimate,
    /// Peak normal force, N.
    pub peak_force: Estimate,
    /// The coarse ensemble.
    pub coarse: PhaseEnsemble,
    /// The fine ensemble.
    pub fine: PhaseEnsemble,
    /// The fine ensemble's pilot run (history and force pulse for curves).
    #[serde(skip)]
    pub pilot: ImpactResult,
    /// With a banded plan, the contact edge the band is centred on, m.
    pub band_edge: Option<f64>,
    /// Level of the fine ensemble that answered (the plan's, or deeper after refinements).
    pub fine_level: i32,
    /// CPU time of all runs (sum of their wall times), s.
    pub cpu_time_s: f64,
}

/// What a head-on impact hits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum HeadOnTarget {
    /// An identical ball (the symmetry plane between them).
    IdenticalBall,
    /// A rigid wall.
    RigidWall,
}

/// A head-on impact for [`converged_head_on`].
#[derive(Debug, Clone, Copy)]
pub struct HeadOnCase {
    /// Ball diameter, m (> 0).
    pub diameter: f64,
    /// Ball material.
    pub material: Material,
    /// Relative approach speed, m/s (> 0): twice the ball's speed against an identical ball,
    /// the ball's speed against a wall.
    pub relative_speed: f64,
    /// What the ball hits.
    pub target: HeadOnTarget,
    /// Element formulation.
    pub formulation: QuadFormulation,
    /// How the rigid plane (the symmetry plane, or the wall) is enforced.
    pub plane: PlaneContact,
    /// Mass-scaling budget of every run: added mass over the section's (0: none;
    /// [`crate::fe::section::mass_scaling`]); its bias bound joins every bar
    /// ([`MASS_SCALING_BIAS`]).
    pub mass_scaling: f64,
    /// Time integration of every run (by default [`Integration::subcycled`]).
    pub integration: Integration,
}

impl HeadOnCase {
    /// The default scene as a head-on case: two D = 20 mm copper-fe balls at 2 m/s relative
    /// speed, one-point quads, the kinematic symmetry plane.
    pub fn default_scene() -> HeadOnCase {
        HeadOnCase {
            diameter: 0.02,
            material: Material::copper_fe(),
            relative_speed: 2.0,
            target: HeadOnTarget::IdenticalBall,
            formulation: QuadFormulation::default(),
            plane: PlaneContact::Kinematic,
            mass_scaling: 0.0,
            integration: Integration::subcycled(),
        }
    }
}

/// How fine and how large the ensembles are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhasePlan {
    /// Level of the fine ensemble: ℓ ≥ 0 the ladder level of `mesh::section::ladder_ball`
    /// sized from Hertz's contact radius a; ℓ < 0 the level-0 ladder sized from 2^−ℓ a (pole
    /// cells 2^−ℓ times larger). The coarse ensemble is level ℓ − 1.
    pub level: i32,
    /// Meshes per ensemble (even, ≥ 2).
    pub meshes: usize,
    /// With `Some(split)`, the banded family ([`crate::study::convergence::phase_band`]): the ladder around the
    /// contact edge with the rings there split `split`-fold (1..=16); the fine level is then
    /// ≥ 1 (its coarse level ≥ 0).
    pub band: Option<usize>,
    /// With `Some(t)`: while the relative bar of e exceeds t (> 0), run the next finer level
    /// (the fine ensemble becomes the coarse one), at most `max_refinements` times.
    pub tolerance: Option<f64>,
    /// Most refinements beyond `level` under `tolerance`.
    pub max_refinements: u32,
}

impl Default for PhasePlan {
    fn default() -> Self {
        PhasePlan {
            level: 0,
            meshes: DEFAULT_PHASE_MESHES,
            band: None,
            tolerance: None,
            max_refinements: 0,
        }
    }
}

/// The ratio r_{k+1}/r_k of the surface ring whose initial radius is closest to `radius` (m)
/// and the next one outwards, on the nodes of `mesh`'s `contact` set (its boundary without).
///
/// Errors: a radius that is not finite and positive, or no surface ring outside it.
pub fn ring_ratio(mesh: &SectionMesh, radius: f64) -> Result<f64> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(Error::invalid(
            "contact_radius",
            radius,
            "> 0 m (the pilot run made contact)",
        ));
    }
    let segments = mesh.segment_sets.get("contact").unwrap_or(&mesh.boundary);
    let mut r: Vec<f64> = segments
        .iter()
        .flatten()
        .map(|&i| mesh.nodes[i as usize][0])
        .collect();
    r.sort_by(f64::total_cmp);
    r.dedup();
    let k = r
        .iter()
        .enumerate()
        .min_by(|a, b| (a.1 - radius).abs().total_cmp(&(b.1 - radius).abs()))
        .map(|(k, _)| k)
        .unwrap_or(0);
    match (r.get(k), r.get(k + 1)) {
        (Some(&a), Some(&b)) if a > 0.0 => Ok(b / a),
        _ => Err(Error::invalid(
            "contact_radius",
            radius,
            "inside the meshed contact surface",
        )),
    }
}

/// The mean of `f` over `runs` with its sampling error (even members against all).
fn phase_mean(runs: &[PhaseRun], f: fn(&PhaseRun) -> f64) -> PhaseMean {
    let all: Vec<f64> = runs.iter().map(f).collect();
    PhaseMean::of(&all)
}

impl PhaseMean {
    /// The mean of the members `values` (pilot first, in phase order; at least one) with
    /// its sampling error (the even members' mean against all).
    pub fn of(values: &[f64]) -> PhaseMean {
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let even: Vec<f64> = values.iter().step_by(2).copied().collect();
        let half = even.iter().sum::<f64>() / even.len() as f64;
        PhaseMean {
            mean,
            sampling_error: (half - mean).abs(),
            min: values.iter().copied().fold(f64::INFINITY, f64::min),
            max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        }
    }
}

/// Checks that an ensemble has an even number of meshes, at least two.
fn check_meshes(meshes: usize) -> Result<()> {
    if meshes < 2 || !meshes.is_multiple_of(2) {
        return Err(Error::invalid(
            "phase_meshes",
            meshes,
            "an even number of meshes >= 2",
        ));
    }
    Ok(())
}

/// One member's summary.
fn member(scale: f64, r: &ImpactResult) -> PhaseRun {
    PhaseRun {
        scale,
        e: r.e,
        delta_max: r.delta_max,
        contact_duration: r.contact_duration,
        peak_force: r.peak_force,
        energy_error: r.energy_error,
        contact_radius: r.contact_radius_max,
        wall_time_s: r.wall_time_s,
    }
}

/// The ensemble of `meshes` (even, ≥ 2) members: `mesh_at(s)` builds the mesh whose sizing
/// length is s times the pilot's, `run` runs one mesh. Returns the ensemble and the pilot's
/// run.
///
/// Errors: an odd or too small `meshes`; any error of `mesh_at` or `run` (the first one).
pub fn run_ensemble(
    mesh_at: &(dyn Fn(f64) -> Result<SectionMesh> + Sync),
    run: &(dyn Fn(SectionMesh) -> Result<ImpactResult> + Sync),
    meshes: usize,
) -> Result<(PhaseEnsemble, ImpactResult)> {
    check_meshes(meshes)?;
    let pilot_mesh = mesh_at(1.0)?;
    let pilot = run(pilot_mesh.clone())?;
    let q = ring_ratio(&pilot_mesh, pilot.contact_radius_max)?;
    let token = crate::study::common::interrupt::current();
    let rest: Vec<PhaseRun> = (1..meshes)
        .into_par_iter()
        .map(|j| {
            crate::study::common::interrupt::within(token.as_ref(), || {
                let s = q.powf(j as f64 / meshes as f64);
                Ok(member(s, &run(mesh_at(s)?)?))
            })
        })
        .collect::<Result<_>>()?;
    let mut runs = vec![member(1.0, &pilot)];
    runs.extend(rest);
    Ok((ensemble_of(q, runs), pilot))
}

/// The ensemble of the members `runs` (in phase order) of ring ratio `q`.
fn ensemble_of(q: f64, runs: Vec<PhaseRun>) -> PhaseEnsemble {
    PhaseEnsemble {
        ring_ratio: q,
        e: phase_mean(&runs, |r| r.e),
        delta_max: phase_mean(&runs, |r| r.delta_max),
        contact_duration: phase_mean(&runs, |r| r.contact_duration),
        peak_force: phase_mean(&runs, |r| r.peak_force),
        runs,
    }
}

/// Hertz's contact radius (m) of `case` (the elastic estimate that sizes the ladder).
pub fn hertz_contact_radius(case: &HeadOnCase) -> f64 {
    let m = &case.material;
    let r = case.diameter / 2.0;
    let mass = m.rho * PI * case.diameter.powi(3) / 6.0;
    let e1 = m.plane_strain_modulus();
    let pair = match case.target {
        HeadOnTarget::IdenticalBall => HertzPair::new(e1 / 2.0, r / 2.0, mass / 2.0),
        HeadOnTarget::RigidWall => HertzPair::new(e1, r, mass),
    };
    pair.contact_radius(pair.max_approach(case.relative_speed))
}

/// Checks the numbers of `case` and `plan`.
fn check(case: &HeadOnCase, plan: &PhasePlan) -> Result<()> {
    if !(case.relative_speed.is_finite() && case.relative_speed > 0.0) {
        return Err(Error::invalid(
            "relative_speed",
            case.relative_speed,
            "> 0 m/s, finite",
        ));
    }
    if !(case.diameter.is_finite() && case.diameter > 0.0) {
        return Err(Error::invalid("diameter", case.diameter, "> 0 m, finite"));
    }
    crate::fe::section::mass_scaling::check_budget(case.mass_scaling)?;
    let max = crate::mesh::section::ladder::MAX_LEVEL as i32;
    if !(MIN_LEVEL..=max).contains(&plan.level) {
        // `plan.level` is the fine level: its coarse ensemble is one below.
        return Err(Error::invalid(
            "level",
            plan.level,
            format!("{MIN_LEVEL}..={max}"),
        ));
    }
    if let Some(split) = plan.band {
        crate::study::convergence::phase_band::check_split(split)?;
        if plan.level < 1 {
            return Err(Error::invalid(
                "level",
                plan.level,
                format!("1..={max} with an edge band (its coarse level is the ladder's 0)"),
            ));
        }
    }
    if let Some(t) = plan.tolerance {
        if !(t.is_finite() && t > 0.0) {
            return Err(Error::invalid("tolerance", t, "> 0, finite"));
        }
        let deepest = plan.level + plan.max_refinements as i32;
        if deepest > max {
            return Err(Error::invalid(
                "max_refinements",
                plan.max_refinements,
                format!(
                    "<= {} (the ladder's deepest level is {max})",
                    max - plan.level
                ),
            ));
        }
    }
    check_meshes(plan.meshes)
}

/// Checks `case` for an ensemble on family level `level` (which may be one below a plan's
/// coarsest fine level: it is checked as the coarse ensemble of level + 1).
fn check_ensemble_level(case: &HeadOnCase, level: i32, meshes: usize) -> Result<()> {
    check(
        case,
        &PhasePlan {
            level: level + 1,
            meshes,
            ..PhasePlan::default()
        },
    )
}

/// The HeadOn model of `case` on `mesh`.
pub(super) fn head_on(case: &HeadOnCase, mesh: SectionMesh) -> HeadOn {
    let (speed, target) = match case.target {
        HeadOnTarget::IdenticalBall => (case.relative_speed / 2.0, Target::MirrorBall),
        HeadOnTarget::RigidWall => (case.relative_speed, Target::RigidWall),
    };
    let mut h = HeadOn::new(mesh, case.material, speed, target);
    h.formulation = case.formulation;
    h.plane_contact = case.plane;
    h.mass_scaling = case.mass_scaling;
    h.integration = case.integration;
    h
}

/// Runs `case` on `mesh`, stopping at the next observation of the solver when the job is
/// interrupted (Ctrl-C, or its cancel token).
///
/// Errors: those of the run; [`Error::Interrupted`] on an interrupt.
pub(super) fn run_head_on(case: &HeadOnCase, mesh: SectionMesh) -> Result<ImpactResult> {
    head_on(case, mesh).run_observed(&mut |solver, _| {
        if crate::study::common::interrupt::requested() {
            return Err(Error::Interrupted(format!(
                "at t = {:.3e} s of a head-on run",
                solver.time()
            )));
        }
        Ok(())
    })
}

/// The ensemble of `meshes` members of `case` on family level `level` ([`family_mesh`],
/// sized from Hertz's contact radius) and the pilot's run.
///
/// Errors: a non-positive speed or diameter, a level outside [`MIN_LEVEL`]..=7 (or
/// [`MIN_LEVEL`] − 1 for a coarse ensemble), a contact radius the ladder cannot mesh, or a
/// failed run.
pub fn ensemble_at(
    case: &HeadOnCase,
    level: i32,
    meshes: usize,
) -> Result<(PhaseEnsemble, ImpactResult)> {
    check_ensemble_level(case, level, meshes)?;
    let a = hertz_contact_radius(case);
    let d = case.diameter;
    let run = |mesh: SectionMesh| run_head_on(case, mesh);
    let mesh_at = |s: f64| family_mesh(d, a * s, level);
    run_ensemble(&mesh_at, &run, meshes)
}

/// The ensemble of `meshes` members of `case` on family level `level`, like [`ensemble_at`],
/// but with the ring ratio read at the contact radius `radius` (m; e.g. a coarser level's)
/// instead of from a pilot run, so that all members run at once: the deep levels of a
/// ladder, whose pilot alone would take as long as the rest.
///
/// Errors: as [`ensemble_at`]; a `radius` not inside the meshed contact surface.
pub fn ensemble_at_radius(
    case: &HeadOnCase,
    level: i32,
    meshes: usize,
    radius: f64,
) -> Result<PhaseEnsemble> {
    check_ensemble_level(case, level, meshes)?;
    let a = hertz_contact_radius(case);
    let d = case.diameter;
    let q = ring_ratio(&family_mesh(d, a, level)?, radius)?;
    let mesh_at = |s: f64| family_mesh(d, a * s, level);
    let run = |mesh: SectionMesh| run_head_on(case, mesh);
    Ok(ensemble_over(q, meshes, &mesh_at, &run)?.0)
}

/// The ensemble of `meshes` (even, ≥ 2) members at s = q^{j/M}, all run at once: `mesh_at(s)`
/// builds a member's mesh, `run` runs it. Returns the ensemble and the run at s = 1.
///
/// Errors: a ring ratio `q` that is not finite and > 1; an odd or too small `meshes`; any
/// error of `mesh_at` or `run` (the first one).
pub fn ensemble_over(
    q: f64,
    meshes: usize,
    mesh_at: &(dyn Fn(f64) -> Result<SectionMesh> + Sync),
    run: &(dyn Fn(SectionMesh) -> Result<ImpactResult> + Sync),
) -> Result<(PhaseEnsemble, ImpactResult)> {
    if !(q.is_finite() && q > 1.0) {
        return Err(Error::invalid("ring_ratio", q, "> 1, finite"));
    }
    check_meshes(meshes)?;
    let token = crate::study::common::interrupt::current();
    let counter = crate::study::common::progress::members();
    let mut results: Vec<(PhaseRun, ImpactResult)> = (0..meshes)
        .into_par_iter()
        .map(|j| {
            crate::study::common::interrupt::within(token.as_ref(), || {
                let s = q.powf(j as f64 / meshes as f64);
                let r = run(mesh_at(s)?)?;
                if let Some(c) = &counter {
                    c.case_done(false, &format!("mesh scale {s:.4}: e = {:.5}", r.e));
                }
                Ok((member(s, &r), r))
            })
        })
        .collect::<Result<_>>()?;
    let runs = results.iter().map(|t| t.0).collect();
    let first = results.swap_remove(0).1;
    Ok((ensemble_of(q, runs), first))
}

/// The head-on impact of `case` converged over the phase of the section's rings, with error
/// bars: an ensemble of `plan.meshes` meshes on family level `plan.level` (sized from
/// Hertz's contact radius a; [`family_mesh`]) and one on the next coarser level; with
/// `plan.band`, on the banded family around the contact edge of a level-0 run
/// ([`crate::study::convergence::phase_band`]). With `plan.tolerance`, while e's relative bar exceeds it the
/// next finer level runs and the fine ensemble becomes the coarse one, at most
/// `plan.max_refinements` times ([`HeadOnAnswer::fine_level`] says where it stopped).
///
/// Errors: as [`ensemble_at`]; a band's split outside 1..=16 or a banded fine level below 1;
/// a tolerance that is not finite and positive, or refinements past the ladder's level 7.
pub fn converged_head_on(case: &HeadOnCase, plan: &PhasePlan) -> Result<HeadOnAnswer> {
    check(case, plan)?;
    use crate::study::convergence::phase_band::{banded_ensemble_at, contact_edge};
    let edge = match plan.band {
        Some(_) => Some(contact_edge(case)?),
        None => None,
    };
    // The ensemble of `level` and its pilot run, on the plan's family.
    let at = |level: i32| -> Result<(PhaseEnsemble, ImpactResult)> {
        match (plan.band, &edge) {
            (Some(split), Some((e, _))) => {
                banded_ensemble_at(case, level as u32, plan.meshes, *e, split)
            }
            _ => ensemble_at(case, level, plan.meshes),
        }
    };
    let (coarse, fine) = match plan.band {
        // The banded ring ratio is read at the edge: both levels' members run at once.
        Some(_) => {
            let token = crate::study::common::interrupt::current();
            let counter = crate::study::common::progress::members();
            let within = |level: i32| {
                crate::study::common::interrupt::within(token.as_ref(), || {
                    crate::study::common::progress::counting_members(counter.as_ref(), || at(level))
                })
            };
            rayon::join(|| within(plan.level - 1), || within(plan.level))
        }
        None => (at(plan.level - 1), at(plan.level)),
    };
    let (mut coarse, (mut fine, mut pilot)) = (coarse?.0, fine?);
    let mut level = plan.level;
    let mut cpu_time_s = edge.as_ref().map_or(0.0, |(_, r)| r.wall_time_s) + cpu_of(&coarse);
    let bar_e = |c: &PhaseEnsemble, f: &PhaseEnsemble| estimate_of(&c.e, &f.e, case.mass_scaling);
    if let Some(tol) = plan.tolerance {
        // Met unless the relative bar of e exceeds the tolerance (no relative bar, a zero
        // extrapolated e, stops refining).
        let met = |(c, f, ..): &Refined| Ok(bar_e(c, f)?.relative_error.is_none_or(|r| r <= tol));
        let finer = |(_, f, _, l, cpu): Refined| -> Result<Refined> {
            if let Some(c) = crate::study::common::progress::members() {
                c.add_total(plan.meshes);
            }
            let cpu = cpu + cpu_of(&f);
            let (finer, finer_pilot) = at(l + 1)?;
            Ok((f, finer, finer_pilot, l + 1, cpu))
        };
        let state = (coarse, fine, pilot, level, cpu_time_s);
        ((coarse, fine, pilot, level, cpu_time_s), _) =
            refine(state, plan.max_refinements, met, finer)?;
    }
    cpu_time_s += cpu_of(&fine);
    let ms = case.mass_scaling;
    Ok(HeadOnAnswer {
        e: estimate_of(&coarse.e, &fine.e, ms)?,
        delta_max: estimate_of(&coarse.delta_max, &fine.delta_max, ms)?,
        contact_duration: estimate_of(&coarse.contact_duration, &fine.contact_duration, ms)?,
        peak_force: estimate_of(&coarse.peak_force, &fine.peak_force, ms)?,
        coarse,
        fine,
        pilot,
        band_edge: edge.map(|(e, _)| e),
        fine_level: level,
        cpu_time_s,
    })
}

/// The state of the refine loop: coarse and fine ensembles, the fine pilot run, the fine
/// level and the CPU time so far (s).
type Refined = (PhaseEnsemble, PhaseEnsemble, ImpactResult, i32, f64);

/// CPU time of an ensemble's runs (the sum of their wall times), s.
fn cpu_of(en: &PhaseEnsemble) -> f64 {
    en.runs.iter().map(|r| r.wall_time_s).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(mean: f64) -> PhaseRun {
        PhaseRun {
            scale: 1.0,
            e: mean,
            delta_max: 0.0,
            contact_duration: 0.0,
            peak_force: 0.0,
            energy_error: 0.0,
            contact_radius: 0.0,
            wall_time_s: 0.0,
        }
    }

    /// The mean of M members spread over one period of a sawtooth is within its half-width
    /// over M of the period mean, at any phase of the pilot.
    #[test]
    fn the_mean_over_one_period_removes_a_sawtooth() {
        let saw = |x: f64| 0.3 + 0.01 * (2.0 * (x - x.floor()) - 1.0);
        let err = |m: usize, phase: f64| {
            let runs: Vec<PhaseRun> = (0..m)
                .map(|j| run(saw(phase + j as f64 / m as f64)))
                .collect();
            let pm = phase_mean(&runs, |r| r.e);
            ((pm.mean - 0.3).abs(), pm.sampling_error)
        };
        for phase in [0.0, 0.13, 0.5, 0.77] {
            for m in [4, 16] {
                let (e, s) = err(m, phase);
                assert!(e <= 0.01 / m as f64 + 1e-15, "M = {m}: {e}");
                assert!(s <= 0.03 / m as f64 + 1e-15, "M = {m}: {s}");
            }
        }
    }

    /// A cancelled job stops every run of the ensembles (the pilot, and the members on the
    /// pool's threads) at their first observation.
    #[test]
    fn a_cancelled_job_stops_the_ensembles() {
        use crate::study::common::interrupt::{within, CancelToken};
        let token = CancelToken::new();
        token.cancel();
        let plan = PhasePlan {
            level: 1,
            meshes: 2,
            band: Some(5),
            ..PhasePlan::default()
        };
        let start = std::time::Instant::now();
        let case = HeadOnCase::default_scene();
        let e = within(Some(&token), || converged_head_on(&case, &plan)).unwrap_err();
        assert!(matches!(e, Error::Interrupted(_)), "{e}");
        let e = within(Some(&token), || ensemble_at(&case, 0, 2)).unwrap_err();
        assert!(matches!(e, Error::Interrupted(_)), "{e}");
        // Each run stops within its first observation (a few hundred steps).
        assert!(start.elapsed().as_secs_f64() < 2.0, "{:?}", start.elapsed());
    }

    #[test]
    fn an_odd_ensemble_is_refused() {
        let mesh_at = |_s: f64| -> Result<SectionMesh> { unreachable!() };
        let run = |_m: SectionMesh| -> Result<ImpactResult> { unreachable!() };
        let e = run_ensemble(&mesh_at, &run, 3).unwrap_err().to_string();
        assert!(e.contains("phase_meshes") && e.contains("3"), "{e}");
        for q in [f64::NAN, 1.0, 0.5] {
            let e = ensemble_over(q, 2, &mesh_at, &run).unwrap_err().to_string();
            assert!(e.contains("ring_ratio"), "{e}");
        }
    }

    /// An ensemble read at a given radius checks its numbers before running anything.
    #[test]
    fn an_ensemble_at_a_radius_refuses_bad_numbers_before_running() {
        let case = HeadOnCase::default_scene();
        let odd = ensemble_at_radius(&case, 0, 3, 890e-6)
            .unwrap_err()
            .to_string();
        assert!(odd.contains("phase_meshes"), "{odd}");
        let outside = ensemble_at_radius(&case, 0, 2, 0.05)
            .unwrap_err()
            .to_string();
        assert!(outside.contains("contact_radius"), "{outside}");
        let deep = ensemble_at_radius(&case, 9, 2, 890e-6)
            .unwrap_err()
            .to_string();
        assert!(deep.contains("level"), "{deep}");
    }

    #[test]
    fn the_ring_ratio_is_that_of_the_ring_at_the_radius() {
        let a = 470e-6;
        let mesh = ladder_ball(0.02, a, 0).unwrap();
        let q = ring_ratio(&mesh, 1.5 * a).unwrap();
        // About one pole cell (a/6) over 1.5 a at the edge of the core.
        assert!(q > 1.05 && q < 1.25, "{q}");
        assert!(ring_ratio(&mesh, 0.0).is_err());
        assert!(ring_ratio(&mesh, 0.05).is_err());
    }
}
