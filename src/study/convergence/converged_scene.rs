//! `--tolerance` on a head-on scene of the meridian section: the scene as a [`HeadOnCase`]
//! converged by [`converged_head_on`] on the banded, mass-scaled family (the plan of the law
//! bench, docs/contact-laws.md, subcycled to [`SUBCYCLE_MAX_LEVEL`]), its bars the run's
//! error estimate.
//!
//! A section run's plastic e is a sawtooth over the ring spacing at the contact edge, so the
//! scene's own ladder (pole and bulk sizes halved per level) converges slowly and its bar is
//! loose (verification/contact-penalty.md, "Why the section's e scatters"). The banded family splits
//! the rings at the contact edge five-fold, mass scaling lifts the step of the smallest
//! quads, and two members per level average the sawtooth: on the default scene e comes to
//! within 0.2 % of the converged 0.3184 with a bar of 0.4 % in about 4 s on 2 cores
//! (verification/contact-penalty.md, "Mass scaling of the contact region"). The family is sized from
//! the physics (Hertz's contact radius, then the contact edge of a level-0 run), not from the
//! scene's mesh settings.
//!
//! The plan covers two identical balls and a ball on a rigid wall whose solver settings are
//! those the family runs with; any other head-on scene keeps its own ladder, and the
//! estimate says why ([`EstimateMethod::SceneLadder`]).

use crate::error::{Error, Result};
use crate::fe::subcycle::Integration;
use crate::fe::subcycle::Subcycling;
use crate::mesh::section::SectionMesh;
use crate::scene::{approach, Approach, PlaneEnforcement, Scene, Switch, WallKind};
use crate::study::convergence::phase_band::banded_mesh;
use crate::study::convergence::phase_ensemble::{
    converged_head_on, HeadOnAnswer, HeadOnCase, HeadOnTarget, PhaseEnsemble, PhasePlan,
    MASS_SCALING_BIAS,
};
use crate::study::records::error_estimate::{
    ErrorEstimate, EstimateMethod, LevelOutcome, PhaseSummary, LADDER_RATIO,
};
use crate::study::run::scene::{take_phase_mean, RunReport};
use crate::study::run::section::{formulation, plane_contact};
use crate::study::run::simulate::{choose_reduction, Reduction};

/// The band's split: each surface ring at the contact edge split five-fold, its shells
/// confined to the surface ([`crate::mesh::section::band::SURFACE_DEPTH`]).
pub const SPLIT: usize = 5;

/// The fine level the plan starts on (its coarse ensemble is level 0).
pub const FINE_LEVEL: i32 = 1;

/// Meshes per ensemble: the pilot and the one half a period of the sawtooth away.
pub const MESHES: usize = 2;

/// The largest mass-scaling budget (added mass over the section's) the plan uses.
pub const MAX_MASS_SCALING: f64 = 1e-4;

/// The highest subcycling level of the family's runs: one above the section's default
/// ([`crate::fe::subcycle::DEFAULT_MAX_LEVEL`]). Mass scaling has lifted the step of
/// the smallest quads, so the levels' pseudo-energy stays small: on levels 0 and 1 of the
/// default scene, steel at 1 m/s, aluminum at 10 m/s and copper-fe at 0.2 m/s the energy
/// error is 2e-5 to 6e-5 of KE₀ (3e-6 to 1.3e-5 at the default cap), e moves by at most
/// 3e-5 and the family's CPU time falls by 15-30 % (docs/design.md, "Subcycling of the
/// section").
pub const SUBCYCLE_MAX_LEVEL: u8 = 3;

/// The share of the tolerance that the mass-scaling bias bound may take.
const MASS_SCALING_SHARE: f64 = 0.2;

/// The mass-scaling budget for a relative tolerance `tolerance` on e: the largest whose bias
/// bound ([`MASS_SCALING_BIAS`] · budget) is at most a fifth of the tolerance, and at most
/// [`MAX_MASS_SCALING`].
pub fn mass_scaling_for(tolerance: f64) -> f64 {
    (MASS_SCALING_SHARE * tolerance / MASS_SCALING_BIAS).min(MAX_MASS_SCALING)
}

/// The plan for a relative tolerance `tolerance` on e with at most `max_refinements` levels
/// beyond [`FINE_LEVEL`].
pub fn plan(tolerance: f64, max_refinements: u32) -> PhasePlan {
    PhasePlan {
        level: FINE_LEVEL,
        meshes: MESHES,
        band: Some(SPLIT),
        tolerance: Some(tolerance),
        max_refinements,
    }
}

/// The head-on case of `scene` that the banded family runs with mass-scaling `budget`, or why
/// the family does not cover the scene (one line).
///
/// Errors: those of [`approach`] and [`choose_reduction`].
pub fn head_on_case(scene: &Scene, budget: f64) -> Result<std::result::Result<HeadOnCase, String>> {
    let Approach::Impact(touch) = approach(scene)? else {
        return Ok(Err("the balls do not collide".into()));
    };
    let (reduction, _) = choose_reduction(scene, &touch)?;
    if reduction != Reduction::Axisymmetric {
        return Ok(Err(format!(
            "the scene runs the {} model",
            reduction.name()
        )));
    }
    let target = match scene.wall {
        Some(w) if w.kind == WallKind::Rigid => HeadOnTarget::RigidWall,
        Some(_) => return Ok(Err("an elastic wall is meshed, not a plane".into())),
        None if scene.identical_balls() => HeadOnTarget::IdenticalBall,
        None => return Ok(Err("the balls differ (both sections are meshed)".into())),
    };
    if let Some(why) = unsupported_settings(scene) {
        return Ok(Err(why));
    }
    Ok(Ok(HeadOnCase {
        diameter: scene.ball1.diameter,
        material: scene.ball1.material,
        // A wall scene's ball 2 is ball 1's mirror image: the approach speed is twice the
        // ball's, which is the case's speed against a wall.
        relative_speed: match target {
            HeadOnTarget::IdenticalBall => touch.approach_speed,
            HeadOnTarget::RigidWall => touch.approach_speed / 2.0,
        },
        target,
        formulation: formulation(scene),
        plane: plane_contact(scene),
        mass_scaling: budget,
        integration: Integration::Subcycled {
            max_level: SUBCYCLE_MAX_LEVEL,
        },
    }))
}

/// The first solver or contact setting of `scene` that the banded family does not run with
/// (it runs the defaults), in words; None when all match.
fn unsupported_settings(scene: &Scene) -> Option<String> {
    let s = &scene.solver;
    let penalty = scene.contact.plane == PlaneEnforcement::Penalty;
    if penalty && scene.contact.penalty_factor != 1.0 {
        return Some(format!(
            "contact.penalty_factor = {} (the family runs 1)",
            scene.contact.penalty_factor
        ));
    }
    if s.time_step_factor != 0.9 {
        return Some(format!(
            "solver.time_step_factor = {} (the family runs 0.9)",
            s.time_step_factor
        ));
    }
    if s.subcycling == Subcycling::Off {
        return Some("solver.subcycling = \"off\" (the family subcycles)".into());
    }
    if s.end_time.is_some() || scene.reduction.stop_at_separation == Switch::Off {
        return Some("a fixed end time (the family stops at separation)".into());
    }
    if let Some(h) = s.hold_time {
        return Some(format!(
            "solver.hold_time = {h} s (the family holds 3 % of the contact)"
        ));
    }
    None
}

/// The head-on case the banded family runs for `scene` at relative tolerance `tolerance` on
/// e (its mass-scaling budget [`mass_scaling_for`]), or why the family does not cover the
/// scene (one line).
///
/// Errors: as [`head_on_case`].
pub fn family_case(
    scene: &Scene,
    tolerance: f64,
) -> Result<std::result::Result<HeadOnCase, String>> {
    head_on_case(scene, mass_scaling_for(tolerance))
}

/// Converges `case` (the [`family_case`] of a scene) to relative tolerance `tolerance` on e
/// on the banded family, at most `max_refinements` levels beyond [`FINE_LEVEL`], and makes
/// `report` (the scene's own run: history, steps, energies, the analytical side) its answer:
/// e, δ_max and the contact duration (and the after-impact velocities, scaled to e) those of
/// the family's fine ensemble, and `error_estimate` its bars.
///
/// Errors: those of [`converged_head_on`] and [`take_phase_mean`].
pub fn converge_report(
    case: &HeadOnCase,
    mut report: RunReport,
    tolerance: f64,
    max_refinements: u32,
) -> Result<RunReport> {
    let max = crate::mesh::section::ladder::MAX_LEVEL - FINE_LEVEL as u32;
    let plan = plan(tolerance, max_refinements.min(max));
    let answer = converged_head_on(case, &plan)?;
    let estimate = estimate_of(case, &answer, tolerance)?;
    if let Some(fine) = estimate.meshes.last() {
        take_phase_mean(&mut report, fine)?;
    }
    report.error_estimate = Some(estimate);
    Ok(report)
}

/// The error estimate of `answer` (the bars of `case` on the banded family) for `tolerance`.
///
/// Errors: a contact edge missing from the answer, or a mesh the family cannot build.
fn estimate_of(case: &HeadOnCase, answer: &HeadOnAnswer, tolerance: f64) -> Result<ErrorEstimate> {
    let edge = answer
        .band_edge
        .ok_or_else(|| Error::Numerical("banded estimate: the answer has no band edge".into()))?;
    let level = |en: &PhaseEnsemble, level: i32| -> Result<LevelOutcome> {
        let mesh = banded_mesh(case.diameter, edge, level as u32, SPLIT, 1.0)?;
        let (pole_size, size) = contact_segment_sizes(&mesh);
        Ok(LevelOutcome {
            level,
            pole_size,
            size,
            e: en.e.mean,
            delta_max: en.delta_max.mean,
            contact_duration: en.contact_duration.mean,
            peak_force: en.peak_force.mean,
            wall_time_s: en.runs.iter().map(|r| r.wall_time_s).sum(),
            phase: Some(PhaseSummary {
                meshes: en.runs.len(),
                ring_ratio: en.ring_ratio,
                e_sampling_error: en.e.sampling_error,
                e_min: en.e.min,
                e_max: en.e.max,
                peak_force_sampling_error: en.peak_force.sampling_error,
            }),
            tangential: None,
        })
    };
    let meshes = vec![
        level(&answer.coarse, answer.fine_level - 1)?,
        level(&answer.fine, answer.fine_level)?,
    ];
    let e = answer.e;
    let tolerance_met = Some(e.relative_error.is_some_and(|r| r <= tolerance));
    Ok(ErrorEstimate {
        ratio: LADDER_RATIO,
        e,
        delta_max: answer.delta_max,
        contact_duration: answer.contact_duration,
        peak_force: answer.peak_force,
        tangential: None,
        meshes,
        tolerance: Some(tolerance),
        tolerance_met,
        method: EstimateMethod::BandedFamily {
            band_split: SPLIT,
            band_edge_m: edge,
            meshes_per_level: MESHES,
            mass_scaling: case.mass_scaling,
            mass_scaling_bias: MASS_SCALING_BIAS * case.mass_scaling,
            cpu_time_s: answer.cpu_time_s,
        },
    })
}

/// The lengths (m) of the contact surface's segment at the pole (on the axis) and of its
/// longest segment.
fn contact_segment_sizes(mesh: &SectionMesh) -> (f64, f64) {
    let segments = mesh.segment_sets.get("contact").unwrap_or(&mesh.boundary);
    let length = |s: &[u32; 2]| {
        let (a, b) = (mesh.nodes[s[0] as usize], mesh.nodes[s[1] as usize]);
        (a[0] - b[0]).hypot(a[1] - b[1])
    };
    let on_axis = |s: &&[u32; 2]| s.iter().any(|&i| mesh.nodes[i as usize][0] == 0.0);
    let pole = segments.iter().find(on_axis).map_or(f64::NAN, length);
    let longest = segments.iter().map(length).fold(0.0, f64::max);
    (pole, longest)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::ring::QuadFormulation;
    use crate::scene::{Override, DEFAULT_SCENE, WALL_SCENE};
    use std::path::Path;

    fn scene(text: &str, sets: &[&str]) -> Scene {
        let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
        Scene::from_toml(text, Path::new("."), &sets).unwrap()
    }

    fn why_not(text: &str, sets: &[&str]) -> String {
        head_on_case(&scene(text, sets), 0.0).unwrap().unwrap_err()
    }

    #[test]
    fn the_mass_scaling_bias_takes_at_most_a_fifth_of_the_tolerance() {
        assert_eq!(mass_scaling_for(0.005), MAX_MASS_SCALING);
        let b = mass_scaling_for(0.001);
        assert!((MASS_SCALING_BIAS * b - 0.2 * 0.001).abs() < 1e-15, "{b}");
        for t in [1e-4, 1e-3, 3e-3, 0.05] {
            assert!(MASS_SCALING_BIAS * mass_scaling_for(t) <= 0.2 * t + 1e-15);
        }
    }

    /// The default pair at ±1 m/s and the ball at 1 m/s on a rigid wall are the same section
    /// model (the wall is the pair's symmetry plane): the same ball speed against the plane.
    #[test]
    fn the_pair_and_the_ball_on_a_wall_map_to_the_same_section_run() {
        let pair = head_on_case(&scene(DEFAULT_SCENE, &[]), 1e-4)
            .unwrap()
            .unwrap();
        assert_eq!(pair.target, HeadOnTarget::IdenticalBall);
        assert_eq!(pair.relative_speed, 2.0);
        assert_eq!(pair.mass_scaling, 1e-4);
        assert_eq!(pair.diameter, 0.02);
        let wall = head_on_case(&scene(WALL_SCENE, &[]), 1e-4)
            .unwrap()
            .unwrap();
        assert_eq!(wall.target, HeadOnTarget::RigidWall);
        assert_eq!(wall.relative_speed, 1.0);
        let mesh = || crate::mesh::section::ladder_ball(0.02, 5e-4, 0).unwrap();
        let (a, b) = (
            crate::study::convergence::phase_ensemble::head_on(&pair, mesh()),
            crate::study::convergence::phase_ensemble::head_on(&wall, mesh()),
        );
        assert_eq!(a.speed, b.speed);
        assert_eq!(a.speed, 1.0);
        let bbar = head_on_case(&scene(DEFAULT_SCENE, &["solver.element=b-bar"]), 0.0)
            .unwrap()
            .unwrap();
        assert_eq!(bbar.formulation, QuadFormulation::SelectiveReduced);
    }

    /// What the family does not run keeps the scene's own ladder, and says why.
    #[test]
    fn scenes_the_family_does_not_cover_say_why() {
        let cases: [(&str, &[&str], &str); 6] = [
            (DEFAULT_SCENE, &["ball2.diameter=0.03"], "differ"),
            (DEFAULT_SCENE, &["reduction.symmetry=quarter"], "quarter"),
            (
                DEFAULT_SCENE,
                &["solver.time_step_factor=0.8"],
                "time_step_factor",
            ),
            (DEFAULT_SCENE, &["solver.subcycling=off"], "subcycling"),
            (DEFAULT_SCENE, &["solver.end_time=2e-4"], "end time"),
            (
                DEFAULT_SCENE,
                &["ball2.velocity=[1.0,0,0]"],
                "do not collide",
            ),
        ];
        for (text, sets, want) in cases {
            let why = why_not(text, sets);
            assert!(why.contains(want) && !why.contains('\n'), "{sets:?}: {why}");
        }
        let elastic = why_not(WALL_SCENE, &["wall.kind=elastic", "wall.material=steel"]);
        assert!(elastic.contains("elastic wall"), "{elastic}");
        // The penalty factor matters only to a penalty plane.
        let kinematic = scene(DEFAULT_SCENE, &["contact.penalty_factor=2"]);
        assert!(head_on_case(&kinematic, 0.0).unwrap().is_ok());
        let penalty = why_not(
            DEFAULT_SCENE,
            &["contact.penalty_factor=2", "contact.plane=penalty"],
        );
        assert!(penalty.contains("penalty_factor"), "{penalty}");
    }
}
