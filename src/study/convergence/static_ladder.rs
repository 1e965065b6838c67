//! A quasi-static loop's numbers with their error bars: the loop run on consecutive levels
//! of the mesh ladder (each halving every length), each quantity the finest level's value
//! with the estimate of [`crate::study::records::estimate`] (two levels: order 2 assumed,
//! safety factor 3; three: the observed order).
//!
//! The plastic e of a section is a sawtooth over the ring spacing at the contact edge, in a
//! loop as in an impact (where the outermost ring on the plane lands), so the plain ladder's
//! levels differ by more than their error. [`banded_case`] runs the plain level 0 once, reads
//! the contact edge from it and meshes every level with a band of finer rings from 0.6 to
//! 1.15 edges ([`loop_band`]), past the edge at δ_max/2 too: on the default held ball levels
//! 0 and 1 then differ by 0.18 % in e instead of 1.3 % (`twoball static`, `--band none`) and
//! by 0.23 % in F(δ_max/2); level 2 lies within each of level 1's bars but those of F(δ_max)
//! (0.11 % off, bar 0.10 %) and the contact radius (0.05 %, bar 0.02 %; `--level 2
//! --levels 3`).

use super::converged_scene::head_on_case;
use super::phase_band::check_split;
use super::phase_ensemble::{hertz_contact_radius, ring_ratio, HeadOnCase, HeadOnTarget};
use crate::error::{Error, Result};
use crate::mesh::section::{ladder_ball, EdgeBand};
use crate::scene::Scene;
use crate::study::records::estimate::{estimate, Estimate};
use crate::study::run::quasi_static::{
    peak_of, run_loop, LoadTo, LoopMesh, LoopSummary, StaticCase, StaticLoop, Support,
};
use serde::Serialize;

/// The finest ladder level of a loop unless asked otherwise (levels 0 and 1 behind the
/// bars).
pub const DEFAULT_LEVEL: u32 = 1;

/// Increments of loading at level 0 unless asked otherwise ([`StaticCase::increments`]).
pub const DEFAULT_INCREMENTS: usize = 20;

/// The edge band's split unless asked otherwise: five-fold, its shells confined to the
/// surface (the laws bench's head-on band).
pub const DEFAULT_BAND_SPLIT: usize = 5;

/// The loop's band reaches in to 0.6 contact edges (of δ_max), past the edge at δ_max / 2
/// (a ∝ δ^½ elastic; 0.68 edges on the default plastic loop), so that F(δ_max / 2) is read
/// on the band's rings as well: from [0.8, 1.15] edges (the impacts' band) to [0.6, 1.15],
/// its bar falls from 1.1 % to 0.2 % at 7 % more quads.
pub const LOOP_BAND_INNER_PER_EDGE: f64 = 0.6;

/// The loop's sizing radius over the edge: the refined core then reaches
/// 1.5 × 0.38 = 0.57 edges along the surface, inside the band.
pub const LOOP_SIZING_PER_EDGE: f64 = 0.38;

/// The loop's edge band around the contact edge `edge` (m): [0.6, 1.15] edges, each layer
/// split `split`-fold (its depth as [`EdgeBand::around`]'s).
pub fn loop_band(edge: f64, split: usize) -> EdgeBand {
    EdgeBand {
        inner: LOOP_BAND_INNER_PER_EDGE * edge,
        ..EdgeBand::around(edge, split)
    }
}

/// Where a banded ladder put its band, and what finding it cost.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BandPilot {
    /// The contact edge, m: midway between the rest radii of the outermost surface ring on
    /// the plane at δ_max in the plain level-0 loop and of the next ring.
    pub edge_m: f64,
    /// Shells per layer interval in the band.
    pub split: usize,
    /// Quads of the pilot's mesh.
    pub pilot_quads: usize,
    /// Newton iterations of the pilot's loading (its unloading is not run).
    pub pilot_iterations: usize,
}

/// Increments of the pilot's loading for a case of `increments` at level 0: a quarter (at
/// least 4). The pilot only reads which surface ring is the outermost on the plane at δ_max,
/// which the increments barely move, so it need not follow the load path finely.
pub fn pilot_increments(increments: usize) -> usize {
    (increments / 4).max(4)
}

/// `case` (on the plain ladder) with every level meshed with an edge band split `split`-fold
/// at the contact edge of its plain level-0 loading (with [`pilot_increments`]), and where
/// the band went.
///
/// Errors: a bad `split`, a case not on the plain ladder; those of the pilot loop (a band
/// that does not fit a level fails when the ladder meshes it).
pub fn banded_case(case: &StaticCase, split: usize) -> Result<(StaticCase, BandPilot)> {
    check_split(split)?;
    let LoopMesh::Ladder { sizing_radius } = case.mesh else {
        return Err(Error::invalid(
            "static.mesh",
            format!("{:?}", case.mesh),
            "the plain ladder (the band is placed from its level 0)",
        ));
    };
    let pilot = peak_of(&StaticCase {
        level: 0,
        increments: pilot_increments(case.increments),
        ..*case
    })?;
    let r = pilot.outermost_ring;
    let q = ring_ratio(&ladder_ball(case.diameter, sizing_radius, 0)?, r)?;
    let edge = 0.5 * r * (1.0 + q);
    let banded = StaticCase {
        mesh: LoopMesh::Banded {
            sizing_radius: LOOP_SIZING_PER_EDGE * edge,
            band: loop_band(edge, split),
        },
        ..*case
    };
    Ok((
        banded,
        BandPilot {
            edge_m: edge,
            split,
            pilot_quads: pilot.quads,
            pilot_iterations: pilot.iterations,
        },
    ))
}

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
    let loops = run_levels(case, case.level + 1 - levels)?;
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

/// The loops of `case` on levels `first ..= case.level`, coarse to fine. The finest level
/// (the longest, by about four times the next) runs on the shared thread pool, the coarser
/// ones meanwhile on a thread of their own: the finest level's sequential linear solves then
/// never wait behind the coarser levels' element work, which a shared pool's work stealing
/// lets them do. Each loop's numbers do not depend on the threads that run it.
fn run_levels(case: &StaticCase, first: u32) -> Result<Vec<StaticLoop>> {
    let coarse = || -> Result<Vec<StaticLoop>> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .map_err(|e| Error::Numerical(format!("static ladder: no thread pool ({e})")))?;
        pool.install(|| {
            (first..case.level)
                .map(|level| run_loop(&StaticCase { level, ..*case }))
                .collect()
        })
    };
    let (coarse, finest) = std::thread::scope(|s| {
        let coarse = s.spawn(coarse);
        let finest = run_loop(case);
        let coarse = coarse
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (coarse, finest)
    });
    let mut loops = coarse?;
    loops.push(finest?);
    Ok(loops)
}

/// The head-on case of a `scene` whose static image is one ball on a plane (identical
/// balls, or a ball on a rigid wall).
///
/// Errors: any other scene (one line saying why); those of the scene's approach.
pub fn static_image_of(scene: &Scene) -> Result<HeadOnCase> {
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
/// on a rigid plane, as [`case_of_head_on`].
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
    Ok(case_of_head_on(
        &static_image_of(scene)?,
        support,
        to,
        level,
        increments,
    ))
}

/// The loop case of a head-on `case`: its ball on a rigid plane, its section element, the
/// mesh sized from Hertz's contact radius of the impact, loaded to `to` or, when `None`, to
/// the kinetic energy one ball brings to the plane (½ m v², v its speed against the mirror
/// plane or the wall).
pub fn case_of_head_on(
    case: &HeadOnCase,
    support: Support,
    to: Option<LoadTo>,
    level: u32,
    increments: usize,
) -> StaticCase {
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
            sizing_radius: hertz_contact_radius(case),
        },
        level,
        increments,
    };
    let work = LoadTo::Work(0.5 * loop_case.ball_mass() * speed * speed);
    StaticCase {
        to: to.unwrap_or(work),
        ..loop_case
    }
}

/// The free ball's loops of a head-on `case` to the work one ball brings: the banded ladder
/// (band [`DEFAULT_BAND_SPLIT`]) on `level` and the level below, `increments` at level 0.
///
/// Errors: those of [`banded_case`] and [`run_loop_ladder`].
pub fn free_ball_ladder(
    case: &HeadOnCase,
    level: u32,
    increments: usize,
) -> Result<(Vec<StaticLoop>, LoopEstimate)> {
    let plain = case_of_head_on(case, Support::Free, None, level, increments);
    let (banded, _) = banded_case(&plain, DEFAULT_BAND_SPLIT)?;
    run_loop_ladder(&banded, 2)
}
