//! A quasi-static loop's numbers with their error bars: the loop run on consecutive levels
//! of the mesh ladder (each halving every length), each quantity the finest level's value
//! with the estimate of [`crate::study::records::estimate`] (two levels: order 2 assumed,
//! safety factor 3; three: the observed order).

use super::converged_scene::head_on_case;
use super::phase_ensemble::{hertz_contact_radius, HeadOnCase, HeadOnTarget};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::study::records::estimate::{estimate, Estimate};
use crate::study::run::quasi_static::{
    run_loop, LoadTo, LoopMesh, LoopSummary, StaticCase, StaticLoop, Support,
};
use serde::Serialize;

/// The finest ladder level of a loop unless asked otherwise (levels 0 and 1 behind the
/// bars).
pub const DEFAULT_LEVEL: u32 = 1;

/// Increments of loading at level 0 unless asked otherwise ([`StaticCase::increments`]).
pub const DEFAULT_INCREMENTS: usize = 20;

/// Each number of [`LoopSummary`] with its bar.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LoopEstimate {
    /// Largest approach, m.
    pub delta_max: Estimate,
    /// Contact force at δ_max / 2 on loading, N.
    pub force_at_half: Estimate,
    /// Contact force at δ_max, N.
    pub force_at_max: Estimate,
    /// Approach left after unloading, m.
    pub residual_approach: Estimate,
    /// Work returned on unloading, J.
    pub work_returned: Estimate,
    /// Quasi-static coefficient of restitution √(W_returned / W_in).
    pub e: Estimate,
    /// Contact radius at δ_max, m.
    pub contact_radius: Estimate,
}

/// The loops of `case` on levels `case.level − levels + 1 ..= case.level` (coarse to fine)
/// and the estimate of each number. `levels` is 2 or 3.
///
/// Errors: a level count outside 2..=3 or a first level below 0; those of [`run_loop`].
pub fn run_loop_ladder(case: &StaticCase, levels: u32) -> Result<(Vec<StaticLoop>, LoopEstimate)> {
    if !(2..=3).contains(&levels) || case.level.saturating_add(1) < levels {
        return Err(Error::invalid(
            "static.levels",
            format!("{levels} levels ending at level {}", case.level),
            "2 or 3 levels, the coarsest at level >= 0",
        ));
    }
    let loops = (case.level + 1 - levels..=case.level)
        .map(|level| run_loop(&StaticCase { level, ..*case }))
        .collect::<Result<Vec<_>>>()?;
    let of = |name: &str, f: fn(&LoopSummary) -> f64| -> Result<Estimate> {
        let v: Vec<f64> = loops.iter().map(|l| f(&l.summary)).collect();
        estimate(&v, 2.0).ok_or_else(|| {
            Error::Numerical(format!(
                "static loop: {name} not finite on every level: {v:?}"
            ))
        })
    };
    let est = LoopEstimate {
        delta_max: of("delta_max", |s| s.delta_max)?,
        force_at_half: of("F(delta_max/2)", |s| s.force_at_half)?,
        force_at_max: of("F(delta_max)", |s| s.force_at_max)?,
        residual_approach: of("residual approach", |s| s.residual_approach)?,
        work_returned: of("work returned", |s| s.work_returned)?,
        e: of("e", |s| s.e)?,
        contact_radius: of("contact radius", |s| s.contact_radius)?,
    };
    Ok((loops, est))
}

/// The head-on case of a `scene` whose static image is one ball on a plane (identical
/// balls, or a ball on a rigid wall).
///
/// Errors: any other scene (one line saying why); those of the scene's approach.
fn static_image_of(scene: &Scene) -> Result<HeadOnCase> {
    head_on_case(scene, 0.0)?.map_err(|why| {
        Error::invalid(
            "scene",
            why,
            "a head-on scene of identical balls or of a ball on a rigid wall",
        )
    })
}

/// The approach speed v_r (m/s) of a head-on `scene` whose static image is one ball on a
/// plane, and whether its partner is a rigid wall (else an identical ball).
///
/// Errors: as [`case_of_scene`].
pub fn impact_of_scene(scene: &Scene) -> Result<(f64, bool)> {
    let case = static_image_of(scene)?;
    Ok((
        case.relative_speed,
        matches!(case.target, HeadOnTarget::RigidWall),
    ))
}

/// The loop case of a head-on `scene` (identical balls, or a ball on a rigid wall): its ball
/// on a rigid plane, its section element, the mesh sized from Hertz's contact radius of the
/// impact, loaded to `to` or, when `None`, to the kinetic energy one ball brings to the plane
/// (½ m v², v its speed against the mirror plane or the wall).
///
/// Errors: a scene the section does not run head-on (one line saying why); those of the
/// scene's approach.
pub fn case_of_scene(
    scene: &Scene,
    support: Support,
    to: Option<LoadTo>,
    level: u32,
    increments: usize,
) -> Result<StaticCase> {
    let case = static_image_of(scene)?;
    let speed = match case.target {
        HeadOnTarget::IdenticalBall => case.relative_speed / 2.0,
        HeadOnTarget::RigidWall => case.relative_speed,
    };
    let loop_case = StaticCase {
        diameter: case.diameter,
        material: case.material,
        formulation: case.formulation,
        support,
        to: LoadTo::Work(0.0),
        mesh: LoopMesh::Ladder {
            sizing_radius: hertz_contact_radius(&case),
        },
        level,
        increments,
    };
    let work = LoadTo::Work(0.5 * loop_case.ball_mass() * speed * speed);
    Ok(StaticCase {
        to: to.unwrap_or(work),
        ..loop_case
    })
}
