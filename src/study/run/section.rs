//! The FE side of a head-on run on the meridian section ([`crate::fe::section`]): the scene's
//! balls meshed as half-discs, run from first touch to separation by
//! [`HeadOn::run_observed`], and the outcome written in the scene's terms (the same
//! [`Simulation`], results.json keys and history.csv columns as the 3D models).
//!
//! Frames: the section's axis z is the contact frame's x (the line of centres, from ball 1
//! towards ball 2), and the run is in the pair's centre-of-mass frame, like the 3D models.

use crate::error::{Error, Result};
use crate::fe::elements::ring::QuadFormulation;
use crate::fe::solver::subcycle::{SubcycleReport, Subcycling};
use crate::fe::subcycle::Integration;
use crate::fe::Formulation;
use crate::mesh::section::{ball, block, BlockSpec, SectionMesh, SectionSpec};
use crate::scene::{BallScene, MeshSettings, PlaneEnforcement, Scene, Switch, Touch};
use crate::study::common::progress::{Mode, RunProgress};
use crate::study::records::outcome::{dissipation_factor, Outcome};
use crate::study::run::history::HistoryRow;
use crate::study::run::reduction::Reduction;
use crate::study::run::section_impact::{
    HeadOn, ImpactRow, OtherBall, PlaneContact, Target, WallBlock,
};
use crate::study::run::simulation::{
    CentreOfMassFrame, RunOptions, Savings, Simulation, DEFAULT_HOLD_FRACTION,
};
use crate::study::run::smoothed_force::smooth_history;
use crate::study::run::snapshots::Snapshots;
use std::time::Instant;

/// What the section run needs beyond the scene: the kinematics at touch, the analytical
/// contact duration (s) and the reduction's reason.
pub(super) struct SectionRun<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// First touch.
    pub touch: &'a Touch,
    /// Centre-of-mass frame velocities.
    pub kin: &'a CentreOfMassFrame,
    /// Expected contact duration (s), from the analytical model.
    pub expected_duration: f64,
    /// Why the reduction was chosen.
    pub reason: String,
    /// Per ball: plasticity skipped.
    pub elastic_only: [bool; 2],
}

/// The meridian mesh of ball `name` from its built-in mesh settings.
///
/// Errors: a mesh file (the section model meshes its own sections), or sizes the section
/// mesher rejects (named from the scene root).
pub fn section_mesh(name: &str, b: &BallScene) -> Result<SectionMesh> {
    ball(&section_spec(name, b)?).map_err(|e| e.within(&format!("{name}.mesh")))
}

/// The meridian mesh settings of ball `name` from its built-in mesh settings.
///
/// Errors: a mesh file (the section model meshes its own sections).
pub fn section_spec(name: &str, b: &BallScene) -> Result<SectionSpec> {
    match b.mesh {
        MeshSettings::Builtin { size, pole_size } => Ok(SectionSpec {
            diameter: b.diameter,
            size,
            pole_size: Some(pole_size),
        }),
        MeshSettings::File { .. } => Err(Error::Parse(format!(
            "{name}.mesh.file is set: the axisymmetric model needs the built-in mesher \
             (set reduction.symmetry = \"off\" to run the file's 3D mesh)"
        ))),
    }
}

/// Pole cells of an elastic wall's block across its uniformly meshed core (about 1.7
/// contact radii at the ladder's six pole cells per contact radius).
const BLOCK_CORE_CELLS: f64 = 10.0;

/// Cells of the block's far-field size across its smaller side.
const BLOCK_CELLS_PER_SIDE: f64 = 10.0;

/// The block of sides `sides` = [W, H] (m) under a ball of pole size `pole` (m): the pole size
/// over [`BLOCK_CORE_CELLS`] cells, growing to a [`BLOCK_CELLS_PER_SIDE`]th of the smaller side
/// (the section's block and the 3D models' alike).
pub(crate) fn block_grading(pole: f64, [width, height]: [f64; 2]) -> BlockSpec {
    let size = width.min(height) / BLOCK_CELLS_PER_SIDE;
    BlockSpec {
        width,
        height,
        size,
        pole_size: pole.min(size),
        core: BLOCK_CORE_CELLS * pole,
    }
}

/// The block of an elastic `[wall]` (`None` for a rigid wall or two balls): its section
/// meshed with ball 1's pole size at the contact point over [`BLOCK_CORE_CELLS`] cells,
/// growing to a tenth of its smaller side.
///
/// Errors: a ball-1 mesh file, or block sizes the mesher rejects (named from `wall`).
pub fn wall_block(scene: &Scene) -> Result<Option<WallBlock>> {
    let Some(w) = scene.wall else {
        return Ok(None);
    };
    let (Some(material), Some([width, height])) = (w.material, w.size) else {
        return Ok(None);
    };
    let pole = match &scene.ball1.mesh {
        MeshSettings::Builtin { pole_size, .. } => *pole_size,
        MeshSettings::File { .. } => {
            return Err(Error::Parse(
                "ball1.mesh.file is set: the axisymmetric model needs the built-in mesher".into(),
            ))
        }
    };
    let mesh = block(&block_grading(pole, [width, height])).map_err(|e| e.within("wall"))?;
    Ok(Some(WallBlock {
        mesh,
        material,
        elastic_only: false,
    }))
}

/// The section element: `solver.section_element` when set, else the counterpart of the 3D
/// element choice (one point with hourglass control for the one-point hexahedron,
/// selectively reduced (B-bar) for B-bar).
pub(crate) fn formulation(scene: &Scene) -> QuadFormulation {
    if let Some(f) = scene.solver.section_element {
        return f;
    }
    match scene.solver.element {
        Formulation::OnePoint => QuadFormulation::default(),
        Formulation::BBar => QuadFormulation::SelectiveReduced,
    }
}

/// How the section enforces its rigid plane for the scene's `contact.plane`.
pub(crate) fn plane_contact(scene: &Scene) -> PlaneContact {
    match scene.contact.plane {
        PlaneEnforcement::Kinematic => PlaneContact::Kinematic,
        PlaneEnforcement::Penalty => PlaneContact::Nodal,
    }
}

/// The head-on model of `run`: ball 1 against the rigid wall of a wall scene (penalty FKN on
/// the ball's own stiffness) or the block of an elastic wall, against the symmetry plane for identical balls, both sections
/// otherwise.
fn head_on(run: &SectionRun<'_>) -> Result<HeadOn> {
    let scene = run.scene;
    let mesh1 = section_mesh("ball1", &scene.ball1)?;
    let speed1 = run.kin.u[0][0];
    let target = if let Some(block) = wall_block(scene)? {
        Target::ElasticWall(Box::new(block))
    } else if scene.wall.is_some() {
        Target::RigidWall
    } else if scene.identical_balls() {
        Target::MirrorBall
    } else {
        Target::Ball(Box::new(OtherBall {
            mesh: section_mesh("ball2", &scene.ball2)?,
            material: scene.ball2.material,
            elastic_only: run.elastic_only[1],
            speed: -run.kin.u[1][0],
        }))
    };
    let two_balls = matches!(target, Target::Ball(_) | Target::ElasticWall(_));
    let mut h = HeadOn::new(mesh1, scene.ball1.material, speed1, target);
    h.integration = integration(scene.solver.subcycling, two_balls);
    h.elastic_only = run.elastic_only[0];
    h.formulation = formulation(scene);
    h.fkn = 10.0 * scene.contact.penalty_factor;
    h.plane_contact = plane_contact(scene);
    h.time_step_factor = scene.solver.time_step_factor;
    h.mass_scaling = scene.solver.mass_scaling;
    let duration = usable_duration(run.expected_duration);
    h.hold_time = Some(
        scene
            .solver
            .hold_time
            .unwrap_or(DEFAULT_HOLD_FRACTION * duration),
    );
    let by_separation =
        scene.reduction.stop_at_separation == Switch::Auto && scene.solver.end_time.is_none();
    if !by_separation {
        h.end_time = Some(scene.solver.end_time.unwrap_or(3.0 * duration));
    }
    h.max_steps = scene.solver.max_steps;
    Ok(h)
}

/// The section's time integration for the scene's `solver.subcycling`: subcycled unless
/// `off`, except for two meshed bodies (two balls, or a ball and a wall's block) under
/// `auto`, whose pair contact has not been checked subcycled (single rate there).
fn integration(sub: Subcycling, two_balls: bool) -> Integration {
    match sub {
        Subcycling::Off => Integration::SingleRate,
        Subcycling::Auto if two_balls => Integration::SingleRate,
        Subcycling::Auto | Subcycling::On => Integration::subcycled(),
    }
}

/// The analytical duration when usable, else 0.1 ms (s).
fn usable_duration(d: f64) -> f64 {
    if d.is_finite() && d > 0.0 {
        d
    } else {
        1e-4
    }
}

/// One history row in the scene frame from a section row.
fn history_row(r: &ImpactRow, run: &SectionRun<'_>) -> HistoryRow {
    let frame = run.touch.frame;
    let v_cm = run.kin.v_cm;
    let to_scene = |u: f64| frame.to_global([u + v_cm[0], v_cm[1], v_cm[2]]);
    HistoryRow {
        t: r.t,
        delta: r.delta,
        normal_force: r.normal_force,
        tangential_force: 0.0,
        v: [to_scene(r.v1), to_scene(r.v2)],
        w: [[0.0; 3]; 2],
        kinetic: r.kinetic,
        elastic: r.elastic,
        plastic: r.plastic,
        hourglass: r.hourglass,
        contact_stored: r.contact_stored,
        contact_dissipated: 0.0,
        total: r.total,
        impulse: r.impulse,
        normal_force_smoothed: 0.0,
    }
}

/// Runs the head-on scene of `run` on the meridian section.
///
/// Errors: mesh settings the section mesher rejects, solver instabilities, no separation
/// within `solver.max_steps`, an interrupt.
pub(super) fn simulate_section(run: SectionRun<'_>, opts: &RunOptions) -> Result<Simulation> {
    let start = Instant::now();
    let scene = run.scene;
    let h = head_on(&run)?;
    let duration = usable_duration(run.expected_duration);
    let hold = h.hold_time.unwrap_or(0.0);
    let mut h = h;
    h.history_interval = Some(
        scene
            .output
            .history_interval
            .unwrap_or(duration / opts.history_rows.max(2) as f64),
    );
    let expected_end = h.end_time.unwrap_or(duration + hold);
    let mut bar = RunProgress::new(Mode::detect(opts.progress), 0.0, expected_end);
    let mut snapshots = match (&opts.snapshot_dir, scene.output.vtu_snapshots) {
        (Some(dir), n) if n > 0 => {
            Some(Snapshots::new(dir.clone(), n, 0.0, duration).ascii(opts.vtu_ascii))
        }
        _ => None,
    };
    let result = h.run_observed(&mut |solver, last| {
        let t = solver.time();
        if crate::study::common::interrupt::requested() {
            return Err(Error::Interrupted(format!(
                "at t = {t:.3e} s of about {expected_end:.3e} s"
            )));
        }
        if let Some(s) = &mut snapshots {
            s.maybe_write_section(solver, last)?;
        }
        bar.update(t);
        Ok(())
    });
    bar.finish();
    let r = result.map_err(crate::study::run::simulation::advice)?;
    let mut history: Vec<HistoryRow> = r.history.iter().map(|row| history_row(row, &run)).collect();
    let force = smooth_history(&mut history, r.contact_duration);
    let frame = run.touch.frame;
    let v_cm = run.kin.v_cm;
    let v_after =
        [r.v1_after, r.v2_after].map(|u| frame.to_global([u + v_cm[0], v_cm[1], v_cm[2]]));
    let w_after = [[0.0; 3]; 2];
    let outcome = Outcome {
        e: r.e,
        v1_after: v_after[0],
        v2_after: v_after[1],
        w1_after: w_after[0],
        w2_after: w_after[1],
        delta_max: r.delta_max,
        contact_duration: r.contact_duration,
        eta: dissipation_factor(scene, v_after, w_after),
    };
    outcome.check_finite("FE model")?;
    let by_separation = h.end_time.is_none();
    let subcycled = matches!(h.integration, Integration::Subcycled { max_level } if max_level > 0);
    Ok(Simulation {
        outcome,
        energy_error: r.energy_error,
        savings: Savings {
            reduction: Reduction::Axisymmetric,
            reduction_reason: run.reason,
            start_at_touch: true,
            free_flight_time: run.touch.t_touch,
            stop_rule: if by_separation {
                "separation".into()
            } else {
                "end_time".into()
            },
            subcycling: SubcycleReport {
                used: subcycled,
                reason: if subcycled {
                    "the section model's power-of-two step classes (fe::subcycle, LevelRule::SECTION)".into()
                } else {
                    "single rate: solver.subcycling = off, or two meshed balls under auto".into()
                },
                element_updates: r.element_updates,
                ..Default::default()
            },
            hold_time: hold,
            elastic_only: run.elastic_only,
            friction: false,
        },
        elements: r.elements,
        nodes: r.nodes,
        steps: r.steps,
        element_cycles: r.element_updates,
        dt: r.dt,
        stop_reason: r.stop_reason,
        wall_time_s: start.elapsed().as_secs_f64(),
        max_penetration: r.max_penetration,
        contact_radius: Some(r.contact_radius_max),
        spin1_inertia_ratio: None,
        force,
        history,
        phases: None,
    })
}
