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
    ContactParams, ContactProbe, Coulomb, PenaltyRule, RigidPlane, SurfacePair,
};
use crate::fe::explicit::{Settings, Solver};
use crate::fe::interaction::Interaction;
use crate::fe::model::Model;
use crate::fe::profile::Totals;
use crate::fe::subcycle::SubcycleReport;
use crate::mesh::ball::{ball, BallSpec, Cut};
use crate::mesh::Mesh;
use crate::scene::{
    BallScene, MeshSettings, PlaneEnforcement, Scene, Switch, Symmetry, Touch, WallKind,
};
use crate::study::records::outcome::{ball_inertia, dissipation_factor, Outcome};
use crate::study::run::section::{simulate_section, SectionRun};
use crate::study::run::smoothed_force::{smooth_history, ForceSummary};
use crate::study::run::snapshots::Snapshots;
use serde::Serialize;
use std::time::Instant;

/// Which symmetry reduction a run used.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reduction {
    /// The meridian section of a head-on impact (the axisymmetric model): one ball against
    /// the frictionless symmetry plane for identical balls, both balls' sections otherwise.
    Axisymmetric,
    /// One quarter of ball 1 against a frictionless rigid plane (1/8 of the system).
    Quarter,
    /// Both balls cut by the plane z = 0 of the motion (1/2 of the system).
    Half,
    /// Both whole balls.
    Full,
}

impl Reduction {
    /// Fraction of the whole two-ball system that the 3D models simulate (the section
    /// model reports whole-system figures itself: 1).
    pub fn fraction(self) -> f64 {
        match self {
            Reduction::Quarter => 1.0 / 8.0,
            Reduction::Half => 0.5,
            Reduction::Axisymmetric | Reduction::Full => 1.0,
        }
    }

    /// Lower-case name, as in results.json.
    pub fn name(self) -> &'static str {
        match self {
            Reduction::Axisymmetric => "axisymmetric",
            Reduction::Quarter => "quarter",
            Reduction::Half => "half",
            Reduction::Full => "full",
        }
    }
}

/// What the scene's motion at first touch allows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Allowed {
    /// Velocities along the line of centres, no spin, built-in meshes: axisymmetric.
    head_on: bool,
    /// Identical balls with built-in meshes.
    identical: bool,
    /// Tangential motion in one plane and spins normal to it.
    planar: bool,
}

fn allowed(scene: &Scene, touch: &Touch) -> Allowed {
    let [v1, v2] = touch.v;
    let [w1, w2] = touch.w;
    let scale = (v1[0] - v2[0]).abs();
    let tiny = |x: f64| x.abs() <= 1e-12 * scale;
    let spin_scale = scale / (scene.ball1.diameter.min(scene.ball2.diameter) / 2.0);
    let no_spin = |w: [f64; 3]| w.iter().all(|c| c.abs() <= 1e-12 * spin_scale);
    let planar_spin =
        |w: [f64; 3]| w[0].abs() <= 1e-12 * spin_scale && w[1].abs() <= 1e-12 * spin_scale;
    let builtin = |b: &BallScene| matches!(b.mesh, MeshSettings::Builtin { .. });
    let normal = tiny(v1[1] - v2[1]) && tiny(v1[2] - v2[2]) && no_spin(w1) && no_spin(w2);
    Allowed {
        head_on: normal && builtin(&scene.ball1) && builtin(&scene.ball2),
        identical: scene.identical_balls() && builtin(&scene.ball1),
        planar: tiny(v1[2] - v2[2]) && planar_spin(w1) && planar_spin(w2),
    }
}

/// The symmetry reduction `scene` runs with when touching as `touch`, and why.
///
/// Automatically (`auto`), a head-on impact (velocities along the line of centres, no spin)
/// of built-in meshes starting at first touch runs on the meridian section (a body of
/// revolution about the line of centres, exactly): one ball's section against the
/// frictionless symmetry plane for identical balls, both sections for unequal ones. Every
/// other scene gets the cheapest exact 3D model (`auto-3d`): a head-on impact of identical
/// balls runs as a quarter ball against the symmetry plane; with tangential motion in the
/// x-y plane (and spins about z only) the plane z = 0 stays a symmetry plane: half model;
/// anything else runs full. `reduction.symmetry` forces a model.
///
/// Errors: a forced model the motion does not allow (axisymmetric or quarter for an oblique
/// impact, quarter or half for unequal balls, any reduction for meshes read from files).
pub fn choose_reduction(scene: &Scene, touch: &Touch) -> Result<(Reduction, String)> {
    let ok = allowed(scene, touch);
    if scene.wall.is_some() {
        return wall_reduction(scene, ok);
    }
    let refuse = |what: &str, needs: &str| {
        Err(Error::invalid(
            "reduction.symmetry",
            format!("\"{what}\""),
            format!("auto or off for this scene: {what} needs {needs}"),
        ))
    };
    let quarter = || {
        (
            Reduction::Quarter,
            "identical balls, pure normal impact: quarter ball against a frictionless rigid plane"
                .to_string(),
        )
    };
    let half = || {
        (
            Reduction::Half,
            "identical balls, tangential motion in one plane: half model".to_string(),
        )
    };
    let axisymmetric = || {
        let how = if ok.identical {
            "one ball's section against the frictionless symmetry plane"
        } else {
            "both balls' sections"
        };
        (
            Reduction::Axisymmetric,
            format!(
                "head-on impact (velocities on the line of centres, no spin): axisymmetric, {how}"
            ),
        )
    };
    let head_on =
        "a head-on impact (velocities on the line of centres, no spin) of built-in meshes";
    let symmetry = resolve_auto(scene, ok.head_on);
    match symmetry {
        Symmetry::Off => Ok((Reduction::Full, "symmetry reduction switched off".into())),
        Symmetry::Axisymmetric if scene.reduction.start_at_touch == Switch::Off => refuse(
            "axisymmetric",
            "reduction.start_at_touch = \"auto\" (the section model starts at first touch)",
        ),
        Symmetry::Axisymmetric if ok.head_on => Ok(axisymmetric()),
        Symmetry::Axisymmetric => refuse("axisymmetric", head_on),
        Symmetry::Quarter if ok.head_on && ok.identical => Ok(quarter()),
        Symmetry::Quarter => refuse("quarter", &format!("identical balls in {head_on}")),
        Symmetry::Half if ok.identical && ok.planar => Ok(half()),
        Symmetry::Half => refuse(
            "half",
            "identical built-in balls with tangential motion in one plane",
        ),
        // `resolve_auto` leaves no `Auto`.
        Symmetry::Auto | Symmetry::Auto3d if !scene.identical_balls() => Ok((
            Reduction::Full,
            "the balls differ (material, diameter or mesh)".into(),
        )),
        Symmetry::Auto | Symmetry::Auto3d if !ok.identical => Ok((
            Reduction::Full,
            "meshes read from files are used whole".into(),
        )),
        Symmetry::Auto | Symmetry::Auto3d if ok.head_on => Ok(quarter()),
        Symmetry::Auto | Symmetry::Auto3d if ok.planar => Ok(half()),
        Symmetry::Auto | Symmetry::Auto3d => {
            Ok((Reduction::Full, "motion out of one plane".into()))
        }
    }
}

/// `reduction.symmetry` with `auto` made concrete: the section where the scene allows it
/// (`section`: a head-on impact of built-in meshes, or a block wall that only the section
/// models; and the run starting at touch), else `auto-3d`. Any other choice is kept.
fn resolve_auto(scene: &Scene, section: bool) -> Symmetry {
    match scene.reduction.symmetry {
        Symmetry::Auto if section && scene.reduction.start_at_touch != Switch::Off => {
            Symmetry::Axisymmetric
        }
        Symmetry::Auto => Symmetry::Auto3d,
        s => s,
    }
}

/// The reduction of a ball against a rigid wall (head-on by the scene's checks): the quarter
/// ball against the wall plane (`auto`, `quarter`) or the ball's meridian section against it
/// (`axisymmetric`). The wall models have no half or full 3D form; an elastic wall is
/// modelled on the section only.
fn wall_reduction(scene: &Scene, ok: Allowed) -> Result<(Reduction, String)> {
    let refuse = |what: &str, needs: &str| {
        Err(Error::invalid(
            "reduction.symmetry",
            format!("\"{what}\""),
            format!(
                "auto, auto-3d, quarter or axisymmetric for a ball on a wall: {what} needs {needs}"
            ),
        ))
    };
    if !ok.head_on {
        return Err(Error::invalid(
            "ball1.mesh.file",
            "a mesh file",
            "the built-in mesher for a ball on a wall (its models cut the ball by symmetry)",
        ));
    }
    let elastic = scene.wall.is_some_and(|w| w.kind == WallKind::Elastic);
    let symmetry = scene.reduction.symmetry;
    if elastic && !matches!(symmetry, Symmetry::Axisymmetric | Symmetry::Auto) {
        return Err(Error::invalid(
            "reduction.symmetry",
            format!("\"{}\"", symmetry_name(symmetry)),
            "\"auto\" or \"axisymmetric\" for an elastic wall (the 3D models have a rigid wall \
             only)",
        ));
    }
    let start_at_touch = scene.reduction.start_at_touch != Switch::Off;
    // An elastic wall has the section only: with start_at_touch = "off" its `auto` is
    // refused below as the section is.
    let symmetry = match resolve_auto(scene, true) {
        Symmetry::Auto3d if elastic && symmetry == Symmetry::Auto => Symmetry::Axisymmetric,
        s => s,
    };
    match symmetry {
        Symmetry::Axisymmetric if elastic && start_at_touch => Ok((
            Reduction::Axisymmetric,
            "ball head-on against an elastic wall: axisymmetric, the ball's section against \
                 the meshed block's face (node-to-segment penalty)"
                .into(),
        )),
        Symmetry::Off | Symmetry::Half => {
            let what = if scene.reduction.symmetry == Symmetry::Off {
                "off"
            } else {
                "half"
            };
            refuse(
                what,
                "two balls (the wall is modelled on the quarter ball or the section)",
            )
        }
        Symmetry::Axisymmetric if !start_at_touch => refuse(
            "axisymmetric",
            "reduction.start_at_touch = \"auto\" (the section model starts at first touch)",
        ),
        Symmetry::Axisymmetric => Ok((
            Reduction::Axisymmetric,
            format!(
                "ball head-on against a rigid wall: axisymmetric, the ball's section against the \
                 wall ({})",
                match scene.contact.plane {
                    PlaneEnforcement::Kinematic => "a unilateral kinematic constraint",
                    PlaneEnforcement::Penalty => "penalty of the ball's own stiffness",
                }
            ),
        )),
        Symmetry::Auto | Symmetry::Auto3d | Symmetry::Quarter => Ok((
            Reduction::Quarter,
            "ball head-on against a rigid wall: quarter ball against the rigid wall plane \
             (penalty of the ball's own stiffness)"
                .into(),
        )),
    }
}

/// The scene word of `s`.
fn symmetry_name(s: Symmetry) -> &'static str {
    match s {
        Symmetry::Auto => "auto",
        Symmetry::Auto3d => "auto-3d",
        Symmetry::Axisymmetric => "axisymmetric",
        Symmetry::Quarter => "quarter",
        Symmetry::Half => "half",
        Symmetry::Off => "off",
    }
}

/// One row of history.csv; every quantity is for the whole two-ball system (for the one ball
/// with a wall, ball 2's columns the wall's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HistoryRow {
    /// Time since first touch, s (negative during simulated free flight).
    pub t: f64,
    /// Approach δ = change of the distance between the mass centres since first touch, m.
    pub delta: f64,
    /// Normal contact force, N.
    pub normal_force: f64,
    /// Tangential (friction) contact force, N.
    pub tangential_force: f64,
    /// Centre-of-mass velocities of ball 1 and 2 (scene frame), m/s.
    pub v: [[f64; 3]; 2],
    /// Angular velocities of ball 1 and 2 (scene frame), rad/s.
    pub w: [[f64; 3]; 2],
    /// Kinetic energy (nodal, includes vibration), J.
    pub kinetic: f64,
    /// Elastic strain energy, J.
    pub elastic: f64,
    /// Plastic work, J.
    pub plastic: f64,
    /// Hourglass energy, J.
    pub hourglass: f64,
    /// Energy stored in the contact penalty springs, J.
    pub contact_stored: f64,
    /// Energy dissipated by friction (and contact damping), J.
    pub contact_dissipated: f64,
    /// Sum of all the above, J.
    pub total: f64,
    /// Normal impulse since the start of the run, ∫F dt accumulated every step, N·s.
    pub impulse: f64,
    /// Normal contact force smoothed by a triangular window of half-width T_c/20 in time,
    /// impulse kept ([`crate::study::run::smoothed_force`]), N.
    pub normal_force_smoothed: f64,
}

/// The header of history.csv, units in brackets.
pub const HISTORY_HEADER: &str = "t [s],delta [m],normal_force [N],tangential_force [N],\
v1x [m/s],v1y [m/s],v1z [m/s],v2x [m/s],v2y [m/s],v2z [m/s],\
w1x [rad/s],w1y [rad/s],w1z [rad/s],w2x [rad/s],w2y [rad/s],w2z [rad/s],\
kinetic [J],elastic [J],plastic [J],hourglass [J],contact_stored [J],contact_dissipated [J],total [J],\
impulse [N s],normal_force_smoothed [N]";

impl HistoryRow {
    /// The row as CSV (all values finite by construction; checked by the caller).
    pub fn csv(&self) -> String {
        self.values()
            .iter()
            .map(|x| format!("{x:.9e}"))
            .collect::<Vec<_>>()
            .join(",")
    }

    /// The row's values in the order of [`HISTORY_HEADER`], in its units.
    pub fn values(&self) -> Vec<f64> {
        let mut v = vec![self.t, self.delta, self.normal_force, self.tangential_force];
        v.extend(self.v.iter().flatten());
        v.extend(self.w.iter().flatten());
        v.extend([
            self.kinetic,
            self.elastic,
            self.plastic,
            self.hourglass,
            self.contact_stored,
            self.contact_dissipated,
            self.total,
            self.impulse,
            self.normal_force_smoothed,
        ]);
        v
    }

    fn is_finite(&self) -> bool {
        self.csv_values().all(f64::is_finite)
    }

    fn csv_values(&self) -> impl Iterator<Item = f64> + '_ {
        [
            self.t,
            self.delta,
            self.normal_force,
            self.tangential_force,
            self.kinetic,
            self.elastic,
            self.plastic,
        ]
        .into_iter()
        .chain([
            self.hourglass,
            self.contact_stored,
            self.contact_dissipated,
            self.total,
            self.impulse,
            self.normal_force_smoothed,
        ])
        .chain(self.v.iter().flatten().copied())
        .chain(self.w.iter().flatten().copied())
    }
}

/// What the automatic savings decided (issue 6 item 3), for results.json.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Savings {
    /// Symmetry reduction used.
    pub reduction: Reduction,
    /// Why.
    pub reduction_reason: String,
    /// Free flight solved in closed form (the run starts at first touch).
    pub start_at_touch: bool,
    /// Free-flight time skipped (or simulated when `start_at_touch` is false), s.
    pub free_flight_time: f64,
    /// `separation` (stopped once apart and force-free for `hold_time`) or `end_time`.
    pub stop_rule: String,
    /// Multi-time-step integration: used or not and why, levels, element updates.
    pub subcycling: crate::fe::subcycle::SubcycleReport,
    /// Hold time of the separation rule, s.
    pub hold_time: f64,
    /// Per ball: plasticity skipped (the Hertz peak pressure stays below yield by a margin).
    pub elastic_only: [bool; 2],
    /// Friction computed (μ > 0 and not the frictionless symmetry plane).
    pub friction: bool,
}

/// One FE run's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Simulation {
    /// Results in the scene frame.
    pub outcome: Outcome,
    /// Largest relative energy error over the run: the drift of the total energy (kinetic +
    /// elastic + plastic + hourglass + contact stored + dissipated) from its start value, or
    /// the solver's work balance error, whichever is larger.
    pub energy_error: f64,
    /// Automatic savings used.
    pub savings: Savings,
    /// Elements simulated.
    pub elements: usize,
    /// Nodes simulated.
    pub nodes: usize,
    /// Time steps taken.
    pub steps: u64,
    /// Element updates actually taken (elements × steps without subcycling).
    pub element_cycles: u64,
    /// Initial stable time step, s.
    pub dt: f64,
    /// Why the run stopped.
    pub stop_reason: String,
    /// Wall time, s.
    pub wall_time_s: f64,
    /// Largest contact penetration over the run (simulated model), m.
    pub max_penetration: f64,
    /// Largest contact radius over the run, m (the section model; None for the 3D models).
    #[serde(skip)]
    pub contact_radius: Option<f64>,
    /// The contact force: raw and smoothed peaks, residual noise, the filter
    /// (results.json `fe.force`).
    pub force: ForceSummary,
    /// History rows.
    #[serde(skip)]
    pub history: Vec<HistoryRow>,
    /// Seconds per phase of the solver's steps (`RunOptions::profile` runs only).
    #[serde(skip)]
    pub phases: Option<Totals>,
}

/// Options of a single FE run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// History rows wanted over the expected contact (≥ 2).
    pub history_rows: usize,
    /// Report progress on stderr (a bar on a terminal, plain lines elsewhere).
    pub progress: bool,
    /// Write the `.vtu` snapshots as ASCII instead of compressed binary.
    pub vtu_ascii: bool,
    /// Folder for the scene's `.vtu` snapshots (`output.vtu_snapshots` of them); none
    /// written without it.
    pub snapshot_dir: Option<std::path::PathBuf>,
    /// Time the solver's phases (`fe::profile`; the totals are [`Simulation::phases`]).
    pub profile: bool,
}

/// Contact-frame state of the pair in its centre-of-mass frame.
pub(super) struct Kinematics {
    /// Centre-of-mass velocity of the pair (contact frame), m/s.
    pub v_cm: [f64; 3],
    /// Ball velocities relative to v_cm (contact frame), m/s.
    pub u: [[f64; 3]; 2],
}

fn pair_kinematics(scene: &Scene, touch: &Touch) -> Kinematics {
    if scene.wall.is_some() {
        // The wall's frame: the wall at rest, ball 1 at its own velocity.
        return Kinematics {
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
    Kinematics { v_cm, u }
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
        Reduction::Half => {
            let mut v = [[0.0; 3]; 2];
            let mut w = [[0.0; 3]; 2];
            let mut c = [[0.0; 3]; 2];
            for p in 0..2 {
                let range = model.part(p)?.nodes.clone();
                let r = rigid(solver, range.clone());
                v[p] = [r.momentum[0] / r.mass, r.momentum[1] / r.mass, 0.0];
                w[p] = [0.0, 0.0, half_spin_z(solver, range, &r)];
                c[p] = [r.com[0], r.com[1], 0.0];
            }
            let d = ((c[1][0] - c[0][0]).powi(2) + (c[1][1] - c[0][1]).powi(2)).sqrt();
            Ok((v, w, d))
        }
        Reduction::Full => {
            let mut v = [[0.0; 3]; 2];
            let mut w = [[0.0; 3]; 2];
            let mut c = [[0.0; 3]; 2];
            for p in 0..2 {
                let (vc, om) = solver.part_motion(p)?;
                v[p] = vc;
                w[p] = om;
                c[p] = rigid(solver, model.part(p)?.nodes.clone()).com;
            }
            let d = (0..3)
                .map(|k| (c[1][k] - c[0][k]).powi(2))
                .sum::<f64>()
                .sqrt();
            Ok((v, w, d))
        }
    }
}

/// Builds the model and interactions for `scene` at `touch` with reduction `red`.
fn build(
    scene: &Scene,
    touch: &Touch,
    red: Reduction,
    kin: &Kinematics,
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
    match red {
        Reduction::Axisymmetric => Err(not_3d()),
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
            let part = model.part(p1)?;
            let faces = part.face_sets.get("contact").cloned().unwrap_or_default();
            let plane = RigidPlane::new(
                &model.nodes,
                &model.hexes,
                &faces,
                &b1.material,
                [0.0; 3],
                [-1.0, 0.0, 0.0],
                params,
            )?;
            let probe = plane.probe();
            Ok((model, vec![Box::new(plane)], probe))
        }
        Reduction::Half | Reduction::Full => {
            let cut = if red == Reduction::Half {
                Cut::Half
            } else {
                Cut::Full
            };
            let m1 = ball_mesh("ball1", b1, cut)?
                .translated([-r1, 0.0, 0.0])
                .translated(back(kin.u[0]));
            let m2 = ball_mesh("ball2", b2, cut)?
                .mirrored_x()
                .translated([r2, 0.0, 0.0])
                .translated(back(kin.u[1]));
            let p1 = model.add_part("ball1", &m1, b1.material, form)?;
            let p2 = model.add_part("ball2", &m2, b2.material, form)?;
            model.part_mut(p1)?.elastic_only = elastic_only[0];
            model.part_mut(p2)?.elastic_only = elastic_only[1];
            if red == Reduction::Half {
                model.fix_set(p1, "sym_z", 2)?;
                model.fix_set(p2, "sym_z", 2)?;
            }
            let c1 = [
                -r1 - kin.u[0][0] * pre_gap_time,
                -kin.u[0][1] * pre_gap_time,
                -kin.u[0][2] * pre_gap_time,
            ];
            let c2 = [
                r2 - kin.u[1][0] * pre_gap_time,
                -kin.u[1][1] * pre_gap_time,
                -kin.u[1][2] * pre_gap_time,
            ];
            model.set_rigid_velocity(p1, kin.u[0], touch.w[0], c1)?;
            model.set_rigid_velocity(p2, kin.u[1], touch.w[1], c2)?;
            params.friction = if mu > 0.0 {
                Some(Coulomb::new(mu))
            } else {
                None
            };
            let f1 = model
                .part(p1)?
                .face_sets
                .get("contact")
                .cloned()
                .unwrap_or_default();
            let f2 = model
                .part(p2)?
                .face_sets
                .get("contact")
                .cloned()
                .unwrap_or_default();
            let pair = SurfacePair::new(
                &model.nodes,
                &model.hexes,
                &f1,
                &b1.material,
                &f2,
                &b2.material,
                params,
            )?;
            let probe = pair.probe();
            Ok((model, vec![Box::new(pair)], probe))
        }
    }
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
    let settings = Settings {
        time_step_factor: scene.solver.time_step_factor,
        subcycling: scene.solver.subcycling,
        profile: opts.profile,
        ..Settings::default()
    };
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
        // A wall scene's system is the one ball: the quarter model is a quarter of it.
        let scale = if wall { 4.0 } else { 1.0 / red.fraction() };
        let frame = touch.frame;
        let to_scene = |v: [f64; 3], add: [f64; 3]| {
            frame.to_global([v[0] + add[0], v[1] + add[1], v[2] + add[2]])
        };
        let (_, _, d_start) = ball_states(&solver, red, wall)?;
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
                        kinetic: scale * e.kinetic,
                        elastic: scale * e.elastic,
                        plastic: scale * e.plastic,
                        hourglass: scale * e.hourglass,
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

/// A solver error in the scene's terms: the energy-growth stop gets the scene keys that
/// cure it; other errors pass unchanged.
pub fn advice(e: Error) -> Error {
    match e {
        Error::EnergyGrowth(g) => Error::Numerical(format!(
            "{g}: lower solver.time_step_factor or contact.penalty_factor"
        )),
        other => other,
    }
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

/// Default hold time after separation, as a fraction of the analytical contact duration:
/// long enough to see that the force stays zero (the gap opens by a few µm, more than the
/// pole's residual vibration), short enough not to integrate dead time.
pub const DEFAULT_HOLD_FRACTION: f64 = 0.03;

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

impl Simulation {
    /// The run as a sweep case: its outcome, figures and δ(t).
    pub fn fe_case(&self) -> crate::study::records::case::FeCase {
        crate::study::records::case::FeCase {
            delta_history: self.history.iter().map(|r| [r.t, r.delta]).collect(),
            summary: crate::study::records::case::FeSummary {
                outcome: self.outcome,
                energy_error: self.energy_error,
                reduction: self.savings.reduction.name().into(),
                elements: self.elements,
                element_cycles: self.element_cycles,
                wall_time_s: self.wall_time_s,
                e_error: None,
                scaled_from: None,
            },
        }
    }
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
