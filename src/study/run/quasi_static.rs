//! The quasi-static loading-unloading loop of one ball on a rigid frictionless plane, on one
//! mesh: the F(δ) curve contact laws are fitted to, by the static implicit solver
//! ([`crate::fe::implicit`]).
//!
//! Two ways to hold the ball, which give different δ at equal force (the far field of a
//! held hemisphere cannot move):
//! - [`Support::Held`]: the hemisphere above its equator, the equator on a roller pushed
//!   towards the plane; δ is the equator's travel (CalculiX's `--support held`);
//! - [`Support::Free`]: the whole ball under the uniform body force that balances the
//!   contact; δ is the approach of the centre of mass (the static image of an impact whose
//!   pulse is long against the ball's vibration; `--support free`).
//!
//! Loading runs to a prescribed approach, force or stored work (the last increment solved
//! again until it meets the target to 1e-6), unloading to zero force in steps sized by Hertz's
//! unloading law through the peak, the release extrapolated along F ∝ (δ − δ_res)^{3/2}
//! through the last two points (near 1 % of the peak; a free body has no support at zero
//! force).

use crate::analytic::hertz::HertzPair;
use crate::error::{Error, Result};
use crate::fe::elements::ring::mass::element_masses;
use crate::fe::elements::ring::QuadFormulation;
use crate::fe::implicit::contact_edge::{contact_edge, GapPoint};
use crate::fe::implicit::plane::ExactPlane;
use crate::fe::implicit::static_solver::{Prescribed, Settings, StaticSolver, Target};
use crate::fe::materials::J2Material;
use crate::fe::section::solver::SectionModel;
use crate::material::Material;
use crate::mesh::section::{ball, ladder_ball, ladder_ball_banded, EdgeBand, SectionSpec};
use serde::{Deserialize, Serialize};

/// How the ball is held against the plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Support {
    /// The hemisphere, its equator on a roller driven towards the plane.
    Held,
    /// The whole ball under the body force that balances the contact.
    Free,
}

impl Support {
    /// The names `--support` takes.
    pub const NAMES: [&'static str; 2] = ["held", "free"];

    /// The support named `name`.
    pub fn from_name(name: &str) -> Option<Support> {
        match name {
            "held" => Some(Support::Held),
            "free" => Some(Support::Free),
            _ => None,
        }
    }
}

/// Where loading stops.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "to", content = "value")]
pub enum LoadTo {
    /// An approach δ_max, m.
    Approach(f64),
    /// A contact force, N.
    Force(f64),
    /// A stored work ∫F dδ (the kinetic energy one ball brings to the plane), J.
    Work(f64),
}

/// The section mesh of a loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LoopMesh {
    /// The static ladder's mesh at the case's level (`mesh::section::ladder_ball`), sized
    /// from an estimate of the largest contact radius, m.
    Ladder {
        /// Contact radius the mesh is sized from, m.
        sizing_radius: f64,
    },
    /// The static ladder's mesh with an edge band of finer surface rings at the contact
    /// edge (`mesh::section::ladder_ball_banded`), which shrinks the sawtooth of the plastic
    /// e over the ring spacing.
    Banded {
        /// Contact radius the mesh is sized from, m.
        sizing_radius: f64,
        /// The band.
        band: EdgeBand,
    },
    /// A scene's built-in section mesh (`mesh::section::ball`; [`super::section::section_spec`]),
    /// the mesh of its dynamic run on the meridian section; the case's level sets only the
    /// increments.
    Builtin(SectionSpec),
}

/// One loop's case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticCase {
    /// Ball diameter, m.
    pub diameter: f64,
    /// Ball material.
    pub material: Material,
    /// Ring element.
    pub formulation: QuadFormulation,
    /// How the ball is held.
    pub support: Support,
    /// Where loading stops.
    pub to: LoadTo,
    /// The mesh the loop runs on.
    pub mesh: LoopMesh,
    /// Ladder level: of the mesh (with [`LoopMesh::Ladder`] or [`LoopMesh::Banded`]) and of
    /// the increments ([`StaticCase::steps`]).
    pub level: u32,
    /// Increments of loading (and as many of unloading) at level 0, ≥ 4; each level
    /// doubles them ([`StaticCase::steps`]), so that a ladder refines the load path with the
    /// mesh (the return mapping's straight strain path per increment is an error of the
    /// loop, of order one in the increment).
    pub increments: usize,
}

impl StaticCase {
    /// Increments of loading on this case's level: `increments` · 2^level.
    pub fn steps(&self) -> usize {
        self.increments << self.level
    }

    /// Increments of unloading on this case's level: half the loading's (at least 4).
    /// Unloading is elastic but for a thin rim of reversed yield, so the straight strain
    /// path of an increment costs it little: on the default held loop, halving them moves
    /// e by 4e-6 relative and saves 8 % of the Newton iterations.
    pub fn unloading_steps(&self) -> usize {
        (self.steps() / 2).max(4)
    }

    /// The ball's mass ρ π D³ / 6, kg.
    pub fn ball_mass(&self) -> f64 {
        self.material.rho * std::f64::consts::PI * self.diameter.powi(3) / 6.0
    }
}

/// One point of a loop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LoopPoint {
    /// Approach δ, m.
    pub approach: f64,
    /// Contact force, N.
    pub force: f64,
    /// Contact radius, m: where the surface leaves the plane, between the outermost node on
    /// it and the next ([`contact_edge`]).
    pub contact_radius: f64,
    /// Plastic work, J.
    pub plastic_work: f64,
    /// Work of the internal forces (stress work ∫σ:dε dV, elastic + plastic, and the
    /// hourglass control's), J.
    pub stress_work: f64,
}

/// What a loop gives.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LoopSummary {
    /// Largest approach, m.
    pub delta_max: f64,
    /// Contact force at δ_max / 2 on loading, N.
    pub force_at_half: f64,
    /// Contact force at δ_max, N.
    pub force_at_max: f64,
    /// Approach left after unloading, m.
    pub residual_approach: f64,
    /// Work put in on loading, J.
    pub work_in: f64,
    /// Work returned on unloading, J.
    pub work_returned: f64,
    /// √(work returned / work in), the quasi-static coefficient of restitution.
    pub e: f64,
    /// Contact radius at δ_max, m.
    pub contact_radius: f64,
    /// Plastic work at the end, J.
    pub plastic_work: f64,
}

/// A loop on one mesh.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StaticLoop {
    /// Quads of the mesh.
    pub quads: usize,
    /// Newton iterations over the loop (of the increments kept).
    pub iterations: usize,
    /// Tangent factorisations over the loop, every attempt included.
    pub factorisations: u64,
    /// Relative residual norms before each Newton iteration of the increment that reached
    /// the peak (the rate of convergence near the solution shows in them).
    pub peak_residuals: Vec<f64>,
    /// Loading points, from touch to δ_max.
    pub loading: Vec<LoopPoint>,
    /// Unloading points, from δ_max to release.
    pub unloading: Vec<LoopPoint>,
    /// The loop's numbers.
    pub summary: LoopSummary,
}

/// The ball's section and how to drive and measure it.
struct Rig {
    solver: StaticSolver,
    support: Support,
    /// The driven nodes: the equator (held), whose travel is prescribed, or the back pole
    /// (free), whose travel sets the body force (load control).
    driven: Vec<u32>,
    /// Nodal masses (free), kg.
    mass: Vec<f64>,
    /// The nodes on the ball's spherical surface facing the plane (z > 0 at rest).
    surface: Vec<u32>,
    iterations: usize,
    /// The relative residuals of the last increment driven.
    residuals: Vec<f64>,
}

impl Rig {
    fn new(case: &StaticCase) -> Result<Rig> {
        let radius = case.diameter / 2.0;
        let mesh = match case.mesh {
            LoopMesh::Ladder { sizing_radius } => {
                ladder_ball(case.diameter, sizing_radius, case.level)?
            }
            LoopMesh::Banded {
                sizing_radius,
                band,
            } => ladder_ball_banded(case.diameter, sizing_radius, case.level, &band)?,
            LoopMesh::Builtin(spec) => ball(&spec)?,
        };
        let (nodes, quads) = match case.support {
            Support::Free => (mesh.nodes, mesh.quads),
            Support::Held => upper_half(&mesh.nodes, &mesh.quads),
        };
        let mut mass = vec![0.0; nodes.len()];
        for q in &quads {
            let m = element_masses(&q.map(|i| nodes[i as usize]), case.material.rho);
            for (k, &i) in q.iter().enumerate() {
                mass[i as usize] += m[k];
            }
        }
        let total: f64 = mass.iter().sum();
        let mut model =
            SectionModel::new(nodes.clone(), quads, J2Material::new(&case.material, false));
        model.formulation = case.formulation;
        let driven = match case.support {
            // One newton of body force towards the plane above the ball.
            Support::Free => {
                for (l, m) in model.loads.iter_mut().zip(&mass) {
                    *l = [0.0, m / total];
                }
                let back = (0..nodes.len() as u32)
                    .filter(|&i| nodes[i as usize][0] == 0.0)
                    .min_by(|&a, &b| nodes[a as usize][1].total_cmp(&nodes[b as usize][1]));
                back.into_iter().collect()
            }
            Support::Held => (0..nodes.len() as u32)
                .filter(|&i| nodes[i as usize][1] == 0.0)
                .collect(),
        };
        let plane = ExactPlane {
            z: radius,
            side: -1.0,
        };
        let surface = (0..nodes.len() as u32)
            .filter(|&i| {
                let [r, z] = nodes[i as usize];
                z > 0.0 && r.hypot(z) >= radius * (1.0 - 1e-9)
            })
            .collect();
        Ok(Rig {
            solver: StaticSolver::new(model, Some(plane), Settings::default())?,
            support: case.support,
            driven,
            mass,
            surface,
            iterations: 0,
            residuals: Vec::new(),
        })
    }

    /// Drives the ball to control value `c`, the driven nodes' travel towards the plane (m):
    /// held, the equator's; free, the back pole's, with the body force (N) as the unknown
    /// that brings it there.
    fn drive(&mut self, c: f64) -> Result<()> {
        let travel = |&node: &u32| Prescribed {
            node,
            dir: 1,
            displacement: c,
        };
        let target = match self.support {
            Support::Held => Target {
                prescribed: self.driven.iter().map(travel).collect(),
                ..Default::default()
            },
            Support::Free => Target {
                load_control: self.driven.first().map(travel),
                ..Default::default()
            },
        };
        let done = self.solver.solve(&target)?;
        self.iterations += done.iterations;
        self.residuals = done.residuals;
        Ok(())
    }

    /// The driven nodes' travel towards the plane now (m), the value [`Rig::drive`] sets.
    fn control(&self) -> f64 {
        let s = &self.solver;
        let i = self.driven[0] as usize;
        s.positions()[i][1] - s.initial_positions()[i][1]
    }

    /// The current point of the loop.
    fn point(&self) -> LoopPoint {
        let s = &self.solver;
        let approach = match self.support {
            Support::Held => self.control(),
            Support::Free => {
                let (mut m, mut mz) = (0.0, 0.0);
                for ((mi, x), x0) in self
                    .mass
                    .iter()
                    .zip(s.positions())
                    .zip(s.initial_positions())
                {
                    m += mi;
                    mz += mi * (x[1] - x0[1]);
                }
                mz / m
            }
        };
        LoopPoint {
            approach,
            force: s.contact_force(),
            contact_radius: self.contact_edge(),
            plastic_work: s.plastic_work(),
            stress_work: s.internal_work(),
        }
    }

    /// The contact radius (m): the radius where the surface leaves the plane, from the
    /// outermost surface node on it and the gaps of the next three ([`contact_edge`]); the
    /// outermost node's radius when fewer than three surface nodes lie beyond it; 0 out of
    /// contact.
    fn contact_edge(&self) -> f64 {
        let s = &self.solver;
        let (Some(plane), x) = (s.plane(), s.positions()) else {
            return 0.0;
        };
        if !s.active().contains(&true) {
            return 0.0;
        }
        let r_on = s.contact_radius();
        let mut past: Vec<GapPoint> = self
            .surface
            .iter()
            .map(|&i| GapPoint {
                r: x[i as usize][0],
                g: plane.gap(x[i as usize][1]),
            })
            .filter(|p| p.r > r_on)
            .collect();
        past.sort_by(|a, b| a.r.total_cmp(&b.r));
        match past[..] {
            [p1, p2, p3, ..] => contact_edge(r_on, [p1, p2, p3]),
            _ => r_on,
        }
    }
}

/// The quads of the upper half z ≥ 0 of a section with its nodes renumbered.
fn upper_half(nodes: &[[f64; 2]], quads: &[[u32; 4]]) -> (Vec<[f64; 2]>, Vec<[u32; 4]>) {
    let keep: Vec<[u32; 4]> = quads
        .iter()
        .filter(|q| q.iter().all(|&i| nodes[i as usize][1] >= 0.0))
        .copied()
        .collect();
    let mut new_of = vec![u32::MAX; nodes.len()];
    let mut out = Vec::new();
    for q in &keep {
        for &i in q {
            if new_of[i as usize] == u32::MAX {
                new_of[i as usize] = out.len() as u32;
                out.push(nodes[i as usize]);
            }
        }
    }
    let quads = keep.iter().map(|q| q.map(|i| new_of[i as usize])).collect();
    (out, quads)
}

/// The loaded quantity a target names, of `p`.
fn measure(to: LoadTo, p: &LoopPoint) -> (f64, f64) {
    match to {
        LoadTo::Approach(v) => (p.approach, v),
        LoadTo::Force(v) => (p.force, v),
        LoadTo::Work(v) => (p.stress_work, v),
    }
}

/// An estimate of the control value (the driven nodes' travel, m) that meets `to`, from
/// Hertz's elastic law of the ball on a rigid plane.
fn control_estimate(case: &StaticCase) -> f64 {
    let modulus = case.material.plane_strain_modulus();
    let hertz = HertzPair::new(modulus, case.diameter / 2.0, case.ball_mass());
    let k = hertz.stiffness();
    match case.to {
        LoadTo::Approach(d) => d,
        LoadTo::Force(f) => (f / k).powf(2.0 / 3.0),
        LoadTo::Work(w) => (2.5 * w / k).powf(0.4),
    }
}

/// The most increments at level 0.
const MAX_INCREMENTS: usize = 10_000;

/// Checks a case's numbers.
fn check(case: &StaticCase) -> Result<()> {
    let (name, v) = match case.to {
        LoadTo::Approach(v) => ("static.approach", v),
        LoadTo::Force(v) => ("static.force", v),
        LoadTo::Work(v) => ("static.work", v),
    };
    if !(v.is_finite() && v > 0.0) {
        return Err(Error::invalid(name, v, "> 0, finite"));
    }
    if !(4..=MAX_INCREMENTS).contains(&case.increments) {
        return Err(Error::invalid(
            "static.increments",
            case.increments,
            format!("4 to {MAX_INCREMENTS}"),
        ));
    }
    Ok(())
}

/// Runs the loop of `case`: loading to its target, unloading to release.
///
/// Errors: a bad case, a mesh out of range, a static solve that does not converge.
pub fn run_loop(case: &StaticCase) -> Result<StaticLoop> {
    let (mut rig, loading) = load_to_target(case)?;
    let peak = *loading.last().expect("the peak");
    let peak_residuals = rig.residuals.clone();
    let c_peak = rig.control();
    let unloading = unload(&mut rig, case, c_peak, peak)?;
    let end = *unloading.last().expect("the release");
    let work_in = peak.stress_work;
    let work_returned = peak.stress_work - end.stress_work;
    let e = (work_returned / work_in).sqrt();
    if !e.is_finite() {
        return Err(Error::Numerical(format!(
            "static loop: work returned {work_returned:.4e} J of {work_in:.4e} J in gives no e"
        )));
    }
    let summary = LoopSummary {
        delta_max: peak.approach,
        force_at_half: interpolate(&loading, 0.5 * peak.approach),
        force_at_max: peak.force,
        residual_approach: end.approach,
        work_in,
        work_returned,
        e,
        contact_radius: peak.contact_radius,
        plastic_work: end.plastic_work,
    };
    Ok(StaticLoop {
        quads: rig.solver.states().len(),
        iterations: rig.iterations,
        peak_residuals,
        factorisations: rig.solver.factorisations(),
        loading,
        unloading,
        summary,
    })
}

/// The loading half of a loop: where it met its target and what that cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadedPeak {
    /// The point where loading met its target.
    pub point: LoopPoint,
    /// The radius of the outermost node on the plane there, m.
    pub outermost_ring: f64,
    /// Quads of the mesh.
    pub quads: usize,
    /// Newton iterations of the loading (of the increments kept).
    pub iterations: usize,
}

/// The loading half of the loop of `case`, which alone fixes its peak (δ_max, contact
/// radius): the unloading's cost saved where only the peak is wanted.
///
/// Errors: as [`run_loop`].
pub fn peak_of(case: &StaticCase) -> Result<LoadedPeak> {
    let (rig, loading) = load_to_target(case)?;
    Ok(LoadedPeak {
        point: *loading.last().expect("the peak"),
        outermost_ring: rig.solver.contact_radius(),
        quads: rig.solver.states().len(),
        iterations: rig.iterations,
    })
}

/// The rig of `case` loaded to its target, and its loading points from touch.
///
/// The loading takes about `increments` steps of the control towards Hertz's estimate; a
/// ball that meets its target within the first quarter of them (much softer than Hertz)
/// starts again with the estimate scaled to where the target was met.
fn load_to_target(case: &StaticCase) -> Result<(Rig, Vec<LoopPoint>)> {
    check(case)?;
    let mut c_est = control_estimate(case);
    loop {
        let mut rig = Rig::new(case)?;
        let loading = load(&mut rig, case, c_est)?;
        let steps = loading.len() - 1;
        if 4 * steps >= case.steps() {
            return Ok((rig, loading));
        }
        c_est *= steps as f64 / case.steps() as f64;
    }
}

/// Loads in equal steps of the driven nodes' travel, about `c_est` / increments each, until
/// the target is met, the last step solved again (Illinois regula falsi from the state
/// before it) until it meets the target to 1e-6; returns the points from touch to the
/// target.
fn load(rig: &mut Rig, case: &StaticCase, c_est: f64) -> Result<Vec<LoopPoint>> {
    let n = case.steps();
    let control = |k: usize| c_est * k as f64 / n as f64;
    let mut loading = vec![rig.point()];
    for k in 1..=40 * n {
        let before = rig.solver.clone();
        let p0 = *loading.last().expect("a first point");
        rig.drive(control(k))?;
        let p1 = rig.point();
        let (q1, goal) = measure(case.to, &p1);
        if q1 < goal {
            loading.push(p1);
            continue;
        }
        let (mut lo, mut hi) = ((control(k - 1), measure(case.to, &p0).0), (control(k), q1));
        let mut side = 0i8;
        let mut last = p1;
        for _ in 0..40 {
            if (measure(case.to, &last).0 - goal).abs() <= 1e-6 * goal {
                loading.push(last);
                return Ok(loading);
            }
            let c = lo.0 + (goal - lo.1) * (hi.0 - lo.0) / (hi.1 - lo.1);
            rig.solver = before.clone();
            rig.drive(c)?;
            last = rig.point();
            let q = measure(case.to, &last).0;
            // Illinois: halve the stale end's offset when the same end moves twice.
            if q < goal {
                if side == -1 {
                    hi.1 = goal + 0.5 * (hi.1 - goal);
                }
                (lo, side) = ((c, q), -1);
            } else {
                if side == 1 {
                    lo.1 = goal - 0.5 * (goal - lo.1);
                }
                (hi, side) = ((c, q), 1);
            }
        }
        return Err(Error::Numerical(format!(
            "static loop: the last loading increment did not meet the target {goal:.6e} to 1e-6"
        )));
    }
    Err(Error::Numerical(format!(
        "static loop: the target not reached after {} increments",
        40 * n
    )))
}

/// Unloads from the peak (control `c_peak`) to release; the last point has zero force.
///
/// Steps of the driven nodes' travel go towards the point where Hertz's unloading law through
/// the peak, F = F_p ((δ − δ_r) / (δ_p − δ_r))^{3/2}, falls to [`RELEASE_FORCE`] of the peak
/// (the recovery δ_p − δ_r = 3 F_p / 2k from the slope k of a probe step), and the release
/// is extrapolated along that law through the last two points. A step that lets go is halved
/// (up to [`RELEASE_CUTS`] times), so the points crowd towards the release; below a tenth of
/// the peak force a step that fails (a free ball the plane all but lets go of) ends the
/// unloading there.
fn unload(
    rig: &mut Rig,
    case: &StaticCase,
    c_peak: f64,
    peak: LoopPoint,
) -> Result<Vec<LoopPoint>> {
    let n = case.unloading_steps();
    let mut points = vec![peak];
    let share = 1.0 - RELEASE_FORCE.powf(2.0 / 3.0);
    let probe = PROBE * c_peak;
    let before = rig.solver.clone();
    rig.drive(c_peak - probe)?;
    let slope = (peak.force - rig.point().force) / probe;
    rig.solver = before;
    if !(slope > 0.0 && slope.is_finite()) {
        return Err(Error::Numerical(format!(
            "static loop: the force does not fall on unloading (slope {slope:.3e} N/m)"
        )));
    }
    let end = c_peak - share * 1.5 * peak.force / slope;
    let mut step = (c_peak - end) / n as f64;
    let (mut c, mut cuts) = (c_peak, 0);
    while c - end > 1e-6 * step {
        let next = (c - step).max(end);
        let before = rig.solver.clone();
        let held = match rig.drive(next) {
            Ok(()) => rig.point().force > 0.0,
            // Near the release a free ball the plane all but lets go of is ill-conditioned:
            // the release is extrapolated from the points so far.
            Err(_) if points[points.len() - 1].force < RELEASE_ZONE * peak.force => {
                rig.solver = before;
                break;
            }
            Err(e) => return Err(e),
        };
        if held {
            points.push(rig.point());
            c = next;
            continue;
        }
        rig.solver = before;
        if cuts == RELEASE_CUTS {
            break;
        }
        cuts += 1;
        step *= 0.5;
    }
    let release = release_point(&points)?;
    points.push(release);
    Ok(points)
}

/// The release after the last two unloading points, along F ∝ (δ − δ_res)^{3/2} through
/// them; its stress work is the last point's less the elastic work (2/5) F (δ − δ_res)
/// that law still stores there.
fn release_point(points: &[LoopPoint]) -> Result<LoopPoint> {
    let [.., a, b] = points else {
        return Err(Error::Numerical(
            "static loop: the contact let go within the first unloading step".into(),
        ));
    };
    let (a, b) = (*a, *b);
    let ratio = (a.force / b.force).powf(2.0 / 3.0);
    if !(ratio > 1.0 && ratio.is_finite()) {
        return Err(Error::Numerical(format!(
            "static loop: no release after unloading forces {:.4e} and {:.4e} N",
            a.force, b.force
        )));
    }
    let release = b.approach - (a.approach - b.approach) / (ratio - 1.0);
    Ok(LoopPoint {
        force: 0.0,
        approach: release,
        stress_work: b.stress_work - 0.4 * b.force * (b.approach - release),
        ..b
    })
}

/// The probe step that measures the unloading stiffness at the peak, of the peak's travel.
const PROBE: f64 = 1e-4;

/// The share of the peak force below which an unloading step that fails ends the unloading.
const RELEASE_ZONE: f64 = 0.1;

/// Halvings of a held unloading step that lets go, before the release is extrapolated.
const RELEASE_CUTS: u32 = 6;

/// The share of the peak force a loop is unloaded to (about, for the held ball) before its
/// release is extrapolated.
const RELEASE_FORCE: f64 = 0.01;

/// The force at approach `delta` on a rising curve, by quadratic interpolation through the
/// three points around it (NaN with fewer than three points; the loop has at least five).
fn interpolate(points: &[LoopPoint], delta: f64) -> f64 {
    if points.len() < 3 {
        return f64::NAN;
    }
    let k = points
        .iter()
        .position(|p| p.approach >= delta)
        .unwrap_or(points.len() - 1)
        .clamp(1, points.len() - 2);
    let (a, b, c) = (points[k - 1], points[k], points[k + 1]);
    let l = |x0: f64, x1: f64, x2: f64| (delta - x1) * (delta - x2) / ((x0 - x1) * (x0 - x2));
    a.force * l(a.approach, b.approach, c.approach)
        + b.force * l(b.approach, a.approach, c.approach)
        + c.force * l(c.approach, a.approach, b.approach)
}
