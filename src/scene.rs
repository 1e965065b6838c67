//! A two-ball scene: what collides, how it is meshed, and how the FE run is set up.
//!
//! A scene is a TOML file (or the built-in default, the paper's Figure 8 case):
//! ```toml
//! [ball1]
//! material = "copper-fe"          # a preset, or { preset = "...", E = ..., yield = ... }
//! diameter = 0.02                 # m
//! velocity = [1.0, 0.0, 0.0]      # m/s; x = line of centres at first touch, y = tangential
//! [ball2]
//! material = "copper-fe"
//! diameter = 0.02
//! velocity = [-1.0, 0.0, 0.0]
//! ```
//! plus optional `angular_velocity`, `position`, `[ballN.mesh]`, `[contact]`, `[solver]`,
//! `[output]` and `[reduction]` tables (see [`Scene::from_toml`] and docs/design.md §6), and
//! a `[wall]` table in place of `[ball2]` for a ball against a rigid wall ([`WallScene`]).
//! `--set PATH=VALUE` overrides ([`Override`]) are applied to the TOML tree before it is read.

mod approach;
mod laws;
mod material_table;
mod overrides;
pub mod pole;
pub(crate) mod reader;
mod wall;

pub use approach::{approach, Approach, Frame, Touch};
pub use laws::{ComparedLaw, LawComparison};
pub use overrides::Override;
pub use wall::{WallKind, WallScene, DEFAULT_BLOCK_PER_D};

use crate::error::{Error, Result};
use crate::material::Material;
use material_table::{read_material, MATERIAL_KEYS};
use reader::{parse_table, Reader};
use serde::Serialize;
use std::path::{Path, PathBuf};
use toml::{Table, Value};
use wall::dot;

/// The built-in default scene: the paper's Figure 8 case (FE-study copper, D = 20 mm,
/// +1 and −1 m/s along the line of centres, no tangential speed).
pub const DEFAULT_SCENE: &str = r#"# The paper's Figure 8 case: two FE-study copper balls, D = 20 mm, +1 / -1 m/s head-on.
[ball1]
material = "copper-fe"
diameter = 0.02
velocity = [1.0, 0.0, 0.0]

[ball2]
material = "copper-fe"
diameter = 0.02
velocity = [-1.0, 0.0, 0.0]
"#;

/// A built-in wall scene: ball 1 of the default scene (FE-study copper, D = 20 mm, 1 m/s)
/// head-on against a rigid wall.
pub const WALL_SCENE: &str = r#"# Ball 1 of the paper's Figure 8 case, 1 m/s head-on against a rigid wall.
[ball1]
material = "copper-fe"
diameter = 0.02
velocity = [1.0, 0.0, 0.0]

[wall]
kind = "rigid"
"#;

/// How a ball is meshed.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum MeshSettings {
    /// The built-in graded ball mesher.
    Builtin {
        /// Element size in the bulk of the ball, m.
        size: f64,
        /// Element size at the contact pole, m (≤ `size`).
        pole_size: f64,
    },
    /// A gmsh `.msh` file (path resolved against the scene file's folder).
    File {
        /// Path of the mesh file.
        path: PathBuf,
    },
}

/// The ball diameters a scene (and `twoball analytic`) accepts, m.
pub const DIAMETER_RANGE: std::ops::RangeInclusive<f64> = 1e-4..=1.0;
/// The largest velocity component a scene (and `twoball analytic`) accepts, m/s.
pub const SPEED_MAX: f64 = 1000.0;

/// One ball of the scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BallScene {
    /// Its material, presets and overrides resolved.
    pub material: Material,
    /// The preset it started from, or `custom`.
    pub material_name: String,
    /// Diameter D, m.
    pub diameter: f64,
    /// Initial centre-of-mass velocity, m/s.
    pub velocity: [f64; 3],
    /// Initial angular velocity about the centre of mass, rad/s (the FE ball spins about its
    /// mesh's centre of mass, so its momentum is `velocity` alone).
    pub angular_velocity: [f64; 3],
    /// Initial centre position, m (`None`: placed touching the other ball along x).
    pub position: Option<[f64; 3]>,
    /// Mesh settings.
    pub mesh: MeshSettings,
}

/// Friction at the ball-ball contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Friction {
    /// Coulomb friction with the balls' coefficients (the mean of the two balls' μ_d and of
    /// their μ_s, as the analytical model's pair friction).
    On,
    /// Frictionless contact.
    Off,
    /// Coulomb friction with this one coefficient (μ_s = μ_d).
    Coefficient(f64),
}

/// Contact settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactSettings {
    /// Multiplier of the contact law's default penalty stiffness (1 = default).
    pub penalty_factor: f64,
    /// Friction model.
    pub friction: Friction,
    /// How the axisymmetric section enforces its rigid plane (the mirror plane of two equal
    /// balls, or a rigid wall); the 3D model always uses its penalty.
    pub plane: PlaneEnforcement,
}

/// How the section's rigid plane is enforced (`contact.plane`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum PlaneEnforcement {
    /// A unilateral kinematic constraint: no penalty compliance, no step limit of its own.
    #[default]
    Kinematic,
    /// The 3D model's penalty rule (FKN · E · A / h per node, times `penalty_factor`).
    Penalty,
}

pub use crate::fe::elements::ring::QuadFormulation;
pub use crate::fe::Formulation;

/// Explicit solver settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SolverSettings {
    /// Element formulation (of the 3D model; the section's counterpart unless
    /// `section_element` is set).
    pub element: Formulation,
    /// The section's ring element (`solver.section_element`, a name of
    /// [`QuadFormulation::NAMES`]); `None`: the counterpart of `element` (one point with
    /// hourglass control, or B-bar).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub section_element: Option<QuadFormulation>,
    /// Safety factor on the critical time step, in (0, 1].
    pub time_step_factor: f64,
    /// Fixed end time after touch, s; `None` = stop by the separation rule.
    pub end_time: Option<f64>,
    /// Separation rule: stop once the balls move apart and the contact force has stayed zero
    /// for this long, s; `None` = a tenth of the Hertz contact-duration estimate.
    pub hold_time: Option<f64>,
    /// Hard cap on the number of time steps.
    pub max_steps: u64,
    /// Multi-time-step integration (`auto`: on when the predicted saving is worth it).
    pub subcycling: crate::fe::subcycle::Subcycling,
    /// Mass-scaling budget of either model: the added mass over the model's mass that may
    /// raise its smallest elements' steps ([`crate::fe::mass_scaling`]; 0 ≤ budget ≤ 1e-2;
    /// default 0: none).
    #[serde(skip_serializing_if = "is_zero")]
    pub mass_scaling: f64,
}

/// True for 0 (a setting at its default is not written).
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// What to write besides results.json and history.csv.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OutputSettings {
    /// Interval between history rows, s; `None` = about 400 rows over the contact.
    pub history_interval: Option<f64>,
    /// Number of `.vtu` snapshots over the run (0 = none).
    pub vtu_snapshots: u32,
}

/// A switch for an automatic saving: decided per scene, or off.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Switch {
    /// Use it when the scene allows it.
    Auto,
    /// Never use it.
    Off,
}

/// Which model of the pair's symmetry to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Symmetry {
    /// The cheapest model the scene allows: the meridian section for a head-on impact of
    /// built-in meshes starting at first touch, else as [`Symmetry::Auto3d`].
    Auto,
    /// The cheapest exact 3D model the scene allows: the quarter or half model of identical
    /// balls (or the quarter ball on a wall), the full model else.
    Auto3d,
    /// The meridian section (a head-on impact only).
    Axisymmetric,
    /// A quarter of ball 1 against the frictionless symmetry plane (identical balls, head-on).
    Quarter,
    /// Both balls cut by the plane of the motion (identical balls, motion in one plane).
    Half,
    /// The full 3D model of both balls.
    Off,
}

impl Symmetry {
    /// `auto` as `auto-3d`, any other choice as it is: for the tools that time or study the
    /// 3D model (the benchmarks).
    pub fn three_d(self) -> Symmetry {
        match self {
            Symmetry::Auto => Symmetry::Auto3d,
            s => s,
        }
    }
}

/// The automatic savings (issue 6 item 3), each switchable off.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReductionSettings {
    /// Symmetry reduction: automatic, or a model forced (the meridian section, the quarter or
    /// half 3D model, or the full 3D model).
    pub symmetry: Symmetry,
    /// Start at first touch (free flight in closed form) instead of at the given positions.
    pub start_at_touch: Switch,
    /// Stop by the separation rule instead of at a fixed end time.
    pub stop_at_separation: Switch,
    /// Skip plasticity work where no element yields, friction work where μ = 0.
    pub skip_work: Switch,
}

/// A complete, validated scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scene {
    /// The left ball (moves towards +x).
    pub ball1: BallScene,
    /// The right ball; with a `[wall]`, ball 1's mirror image in the wall (never meshed).
    pub ball2: BallScene,
    /// The rigid wall ball 1 hits instead of a second ball (`[wall]`), if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall: Option<WallScene>,
    /// Contact settings.
    pub contact: ContactSettings,
    /// Solver settings.
    pub solver: SolverSettings,
    /// Output settings.
    pub output: OutputSettings,
    /// Automatic savings.
    pub reduction: ReductionSettings,
    /// Contact laws integrated beside FE and the three-phase model (`[laws]`).
    pub laws: LawComparison,
}

const TOP_KEYS: [&str; 8] = [
    "ball1",
    "ball2",
    "contact",
    "solver",
    "output",
    "reduction",
    "wall",
    "laws",
];
const BALL_KEYS: [&str; 6] = [
    "material",
    "diameter",
    "velocity",
    "angular_velocity",
    "position",
    "mesh",
];
const MESH_KEYS: [&str; 3] = ["size", "pole_size", "file"];
const CONTACT_KEYS: [&str; 3] = ["penalty_factor", "friction", "plane"];
const SOLVER_KEYS: [&str; 8] = [
    "element",
    "section_element",
    "time_step_factor",
    "end_time",
    "hold_time",
    "max_steps",
    "subcycling",
    "mass_scaling",
];
const OUTPUT_KEYS: [&str; 2] = ["history_interval", "vtu_snapshots"];
const REDUCTION_KEYS: [&str; 4] = [
    "symmetry",
    "start_at_touch",
    "stop_at_separation",
    "skip_work",
];

/// Every key of the scene reference (docs/design.md §6) as a dotted path, `ballN` for either
/// ball and a table such as `ballN.material.hardening` as one key: the list the check of
/// ignored settings ([`crate::study::run::ignored`]) must cover.
pub fn reference_keys() -> Vec<String> {
    let mut keys = Vec::new();
    let mut under = |prefix: &str, names: &[&str]| {
        keys.extend(names.iter().map(|k| format!("{prefix}.{k}")));
    };
    for k in BALL_KEYS {
        match k {
            "material" => under("ballN.material", &MATERIAL_KEYS),
            "mesh" => under("ballN.mesh", &MESH_KEYS),
            k => under("ballN", &[k]),
        }
    }
    under("contact", &CONTACT_KEYS);
    under("solver", &SOLVER_KEYS);
    under("output", &OUTPUT_KEYS);
    under("reduction", &REDUCTION_KEYS);
    under("wall", &wall::WALL_KEYS);
    under("laws", &laws::LAWS_KEYS);
    keys
}

/// Default bulk element size as a fraction of the diameter. With the default pole size, the
/// coarsest bulk that keeps the coefficient of restitution of the default scene within 1 %
/// of the converged value (0.7 %; D/5 is 1.9 % off): docs/performance.md, "Run time
/// against error".
pub const DEFAULT_SIZE_PER_D: f64 = 1.0 / 6.0;
/// Default pole element size as a fraction of the diameter: the contact patch (radius about
/// D/25 at 1 m/s per ball) is then about eight elements across; D/100 left e 2.5 % off.
/// Slower impacts refine it to their own contact radius ([`pole::physics_pole_size`]) unless
/// the scene sets `pole_size`.
pub const DEFAULT_POLE_SIZE_PER_D: f64 = 1.0 / 200.0;

impl Default for Scene {
    fn default() -> Self {
        Scene::from_toml(DEFAULT_SCENE, Path::new("."), &[]).expect("the built-in scene is valid")
    }
}

impl Scene {
    /// Reads a scene file and applies `--set` overrides. Mesh file paths are resolved
    /// against the scene file's folder.
    pub fn from_file(path: &Path, sets: &[Override]) -> Result<Scene> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let dir = path.parent().unwrap_or(Path::new("."));
        Self::parse(&text, &path.display().to_string(), dir, sets)
    }

    /// Reads scene text (origin `scene`); `dir` resolves relative mesh paths.
    pub fn from_toml(text: &str, dir: &Path, sets: &[Override]) -> Result<Scene> {
        Self::parse(text, "scene", dir, sets)
    }

    fn parse(text: &str, origin: &str, dir: &Path, sets: &[Override]) -> Result<Scene> {
        let mut root = parse_table(text, origin)?;
        for s in sets {
            s.apply(&mut root)?;
        }
        Self::from_table(&root, dir)
    }

    /// Reads a scene from a TOML table already parsed (and overridden).
    pub fn from_table(root: &Table, dir: &Path) -> Result<Scene> {
        let r = Reader::new("", root);
        r.only(&TOP_KEYS)?;
        let ball = |key: &str| -> Result<(BallScene, bool)> {
            let b = r
                .table(key)?
                .ok_or_else(|| r.missing(key, "a table with material, diameter, velocity"))?;
            read_ball(b, dir)
        };
        let (ball1, pole1_given) = ball("ball1")?;
        let wall = match r.table("wall")? {
            Some(w) => Some(wall::read_wall(w)?.with_block_size(ball1.diameter)?),
            None => None,
        };
        let (ball1, ball2, pole2_given) =
            match &wall {
                None => {
                    let (ball2, pole2_given) = ball("ball2")?;
                    (ball1, ball2, pole2_given)
                }
                Some(_) if r.raw("ball2").is_some() => return Err(Error::Parse(
                    "ball2 is given with [wall]: a wall scene has one ball (remove one of them)"
                        .into(),
                )),
                Some(w) => {
                    w.check_block_reach(ball1.material, ball1.diameter, ball1.velocity)?;
                    let ball1 = place_against(w, ball1)?;
                    let image = wall_image(w, &ball1);
                    (ball1, image, pole1_given)
                }
            };
        let contact = read_contact(r.table("contact")?)?;
        let solver = read_solver(r.table("solver")?)?;
        let output = read_output(r.table("output")?)?;
        let reduction = read_reduction(r.table("reduction")?)?;
        let laws = laws::read_laws(r.table("laws")?)?;
        if ball1.position.is_some() != ball2.position.is_some() {
            let which = if ball1.position.is_some() {
                "ball2.position"
            } else {
                "ball1.position"
            };
            return Err(Error::Parse(format!(
                "missing required key {which}: give both balls a position or neither"
            )));
        }
        let mut scene = Scene {
            ball1,
            ball2,
            wall,
            contact,
            solver,
            output,
            reduction,
            laws,
        };
        // Rejects overlapping balls; an impact refines the default pole mesh to its contact.
        if let Approach::Impact(touch) = approach(&scene)? {
            scene.refine_poles(touch.approach_speed, [!pole1_given, !pole2_given]);
        }
        Ok(scene)
    }

    /// Applies the physics pole rule ([`pole::physics_pole_size`]) at relative approach speed
    /// `speed` (m/s) to the built-in meshes of the balls flagged in `default_pole` (those whose
    /// scene left `pole_size` unset); it only ever refines.
    fn refine_poles(&mut self, speed: f64, default_pole: [bool; 2]) {
        let rule = [
            pole::physics_pole_size(&self.ball1, &self.ball2, speed),
            pole::physics_pole_size(&self.ball2, &self.ball1, speed),
        ];
        for (k, ball) in [&mut self.ball1, &mut self.ball2].into_iter().enumerate() {
            if let (true, MeshSettings::Builtin { pole_size, .. }) =
                (default_pole[k], &mut ball.mesh)
            {
                *pole_size = pole_size.min(rule[k]);
            }
        }
    }

    /// Initial centre positions (m): as given, or touching at the origin along x.
    pub fn centres(&self) -> ([f64; 3], [f64; 3]) {
        match (self.ball1.position, self.ball2.position) {
            (Some(a), Some(b)) => (a, b),
            _ => (
                [-self.ball1.diameter / 2.0, 0.0, 0.0],
                [self.ball2.diameter / 2.0, 0.0, 0.0],
            ),
        }
    }

    /// The friction coefficients (μ_d, μ_s) of the contact pair.
    pub fn friction_coefficients(&self) -> (f64, f64) {
        match self.contact.friction {
            Friction::Off => (0.0, 0.0),
            Friction::Coefficient(mu) => (mu, mu),
            Friction::On => {
                let (a, b) = (&self.ball1.material, &self.ball2.material);
                (0.5 * (a.mu + b.mu), 0.5 * (a.mu_static + b.mu_static))
            }
        }
    }

    /// True when both balls have the same material, diameter and mesh (symmetry needs it).
    pub fn identical_balls(&self) -> bool {
        self.ball1.material == self.ball2.material
            && self.ball1.diameter == self.ball2.diameter
            && self.ball1.mesh == self.ball2.mesh
    }
}

/// A ball and whether its scene set `mesh.pole_size` (else the physics rule may refine it).
fn read_ball(b: Reader<'_>, dir: &Path) -> Result<(BallScene, bool)> {
    b.only(&BALL_KEYS)?;
    let (material, material_name) = read_material(&b)?;
    let diameter = b
        .f64(
            "diameter",
            |d| DIAMETER_RANGE.contains(&d),
            "1e-4 <= diameter <= 1 m",
        )?
        .ok_or_else(|| b.missing("diameter", "ball diameter in m"))?;
    let speed_ok = |v: f64| v.abs() <= SPEED_MAX;
    let velocity = b
        .vec3("velocity", speed_ok, "|component| <= 1000 m/s")?
        .ok_or_else(|| b.missing("velocity", "[vx, vy, vz] in m/s"))?;
    let angular_velocity = b
        .vec3(
            "angular_velocity",
            |w| w.abs() <= 1e5,
            "|component| <= 1e5 rad/s",
        )?
        .unwrap_or([0.0; 3]);
    let position = b.vec3("position", |x| x.abs() <= 1e3, "|component| <= 1000 m")?;
    let (mesh, pole_given) = read_mesh(b.table("mesh")?, diameter, dir)?;
    let ball = BallScene {
        material,
        material_name,
        diameter,
        velocity,
        angular_velocity,
        position,
        mesh,
    };
    Ok((ball, pole_given))
}

/// The mesh settings and whether `pole_size` was given.
fn read_mesh(m: Option<Reader<'_>>, d: f64, dir: &Path) -> Result<(MeshSettings, bool)> {
    let default = MeshSettings::Builtin {
        size: d * DEFAULT_SIZE_PER_D,
        pole_size: d * DEFAULT_POLE_SIZE_PER_D,
    };
    let Some(m) = m else {
        return Ok((default, false));
    };
    m.only(&MESH_KEYS)?;
    let file = m.string("file")?;
    let size = m.f64(
        "size",
        |s| s > 0.0 && s <= d / 2.0,
        "0 < size <= radius (m)",
    )?;
    let lo = d / 2000.0;
    let pole_allowed = format!("{lo:.3e} m (diameter/2000) <= pole_size <= size");
    let pole = m.f64("pole_size", |s| s >= lo, &pole_allowed)?;
    let mesh = match file {
        Some(f) => {
            if size.is_some() || pole.is_some() {
                return Err(Error::Parse(format!(
                    "{} is given with {}: a mesh file has its own sizes, give one or the other",
                    m.key_path("file"),
                    m.key_path(if size.is_some() { "size" } else { "pole_size" })
                )));
            }
            let p = dir.join(f);
            if !p.is_file() {
                return Err(Error::invalid(
                    m.key_path("file"),
                    format!("\"{f}\""),
                    "an existing gmsh .msh file",
                ));
            }
            MeshSettings::File { path: p }
        }
        None => {
            let size = size.unwrap_or(d * DEFAULT_SIZE_PER_D);
            let pole_size = pole.unwrap_or((d * DEFAULT_POLE_SIZE_PER_D).min(size));
            if pole_size > size {
                return Err(Error::invalid(
                    m.key_path("pole_size"),
                    pole_size,
                    pole_allowed,
                ));
            }
            MeshSettings::Builtin { size, pole_size }
        }
    };
    Ok((mesh, pole.is_some()))
}

impl Default for ContactSettings {
    /// The settings of a scene without `[contact]`.
    fn default() -> Self {
        ContactSettings {
            penalty_factor: 1.0,
            friction: Friction::On,
            plane: PlaneEnforcement::Kinematic,
        }
    }
}

fn read_contact(c: Option<Reader<'_>>) -> Result<ContactSettings> {
    let mut out = ContactSettings::default();
    let Some(c) = c else { return Ok(out) };
    c.only(&CONTACT_KEYS)?;
    if let Some(p) = c.choice("plane", &["kinematic", "penalty"])? {
        out.plane = match p {
            "kinematic" => PlaneEnforcement::Kinematic,
            _ => PlaneEnforcement::Penalty,
        };
    }
    if let Some(p) = c.f64(
        "penalty_factor",
        |p| (1e-3..=1e3).contains(&p),
        "1e-3 <= penalty_factor <= 1e3",
    )? {
        out.penalty_factor = p;
    }
    out.friction = match c.raw("friction") {
        None => Friction::On,
        Some(Value::String(s)) if s == "on" => Friction::On,
        Some(Value::String(s)) if s == "off" => Friction::Off,
        Some(Value::Boolean(b)) => {
            if *b {
                Friction::On
            } else {
                Friction::Off
            }
        }
        Some(Value::Float(_) | Value::Integer(_)) => {
            let mu = c.f64(
                "friction",
                |m| (0.0..=5.0).contains(&m),
                "\"on\", \"off\" or 0 <= mu <= 5",
            )?;
            Friction::Coefficient(mu.unwrap_or(0.0))
        }
        Some(other) => {
            return Err(Error::invalid(
                c.key_path("friction"),
                reader::show(other),
                "\"on\", \"off\" or 0 <= mu <= 5",
            ))
        }
    };
    Ok(out)
}

fn read_solver(s: Option<Reader<'_>>) -> Result<SolverSettings> {
    let mut out = SolverSettings {
        element: Formulation::OnePoint,
        section_element: None,
        time_step_factor: 0.9,
        end_time: None,
        hold_time: None,
        max_steps: 2_000_000,
        subcycling: crate::fe::subcycle::Subcycling::Auto,
        mass_scaling: 0.0,
    };
    let Some(s) = s else { return Ok(out) };
    s.only(&SOLVER_KEYS)?;
    if let Some(e) = s.choice("element", &Formulation::NAMES)? {
        out.element = Formulation::from_name(e).expect("a choice of Formulation::NAMES");
    }
    if let Some(e) = s.choice("section_element", &QuadFormulation::NAMES)? {
        out.section_element = QuadFormulation::from_name(e);
    }
    if let Some(f) = s.f64(
        "time_step_factor",
        |f| f > 0.0 && f <= 1.0,
        "0 < time_step_factor <= 1",
    )? {
        out.time_step_factor = f;
    }
    out.end_time = s.f64("end_time", |t| t > 0.0 && t <= 1.0, "0 < end_time <= 1 s")?;
    out.hold_time = s.f64("hold_time", |t| t > 0.0 && t <= 1.0, "0 < hold_time <= 1 s")?;
    if let Some(n) = s.u64(
        "max_steps",
        |n| (1..=100_000_000).contains(&n),
        "1 <= max_steps <= 1e8",
    )? {
        out.max_steps = n;
    }
    if let Some(c) = s.choice("subcycling", &["auto", "on", "off"])? {
        use crate::fe::subcycle::Subcycling;
        out.subcycling = match c {
            "auto" => Subcycling::Auto,
            "on" => Subcycling::On,
            _ => Subcycling::Off,
        };
    }
    let budget = crate::fe::mass_scaling::MAX_BUDGET;
    if let Some(b) = s.f64(
        "mass_scaling",
        |b| (0.0..=budget).contains(&b),
        "0 <= mass_scaling <= 0.01 (added mass over the model's)",
    )? {
        out.mass_scaling = b;
    }
    Ok(out)
}

fn read_output(o: Option<Reader<'_>>) -> Result<OutputSettings> {
    let mut out = OutputSettings {
        history_interval: None,
        vtu_snapshots: 0,
    };
    let Some(o) = o else { return Ok(out) };
    o.only(&OUTPUT_KEYS)?;
    out.history_interval = o.f64(
        "history_interval",
        |t| t > 0.0 && t <= 1.0,
        "0 < history_interval <= 1 s",
    )?;
    if let Some(n) = o.u64(
        "vtu_snapshots",
        |n| n <= 1000,
        "0 <= vtu_snapshots <= 1000 (written with `twoball run --out DIR`)",
    )? {
        out.vtu_snapshots = n as u32;
    }
    Ok(out)
}

fn read_reduction(r: Option<Reader<'_>>) -> Result<ReductionSettings> {
    let mut out = ReductionSettings {
        symmetry: Symmetry::Auto,
        start_at_touch: Switch::Auto,
        stop_at_separation: Switch::Auto,
        skip_work: Switch::Auto,
    };
    let Some(r) = r else { return Ok(out) };
    r.only(&REDUCTION_KEYS)?;
    let read = |key: &str| -> Result<Option<Switch>> {
        Ok(r.choice(key, &["auto", "off"])?.map(|s| {
            if s == "auto" {
                Switch::Auto
            } else {
                Switch::Off
            }
        }))
    };
    let symmetries = ["auto", "auto-3d", "axisymmetric", "quarter", "half", "off"];
    if let Some(s) = r.choice("symmetry", &symmetries)? {
        out.symmetry = match s {
            "auto-3d" => Symmetry::Auto3d,
            "axisymmetric" => Symmetry::Axisymmetric,
            "quarter" => Symmetry::Quarter,
            "half" => Symmetry::Half,
            "off" => Symmetry::Off,
            _ => Symmetry::Auto,
        };
    }
    if let Some(s) = read("start_at_touch")? {
        out.start_at_touch = s;
    }
    if let Some(s) = read("stop_at_separation")? {
        out.stop_at_separation = s;
    }
    if let Some(s) = read("skip_work")? {
        out.skip_work = s;
    }
    Ok(out)
}

/// Checks ball 1 against the wall and places it: its centre as given, or touching the
/// wall's face at `position`. Returns ball 1 with its position set.
///
/// Errors (one line, naming the field): ball 1 behind or through the wall, or not moving
/// towards it.
fn place_against(wall: &WallScene, mut ball1: BallScene) -> Result<BallScene> {
    let r = ball1.diameter / 2.0;
    let centre = ball1
        .position
        .unwrap_or([0, 1, 2].map(|k| wall.position[k] + r * wall.normal[k]));
    let s = wall.distance(centre);
    if s < r * (1.0 - 1e-9) {
        return Err(Error::invalid(
            "ball1.position",
            format!("{centre:?} ({s:.6e} m in front of the wall)"),
            format!("a centre at least the radius {r:.6e} m in front of the wall's face"),
        ));
    }
    let v = ball1.velocity;
    let vn = dot(v, wall.normal);
    if vn >= 0.0 {
        return Err(Error::invalid(
            "ball1.velocity",
            format!("{v:?}"),
            "towards the wall (velocity · wall.normal < 0)",
        ));
    }
    ball1.position = Some(centre);
    Ok(ball1)
}

/// Ball 1's mirror image in the wall: same material, size and mesh, mirrored centre and
/// velocity, no spin (`ball1` placed by [`place_against`]).
fn wall_image(wall: &WallScene, ball1: &BallScene) -> BallScene {
    let mut b = ball1.clone();
    b.position = ball1.position.map(|p| wall.mirror_point(p));
    b.velocity = wall.mirror_vector(ball1.velocity);
    b.angular_velocity = [0.0; 3];
    b
}
