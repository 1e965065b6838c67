//! The FE side of a two-ball run: build the model from a scene, choose the symmetry reduction,
//! step the explicit solver from first touch until the balls have separated, and reduce the
//! nodal state to centre-of-mass velocities, spins, δ(t) and energies of the full system.
//!
//! Frames: the model is built in the contact frame of [`crate::scene::Touch`] (x along the
//! line of centres, y along the slip) and in the centre-of-mass frame of the pair (Galilean
//! invariance: subtracting a uniform velocity changes nothing in the collision), so that the
//! contact plane x = 0 stays put; results are transformed back to the scene frame.

use crate::error::{Error, Result};
use crate::fe::contact::{
    ContactParams, ContactProbe, CoulombFriction, PenaltyRule, RigidPlane, SurfacePair,
};
use crate::fe::explicit::{Settings, Solver};
use crate::fe::interaction::Interaction;
use crate::fe::model::Model;
use crate::fe::subcycle::SubcycleReport;
use crate::mesh::ball::{ball, BallSpec, Cut};
use crate::mesh::block::{wall_block, WallBlockSpec};
use crate::mesh::Mesh;
use crate::scene::{BallScene, MeshSettings, Scene, Switch, Touch};
use crate::study::records::outcome::{ball_inertia, dissipation_factor, Outcome};
use crate::study::run::section::{block_grading, simulate_section, SectionRun};
use crate::study::run::smoothed_force::smooth_history;
use crate::study::run::snapshots::Snapshots;
use std::time::Instant;

pub use crate::study::run::history::{HistoryRow, HISTORY_HEADER};
pub use crate::study::run::reduction::{choose_reduction, Reduction};
use crate::study::run::simulation::CentreOfMassFrame;
pub use crate::study::run::simulation::{
    advice, RunOptions, Savings, Simulation, DEFAULT_HOLD_FRACTION,
};

/// The point a part spins about: its mesh's centre of mass (so its momentum is the scene's
/// velocity alone; a graded ball's lies microns off the sphere's centre), or `centre` (m)
/// without spin, where the point does not matter.
fn spin_centre(model: &Model, part: usize, spin: [f64; 3], centre: [f64; 3]) -> Result<[f64; 3]> {
    if spin == [0.0; 3] {
        Ok(centre)
    } else {
        model.centre_of_mass(part)
    }
}

fn pair_kinematics(scene: &Scene, touch: &Touch) -> CentreOfMassFrame {
    if scene.wall.is_some() {
        // The wall's frame: the wall at rest, ball 1 at its own velocity.
        return CentreOfMassFrame {
            v_cm: [0.0; 3],
            u: [touch.v[0], [0.0; 3]],
        };
    }
    let m1 = ball_inertia(scene.ball1.material.rho, scene.ball1.diameter).0;
    let m2 = ball_inertia(scene.ball2.material.rho, scene.ball2.diameter).0;
    let [v1, v2] = touch.v;
    let v_cm = [0, 1, 2].map(|k| (m1 * v1[k] + m2 * v2[k]) / (m1 + m2));
    let u = [
        [0, 1, 2].map(|k| v1[k] - v_cm[k]),
        [0, 1, 2].map(|k| v2[k] - v_cm[k]),
    ];
    CentreOfMassFrame { v_cm, u }
}

/// The mesh of ball `name` ("ball1" or "ball2") with its contact pole at +x and centre at the
/// origin; a rejected mesh setting is named from the scene root (`ball2.mesh.size`).
fn ball_mesh(name: &str, b: &BallScene, cut: Cut) -> Result<Mesh> {
    match &b.mesh {
        MeshSettings::Builtin { size, pole_size } => ball(&BallSpec {
            diameter: b.diameter,
            size: *size,
            pole_size: Some(*pole_size),
            cut,
        })
        .map_err(|e| e.within(&format!("{name}.mesh"))),
        MeshSettings::File { path } => file_ball_mesh(name, path, b.diameter),
    }
}

/// A ball mesh read from a gmsh file: checked to span the scene's diameter (within 2 %),
/// centred at the origin, and given a `contact` face set (boundary quads within 30° of +x)
/// when the file has none.
fn file_ball_mesh(name: &str, path: &std::path::Path, d: f64) -> Result<Mesh> {
    let mut mesh = crate::mesh::msh::read(path)?.mesh;
    let field = format!("{name}.mesh.file");
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &mesh.nodes {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let span = hi[0] - lo[0];
    if !(span.is_finite() && (span - d).abs() <= 0.02 * d) {
        return Err(Error::invalid(
            &field,
            format!("{} (x extent {span:.4e} m)", path.display()),
            format!("a whole ball of the scene's diameter {d} m within 2 %"),
        ));
    }
    let centre = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    mesh = mesh.translated(centre.map(|c| -c));
    if !mesh.face_sets.contains_key("contact") {
        let cos30 = (30f64).to_radians().cos() * d / 2.0 * 0.999;
        let faces: Vec<[u32; 4]> = mesh
            .boundary
            .iter()
            .copied()
            .filter(|q| q.iter().all(|&n| mesh.nodes[n as usize][0] >= cos30))
            .collect();
        if faces.is_empty() {
            return Err(Error::invalid(
                &field,
                path.display(),
                "a ball mesh with boundary quads near +x",
            ));
        }
        let mut nodes: Vec<u32> = faces.iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        mesh.face_sets.insert("contact".into(), faces);
        mesh.node_sets.insert("contact".into(), nodes);
    }
    Ok(mesh)
}

/// Whether plasticity can be skipped for a ball: the Hertz peak contact pressure of the
/// elastic impact stays below 0.8 × 1.6 σ_s (first yield under a Hertz contact is at
/// p0 ≈ 1.6 σ_s, Johnson 1985 §4.2), for both balls' yield strengths.
fn never_yields(scene: &Scene, touch: &Touch, b: &BallScene) -> bool {
    let (Ok(b1), Ok(b2)) = (
        crate::analytic::Body::ball(scene.ball1.material, scene.ball1.diameter, "ball1"),
        crate::analytic::Body::ball(scene.ball2.material, scene.ball2.diameter, "ball2"),
    ) else {
        return false;
    };
    let pair = crate::analytic::HertzPair::between(&b1, &b2);
    let v = touch.approach_speed;
    let a = pair.contact_radius(pair.max_approach(v));
    let p0 = 1.5 * pair.peak_force(v) / (std::f64::consts::PI * a * a);
    p0.is_finite() && p0 < 0.8 * 1.6 * b.material.yield_strength
}

/// Mass, centre of mass (m), linear momentum (kg m/s), and angular momentum about the centre
/// of mass (kg m²/s) and inertia tensor about it (kg m²) of the nodes `range`.
struct Rigid {
    mass: f64,
    com: [f64; 3],
    momentum: [f64; 3],
}

fn rigid(solver: &Solver, range: std::ops::Range<usize>) -> Rigid {
    let (x, v, m) = (solver.x(), solver.v(), solver.mass());
    let (mut mt, mut mx, mut mv) = (0.0, [0.0; 3], [0.0; 3]);
    for n in range {
        mt += m[n];
        for k in 0..3 {
            mx[k] += m[n] * x[n][k];
            mv[k] += m[n] * v[n][k];
        }
    }
    Rigid {
        mass: mt,
        com: mx.map(|c| c / mt),
        momentum: mv,
    }
}

/// Spin about z of the half ball `range` whose full ball is mirror-symmetric about z = 0:
/// ω_z = L_z / I_zz about the axis through its centre of mass parallel to z (both sums are
/// independent of the z offset, and doubling both for the mirrored half changes nothing).
fn half_spin_z(solver: &Solver, range: std::ops::Range<usize>, r: &Rigid) -> f64 {
    let (x, v, m) = (solver.x(), solver.v(), solver.mass());
    let vc = r.momentum.map(|p| p / r.mass);
    let (mut lz, mut izz) = (0.0, 0.0);
    for n in range {
        let (rx, ry) = (x[n][0] - r.com[0], x[n][1] - r.com[1]);
        let (ux, uy) = (v[n][0] - vc[0], v[n][1] - vc[1]);
        lz += m[n] * (rx * uy - ry * ux);
        izz += m[n] * (rx * rx + ry * ry);
    }
    if izz > 0.0 {
        lz / izz
    } else {
        0.0
    }
}

/// Part `p`'s rotational inertia about the z axis through its centre of mass over m R² (-,
/// `radius` R in m): 0.4 for a solid sphere; a lumped mesh's surface nodes carry mass out to
/// R, so a ball mesh's is a little larger. Errors: no part `p`.
fn spin_inertia_ratio(solver: &Solver, p: usize, radius: f64) -> Result<f64> {
    let range = solver.model().part(p)?.nodes.clone();
    let r = rigid(solver, range.clone());
    let (x, m) = (solver.x(), solver.mass());
    let izz: f64 = range
        .map(|n| m[n] * ((x[n][0] - r.com[0]).powi(2) + (x[n][1] - r.com[1]).powi(2)))
        .sum();
    Ok(izz / (r.mass * radius * radius))
}

/// Rigid state (contact frame, CoM frame of the pair) of both balls: velocities, spins,
/// centre positions (x only is used for δ).
/// Velocities (m/s) and spins (rad/s) of both balls, and the distance of their centres (m).
type BallStates = ([[f64; 3]; 2], [[f64; 3]; 2], f64);

/// The error of a 3D model asked to build or read the axisymmetric reduction (which runs on
/// the meridian section instead): a defect, not a scene error.
fn not_3d() -> Error {
    Error::Numerical("the 3D model cannot run the axisymmetric reduction".into())
}

/// The model, its interactions, and a read handle on the contact's output.
type Built = (Model, Vec<Box<dyn Interaction>>, ContactProbe);

/// Centre-of-mass velocity (m/s), spin (rad/s) and centre (m) of part `p` on the half model
/// (in the plane z = 0, spin about z) or the full one.
fn part_state(solver: &Solver, red: Reduction, p: usize) -> Result<([f64; 3], [f64; 3], [f64; 3])> {
    let range = solver.model().part(p)?.nodes.clone();
    let r = rigid(solver, range.clone());
    if red == Reduction::Half {
        let m = r.momentum;
        Ok((
            [m[0] / r.mass, m[1] / r.mass, 0.0],
            [0.0, 0.0, half_spin_z(solver, range, &r)],
            [r.com[0], r.com[1], 0.0],
        ))
    } else {
        let (v, w) = solver.part_motion(p)?;
        Ok((v, w, r.com))
    }
}

fn ball_states(solver: &Solver, red: Reduction, wall: bool) -> Result<BallStates> {
    let model = solver.model();
    match red {
        Reduction::Axisymmetric => Err(not_3d()),
        Reduction::Quarter if wall => {
            let r = rigid(solver, model.part(0)?.nodes.clone());
            let u = r.momentum[0] / r.mass;
            // The wall at rest on x = 0: the "centre distance" is the centre's to the wall.
            Ok(([[u, 0.0, 0.0], [0.0; 3]], [[0.0; 3]; 2], -r.com[0]))
        }
        Reduction::Quarter => {
            let r = rigid(solver, model.part(0)?.nodes.clone());
            let u = r.momentum[0] / r.mass;
            // Ball 2 is the mirror image of ball 1: centre distance 2|x_c|.
            Ok((
                [[u, 0.0, 0.0], [-u, 0.0, 0.0]],
                [[0.0; 3]; 2],
                -2.0 * r.com[0],
            ))
        }
        Reduction::Half | Reduction::Full if wall => {
            // Ball 1 alone; the wall at rest on x = 0 (the "centre distance" is the centre's
            // to the wall).
            let (v, w, c) = part_state(solver, red, 0)?;
            Ok(([v, [0.0; 3]], [w, [0.0; 3]], -c[0]))
        }
        Reduction::Half | Reduction::Full => {
            let (v1, w1, c1) = part_state(solver, red, 0)?;
            let (v2, w2, c2) = part_state(solver, red, 1)?;
            let d = if red == Reduction::Half {
                ((c2[0] - c1[0]).powi(2) + (c2[1] - c1[1]).powi(2)).sqrt()
            } else {
                (0..3).map(|k| (c2[k] - c1[k]).powi(2)).sum::<f64>().sqrt()
            };
            Ok(([v1, v2], [w1, w2], d))
        }
    }
}

/// Builds the model and interactions for `scene` at `touch` with reduction `red`.
/// The cut of a ball on the half or the full model.
fn cut_of(red: Reduction) -> Cut {
    if red == Reduction::Half {
        Cut::Half
    } else {
        Cut::Full
    }
}

/// Adds ball `name` (`b`) with its mesh translated by `at.0` and then `at.1` (m), plastic
/// unless `elastic_only`, held on the symmetry plane z = 0 on the half model: its part.
fn add_ball(
    model: &mut Model,
    (name, b): (&str, &BallScene),
    mesh: Mesh,
    at: ([f64; 3], [f64; 3]),
    red: Reduction,
    elastic_only: bool,
    form: crate::fe::Formulation,
) -> Result<usize> {
    let mesh = mesh.translated(at.0).translated(at.1);
    let p = model.add_part(name, &mesh, b.material, form)?;
    model.part_mut(p)?.elastic_only = elastic_only;
    if red == Reduction::Half {
        model.fix_set(p, "sym_z", 2)?;
    }
    Ok(p)
}

/// Part `p`'s contact faces against the rigid plane x = 0 (normal −x, towards the part),
/// penalty from `material` with `params`: the model and its one interaction.
fn plane_x0(
    model: Model,
    p: usize,
    material: &crate::material::Material,
    params: ContactParams,
) -> Result<Built> {
    let faces = contact_faces(&model, p)?;
    let plane = RigidPlane::new(
        &model.nodes,
        &model.hexes,
        &faces,
        material,
        [0.0; 3],
        [-1.0, 0.0, 0.0],
        params,
    )?;
    let probe = plane.probe();
    Ok((model, vec![Box::new(plane)], probe))
}

/// Part `p`'s face set "contact" (empty when it has none).
fn contact_faces(model: &Model, p: usize) -> Result<Vec<[u32; 4]>> {
    Ok(model
        .part(p)?
        .face_sets
        .get("contact")
        .cloned()
        .unwrap_or_default())
}

fn build(
    scene: &Scene,
    touch: &Touch,
    red: Reduction,
    kin: &CentreOfMassFrame,
    elastic_only: [bool; 2],
    mu: f64,
    pre_gap_time: f64,
) -> Result<Built> {
    let (b1, b2) = (&scene.ball1, &scene.ball2);
    let (r1, r2) = (b1.diameter / 2.0, b2.diameter / 2.0);
    let form = scene.solver.element;
    let penalty = PenaltyRule::Fkn {
        factor: default_fkn() * scene.contact.penalty_factor,
    };
    let mut params = ContactParams {
        penalty,
        ..ContactParams::default()
    };
    let mut model = Model::new();
    // Free flight simulated (start_at_touch off): start each centre back along its path.
    let back = |u: [f64; 3]| u.map(|c| -c * pre_gap_time);
    // A centre at (x, 0, 0) at touch, back along the path.
    let centre = |x: f64, u: [f64; 3]| {
        let b = back(u);
        [x + b[0], b[1], b[2]]
    };
    // Ball i (0 or 1) on the half or full model from its mesh `m`, centred at (∓r, 0, 0) at
    // touch, moving with its velocity and spin: its part.
    let moving = |model: &mut Model, i: usize, m: Mesh| -> Result<usize> {
        let (name, b, x) = [("ball1", b1, -r1), ("ball2", b2, r2)][i];
        let at = ([x, 0.0, 0.0], back(kin.u[i]));
        let p = add_ball(model, (name, b), m, at, red, elastic_only[i], form)?;
        let c = spin_centre(model, p, touch.w[i], centre(x, kin.u[i]))?;
        model.set_rigid_velocity(p, kin.u[i], touch.w[i], c)?;
        Ok(p)
    };
    match red {
        Reduction::Axisymmetric => Err(not_3d()),
        Reduction::Quarter if elastic_wall(scene).is_some() => {
            let m1 = ball_mesh("ball1", b1, Cut::Quarter)?;
            let p1 = moving(&mut model, 0, m1)?;
            model.fix_set(p1, "sym_y", 1)?;
            model.fix_set(p1, "sym_z", 2)?;
            params.friction = None;
            block_face(model, scene, p1, Cut::Quarter, params)
        }
        Reduction::Quarter => {
            let m1 = ball_mesh("ball1", b1, Cut::Quarter)?
                .translated([-r1, 0.0, 0.0])
                .translated(back(kin.u[0]));
            let p1 = model.add_part("ball1", &m1, b1.material, form)?;
            model.part_mut(p1)?.elastic_only = elastic_only[0];
            model.fix_set(p1, "sym_y", 1)?;
            model.fix_set(p1, "sym_z", 2)?;
            model.set_rigid_velocity(p1, kin.u[0], [0.0; 3], [-r1, 0.0, 0.0])?;
            // The mirror plane of the pair (design.md §6): each ball crosses it by p while the
            // two-pass pair sees a gap 2p at half stiffness in each of its two passes, so a
            // node of the pair carries 2 k p. The plane reproduces that with twice the pair's
            // factor and half its penetration limit (measured on p instead of 2p).
            params.friction = None;
            if scene.wall.is_none() {
                params.penalty = PenaltyRule::Fkn {
                    factor: 2.0 * default_fkn() * scene.contact.penalty_factor,
                };
                params.max_penetration *= 0.5;
            }
            // A rigid wall is the plane itself: the 3D rule on the ball's own stiffness, once.
            plane_x0(model, p1, &b1.material, params)
        }
        Reduction::Half | Reduction::Full if elastic_wall(scene).is_some() => {
            // An oblique or spinning ball on an elastic wall: the ball against the block's
            // face, both cut alike, with friction.
            let m1 = ball_mesh("ball1", b1, cut_of(red))?;
            let p1 = moving(&mut model, 0, m1)?;
            params.friction = (mu > 0.0).then(|| CoulombFriction::new(mu));
            block_face(model, scene, p1, cut_of(red), params)
        }
        Reduction::Half | Reduction::Full if scene.wall.is_some() => {
            // An oblique or spinning ball on a rigid wall: the half ball (motion in its
            // symmetry plane z = 0) or the whole ball against the frictional wall plane x = 0,
            // penalty of the ball's own stiffness as on the quarter model.
            let m1 = ball_mesh("ball1", b1, cut_of(red))?;
            let p1 = moving(&mut model, 0, m1)?;
            params.friction = (mu > 0.0).then(|| CoulombFriction::new(mu));
            plane_x0(model, p1, &b1.material, params)
        }
        Reduction::Half | Reduction::Full => {
            let m1 = ball_mesh("ball1", b1, cut_of(red))?;
            let m2 = ball_mesh("ball2", b2, cut_of(red))?.mirrored_x();
            let p1 = moving(&mut model, 0, m1)?;
            let p2 = moving(&mut model, 1, m2)?;
            params.friction = (mu > 0.0).then(|| CoulombFriction::new(mu));
            surface_pair(model, (p1, &b1.material), (p2, &b2.material), params)
        }
    }
}

/// The scene's elastic wall: its block's material and its size [W, H] (m), or `None`.
fn elastic_wall(scene: &Scene) -> Option<(crate::material::Material, [f64; 2])> {
    let w = scene.wall?;
    Some((w.material?, w.size?))
}

/// Adds the elastic wall's block under the contact point (face x = 0, body in x > 0, base
/// fixed, cut as the ball `cut`, graded as the section's block by [`block_grading`]) and the
/// node-to-segment pair of ball part `p1`'s contact faces against its face: the model and its
/// one interaction. Errors: no elastic wall, a mesh file for ball 1, or a block the mesher
/// refuses (named from `wall`).
fn block_face(
    mut model: Model,
    scene: &Scene,
    p1: usize,
    cut: Cut,
    params: ContactParams,
) -> Result<Built> {
    let (material, [width, depth]) = elastic_wall(scene)
        .ok_or_else(|| Error::Numerical("an elastic wall's block without its wall".into()))?;
    let b1 = &scene.ball1;
    let MeshSettings::Builtin { pole_size, .. } = &b1.mesh else {
        return Err(Error::invalid(
            "ball1.mesh.file",
            "a mesh file",
            "the built-in mesher for a ball on a wall",
        ));
    };
    let mesh = wall_block(&WallBlockSpec {
        block: block_grading(*pole_size, [width, depth]),
        // The whole face: a ball sliding along it keeps meeting it (check_block_reach).
        contact_radius: width,
        cut,
    })
    .map_err(|e| e.within("wall"))?;
    let p2 = model.add_part("wall", &mesh, material, scene.solver.element)?;
    for axis in 0..3 {
        model.fix_set(p2, "base", axis)?;
    }
    if cut == Cut::Quarter {
        model.fix_set(p2, "sym_y", 1)?;
    }
    if cut != Cut::Full {
        model.fix_set(p2, "sym_z", 2)?;
    }
    surface_pair(model, (p1, &b1.material), (p2, &material), params)
}

/// The node-to-segment pair of two parts' contact faces, each with its material's penalty
/// (`params`): the model and its one interaction. Errors: no part `p1` or `p2`, or faces
/// [`SurfacePair::new`] refuses.
fn surface_pair(
    model: Model,
    (p1, m1): (usize, &crate::material::Material),
    (p2, m2): (usize, &crate::material::Material),
    params: ContactParams,
) -> Result<Built> {
    let (f1, f2) = (contact_faces(&model, p1)?, contact_faces(&model, p2)?);
    let pair = SurfacePair::new(&model.nodes, &model.hexes, &f1, m1, &f2, m2, params)?;
    let probe = pair.probe();
    Ok((model, vec![Box::new(pair)], probe))
}

/// The contact law's default penalty factor FKN (scaled by `contact.penalty_factor`).
pub fn default_fkn() -> f64 {
    match PenaltyRule::default() {
        PenaltyRule::Fkn { factor } => factor,
        _ => 10.0,
    }
}

/// Runs the FE model of `scene` from first touch `touch`. `expected_duration` (s, from the
/// analytical model) sets the default hold time, history spacing and end time.
///
/// Errors: mesh or model construction failures; any solver instability (named by the solver);
/// no separation within `solver.max_steps`.
pub fn simulate(
    scene: &Scene,
    touch: &Touch,
    expected_duration: f64,
    opts: &RunOptions,
) -> Result<Simulation> {
    let start = Instant::now();
    let kin = pair_kinematics(scene, touch);
    let (red, reason) = choose_reduction(scene, touch)?;
    let (mu, _) = scene.friction_coefficients();
    let skip = scene.reduction.skip_work == Switch::Auto;
    let elastic_only = [
        skip && never_yields(scene, touch, &scene.ball1),
        skip && never_yields(scene, touch, &scene.ball2),
    ];
    if red == Reduction::Axisymmetric {
        let run = SectionRun {
            scene,
            touch,
            kin: &kin,
            expected_duration,
            reason,
            elastic_only,
        };
        return simulate_section(run, opts);
    }
    let start_at_touch = scene.reduction.start_at_touch == Switch::Auto;
    let pre = if start_at_touch { 0.0 } else { touch.t_touch };
    let (model, interactions, probe) = build(scene, touch, red, &kin, elastic_only, mu, pre)?;
    let wall = scene.wall.is_some();
    let elements = model.hexes.len();
    let nodes = model.nodes.len();
    let mut settings = Settings {
        time_step_factor: scene.solver.time_step_factor,
        subcycling: scene.solver.subcycling,
        profile: opts.profile,
        mass_scaling: scene.solver.mass_scaling,
        ..Settings::default()
    };
    if let Some((rule, hold)) = opts.level_rule {
        settings.level_rule = rule;
        settings.hold_contact_neighbours = hold;
    }
    let run = move |mut solver: Solver| -> Result<Simulation> {
        let dt0 = solver.dt();

        let duration = if expected_duration.is_finite() && expected_duration > 0.0 {
            expected_duration
        } else {
            1e-4
        };
        let hold = scene
            .solver
            .hold_time
            .unwrap_or(DEFAULT_HOLD_FRACTION * duration);
        let by_separation =
            scene.reduction.stop_at_separation == Switch::Auto && scene.solver.end_time.is_none();
        let end_time = pre + scene.solver.end_time.unwrap_or(3.0 * duration);
        let interval = scene
            .output
            .history_interval
            .unwrap_or(duration / opts.history_rows.max(2) as f64)
            .max(dt0);
        // A wall scene's system is the one ball.
        let scale = 1.0 / red.fraction(wall);
        let frame = touch.frame;
        let to_scene = |v: [f64; 3], add: [f64; 3]| {
            frame.to_global([v[0] + add[0], v[1] + add[1], v[2] + add[2]])
        };
        let (_, _, d_start) = ball_states(&solver, red, wall)?;
        let spin1_inertia_ratio = match red {
            Reduction::Half | Reduction::Full => {
                Some(spin_inertia_ratio(&solver, 0, scene.ball1.diameter / 2.0)?)
            }
            Reduction::Quarter | Reduction::Axisymmetric => None,
        };
        let approach_rate = kin.u[0][0] - kin.u[1][0];
        let d_touch = d_start - approach_rate * pre;

        let mut history = Vec::new();
        let mut impulse = 0.0;
        let e_start = solver.energy().total;
        let mut drift: f64 = 0.0;
        let mut next_row = 0.0;
        let mut apart_since: Option<f64> = None;
        let stop_reason;
        // The bar's end: the stop rule's expected end, refined at the peak and at separation.
        let expected_end = if by_separation {
            pre + duration + hold
        } else {
            end_time
        };
        let mut bar = crate::study::common::progress::RunProgress::new(
            crate::study::common::progress::Mode::detect(opts.progress),
            solver.time(),
            expected_end,
        );
        let mut peak_seen = false;
        let mut max_penetration: f64 = 0.0;
        let mut snapshots = match (&opts.snapshot_dir, scene.output.vtu_snapshots) {
            (Some(dir), n) if n > 0 => {
                Some(Snapshots::new(dir.clone(), n, pre, duration).ascii(opts.vtu_ascii))
            }
            _ => None,
        };
        loop {
            if crate::study::common::interrupt::requested() {
                return Err(Error::Interrupted(format!(
                    "at t = {:.3e} s of about {:.3e} s",
                    solver.time() - pre,
                    expected_end - pre
                )));
            }
            if let Some(s) = &mut snapshots {
                s.maybe_write(&solver, pre)?;
            }
            let t = solver.time();
            let probe_now = probe.last();
            let force_free = probe_now.active_nodes == 0 && probe_now.normal_force == 0.0;
            max_penetration = max_penetration.max(probe_now.max_penetration);
            // The whole system's normal force (the reduced model's times its copies), N.
            let normal_force = probe_now.normal_force
                * match red {
                    Reduction::Axisymmetric => 1.0,
                    Reduction::Quarter => 4.0,
                    Reduction::Half => 2.0,
                    Reduction::Full => 1.0,
                };
            let record = t >= next_row;
            let check = solver.step_count().is_multiple_of(16);
            if record || (by_separation && check) {
                let (u, w, d) = ball_states(&solver, red, wall)?;
                if record {
                    let e = solver.energy();
                    let row = HistoryRow {
                        t: t - pre,
                        delta: d_touch - d,
                        normal_force,
                        tangential_force: probe_now.tangential_force
                            * if red == Reduction::Half { 2.0 } else { 1.0 },
                        v: [to_scene(u[0], kin.v_cm), to_scene(u[1], kin.v_cm)],
                        w: [frame.to_global(w[0]), frame.to_global(w[1])],
                        kinetic: scale * e.solid.kinetic,
                        elastic: scale * e.solid.elastic,
                        plastic: scale * e.solid.plastic,
                        hourglass: scale * e.solid.hourglass,
                        contact_stored: scale * e.interaction_stored,
                        contact_dissipated: scale * e.interaction_dissipated,
                        total: scale * e.total,
                        impulse,
                        normal_force_smoothed: 0.0,
                    };
                    if e_start > 0.0 {
                        drift = drift.max((e.total - e_start).abs() / e_start);
                    }
                    if !row.is_finite() {
                        return Err(Error::Numerical(format!(
                        "non-finite state at t = {t:.6e} s (step {}): unstable run; lower solver.time_step_factor or contact.penalty_factor",
                        solver.step_count()
                    )));
                    }
                    history.push(row);
                    next_row = t + interval;
                    bar.update(t);
                }
                if by_separation {
                    let separating = u[0][0] - u[1][0] < 0.0;
                    let touched = probe.touched();
                    if touched && separating && !peak_seen {
                        // Unloading is no longer than loading: the end is at most this far.
                        peak_seen = true;
                        bar.set_end(t + (t - pre) + hold);
                    }
                    if touched && separating && force_free {
                        let since = *apart_since.get_or_insert(t);
                        bar.set_end(since + hold);
                        if t - since >= hold {
                            stop_reason = format!("separated: contact force zero for {hold:.3e} s");
                            break;
                        }
                    } else {
                        apart_since = None;
                    }
                }
            }
            if !by_separation && t >= end_time {
                stop_reason = format!("end time {:.3e} s reached", end_time - pre);
                break;
            }
            if solver.step_count() >= scene.solver.max_steps {
                return Err(Error::Numerical(format!(
                "the balls had not separated after solver.max_steps = {} steps (t = {:.6e} s): raise solver.max_steps or set solver.end_time",
                scene.solver.max_steps,
                t - pre
            )));
            }
            solver.step().map_err(advice)?;
            impulse += normal_force * (solver.time() - t);
        }
        bar.finish();
        if let Some(s) = &mut snapshots {
            s.finish(&solver, pre)?;
        }
        let (u, w, _) = ball_states(&solver, red, wall)?;
        let v_after = [to_scene(u[0], kin.v_cm), to_scene(u[1], kin.v_cm)];
        let w_after = [frame.to_global(w[0]), frame.to_global(w[1])];
        let data = probe.get();
        let contact_duration = data.contact_duration();
        let force = smooth_history(&mut history, contact_duration);
        let delta_max = history.iter().map(|r| r.delta).fold(0.0, f64::max);
        let e_rel = -(u[0][0] - u[1][0]) / (kin.u[0][0] - kin.u[1][0]);
        let outcome = Outcome {
            e: e_rel,
            v1_after: v_after[0],
            v2_after: v_after[1],
            w1_after: w_after[0],
            w2_after: w_after[1],
            delta_max,
            contact_duration,
            eta: dissipation_factor(scene, v_after, w_after),
        };
        outcome.check_finite("FE model")?;
        let report = solver.energy();
        if e_start > 0.0 {
            drift = drift.max((report.total - e_start).abs() / e_start);
        }
        let steps = solver.step_count();
        Ok(Simulation {
            outcome,
            energy_error: drift.max(report.max_balance_error),
            savings: Savings {
                reduction: red,
                reduction_reason: reason,
                start_at_touch,
                free_flight_time: touch.t_touch,
                stop_rule: if by_separation {
                    "separation".into()
                } else {
                    "end_time".into()
                },
                hold_time: hold,
                elastic_only,
                friction: red != Reduction::Quarter && mu > 0.0,
                subcycling: solver.subcycling(),
            },
            elements,
            nodes,
            steps,
            element_cycles: solver.element_updates(),
            dt: dt0,
            stop_reason,
            wall_time_s: start.elapsed().as_secs_f64(),
            max_penetration,
            contact_radius: None,
            spin1_inertia_ratio,
            force,
            history,
            phases: opts.profile.then(|| solver.profile().totals()),
        })
    };
    // A small model is built and run on one thread, away from any caller's pool (a sweep's).
    // A large one is built on the caller's threads (the results are the same on any thread
    // count), and its time loop then runs on one thread if a step updates few elements.
    if elements < PARALLEL_MIN_ELEMENTS {
        return with_threads_for(elements, move || {
            run(Solver::new(model, interactions, settings)?)
        });
    }
    let solver = Solver::new(model, interactions, settings)?;
    let work = elements_per_step(elements, &solver.subcycling());
    with_threads_for(work, move || run(solver))
}

/// Element updates in one step of a model of `elements` elements, on average: all of them
/// single-rate, `elements` / predicted saving with subcycling.
fn elements_per_step(elements: usize, sub: &SubcycleReport) -> usize {
    if sub.used && sub.predicted_saving > 1.0 {
        (elements as f64 / sub.predicted_saving).round() as usize
    } else {
        elements
    }
}

/// Models whose steps update fewer elements than this on average (all of them single-rate,
/// elements / predicted saving with subcycling) run their time loop on one thread: handing a
/// few hundred or thousand element updates to a second thread costs more than it saves (the
/// converged default scene, 7936 elements subcycled with about 1600 updates a step, ran
/// 10-20 % slower on two threads than on one). The results are the same on any thread count.
pub const PARALLEL_MIN_ELEMENTS: usize = 5000;

/// Runs `f` on the current thread pool, or on a one-thread pool when a step updates fewer
/// than [`PARALLEL_MIN_ELEMENTS`] elements (`elements`, on average).
fn with_threads_for<T: Send>(elements: usize, f: impl FnOnce() -> T + Send) -> T {
    if elements >= PARALLEL_MIN_ELEMENTS || rayon::current_num_threads() == 1 {
        return f();
    }
    let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(1).build() else {
        return f();
    };
    // The caller's cancel request and progress receiver go with the work.
    let (token, hook) = (
        crate::study::common::interrupt::current(),
        crate::study::common::progress::current(),
    );
    let f = move || {
        crate::study::common::interrupt::within(token.as_ref(), || {
            crate::study::common::progress::reporting(hook.as_ref(), f)
        })
    };
    // Wait on a plain thread: a pool worker (a sweep's) that waited inside `install` on
    // another pool would meanwhile take more work from its own pool, and a sweep would start
    // all its small cases at once.
    std::thread::scope(|s| s.spawn(|| pool.install(f)).join())
        .unwrap_or_else(|e| std::panic::resume_unwind(e))
}

/// The FE runner of a sweep case: analytical duration estimate, FE run, summary and δ(t).
///
/// Errors: as [`simulate`]; a scene without impact (the sweep never asks for one).
pub fn sweep_case(scene: &Scene) -> Result<crate::study::records::case::FeCase> {
    let touch = match crate::scene::approach(scene)? {
        crate::scene::Approach::Impact(t) => t,
        crate::scene::Approach::NoImpact { reason } => {
            return Err(Error::Parse(format!("no impact: {reason}")))
        }
    };
    let (an, _) = crate::study::records::outcome::analytic_outcome(scene, &touch)?;
    let sim = simulate(
        scene,
        &touch,
        an.contact_duration,
        &RunOptions {
            history_rows: 400,
            ..RunOptions::default()
        },
    )?;
    Ok(sim.fe_case())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The thread choice follows the element updates of one step: every element single-rate,
    /// elements / predicted saving with subcycling (the converged default scene: 7936
    /// elements at a 5x saving update about 1600 a step, below the parallel threshold).
    #[test]
    fn work_per_step_is_elements_over_the_subcycling_saving() {
        let off = SubcycleReport::default();
        assert_eq!(elements_per_step(7936, &off), 7936);
        let on = SubcycleReport {
            used: true,
            predicted_saving: 4.96,
            ..Default::default()
        };
        let w = elements_per_step(7936, &on);
        assert_eq!(w, 1600);
        assert!(w < PARALLEL_MIN_ELEMENTS && 7936 >= PARALLEL_MIN_ELEMENTS);
    }
}
