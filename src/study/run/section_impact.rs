//! A head-on impact on the meridian section, run end to end: a ball (its section with the
//! contact pole at (0, +R), centre at the origin) moving along +z against the symmetry plane
//! of two equal balls, a second ball, a rigid wall or an elastic wall's meshed block (base
//! fixed; the approach is the ball's displacement, that is its centre of mass against the
//! fixed base, docs/design.md §6), started at first touch and stopped like the
//! 3D study: once the ball separates and the contact force has been zero for a hold time.
//! Reports what the 3D study reports: the coefficient of restitution, the maximum approach,
//! the contact duration, the peak force, the energy terms, the energy error and history rows.

use crate::error::{Error, Result};
use crate::fe::contact::duration::pulse_duration;
use crate::fe::contact::section::plane_kinematic::KinematicPlane;
use crate::fe::contact::section::plane_nodal::{ring_areas_and_thickness, NodalPlane, Side};
use crate::fe::contact::section::plane_segment::SegmentPlane;
use crate::fe::contact::section::segment::{Boundary, SegmentPair};
use crate::fe::elements::ring::QuadFormulation;
use crate::fe::interaction::Interaction;
use crate::fe::materials::J2Material;
use crate::fe::section::mass_scaling;
use crate::fe::section::solver::{SectionModel, SectionSolver};
use crate::fe::simd::KernelPath;
use crate::fe::subcycle::Integration;
use crate::material::Material;
use crate::mesh::section::SectionMesh;
use crate::study::run::smoothed_force::{half_width, triangular};
use serde::Serialize;
use std::time::Instant;

/// Steps between two calls of the observer of [`HeadOn::run_observed`].
pub const OBSERVE_EVERY: u64 = 64;

/// What the ball hits.
#[derive(Debug, Clone)]
pub enum Target {
    /// An identical ball moving the opposite way: the frictionless symmetry plane between
    /// them. Approach, force and restitution are those of the pair.
    MirrorBall,
    /// A rigid frictionless wall.
    RigidWall,
    /// Another ball, meshed too, with node-to-segment contact between the two sections.
    Ball(Box<OtherBall>),
    /// An elastic-plastic wall: a meshed block at rest, its base fixed, with node-to-segment
    /// contact between the ball's boundary and the block's face.
    ElasticWall(Box<WallBlock>),
}

/// The block of an elastic wall.
#[derive(Debug, Clone)]
pub struct WallBlock {
    /// Its meridian mesh: r ∈ [0, W], z ∈ [−H, 0], face z = 0 up, contact segments in
    /// `segment_sets["contact"]`, the nodes to fix in `node_sets["base"]`; it is mirrored and
    /// placed with its face on the ball's pole.
    pub mesh: SectionMesh,
    /// Its material.
    pub material: Material,
    /// Skip plasticity.
    pub elastic_only: bool,
}

/// How a rigid plane (the mirror plane or a wall) takes the ball's boundary.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlaneContact {
    /// A penalty spring per boundary node ([`NodalPlane`]): the contact area grows ring by ring.
    Nodal,
    /// Penalty pressure integrated over the penetrated part of each segment
    /// ([`SegmentPlane`]): the contact area grows continuously.
    Segment,
    /// A unilateral kinematic constraint ([`KinematicPlane`]): no penalty, no compliance, no
    /// step limit of its own.
    #[default]
    Kinematic,
}

/// The second ball of a two-ball head-on impact.
#[derive(Debug, Clone)]
pub struct OtherBall {
    /// Its meridian mesh, in the same convention as the first ball's (pole at (0, +R₂),
    /// centre at the origin); it is mirrored and placed above the first ball's pole.
    pub mesh: SectionMesh,
    /// Its material.
    pub material: Material,
    /// Skip plasticity.
    pub elastic_only: bool,
    /// Its speed towards the first ball, m/s (≥ 0).
    pub speed: f64,
}

/// A head-on impact of one ball section.
#[derive(Debug, Clone)]
pub struct HeadOn {
    /// Meridian mesh of the ball: half-disc of radius R centred at the origin, contact pole at
    /// (0, +R), contact segments in `segment_sets["contact"]` (or the whole boundary).
    pub mesh: SectionMesh,
    /// The ball's material.
    pub material: Material,
    /// Skip plasticity (elastic ball).
    pub elastic_only: bool,
    /// Speed of the ball towards the target, m/s (> 0): half the relative speed for
    /// [`Target::MirrorBall`], the first ball's own for [`Target::Ball`].
    pub speed: f64,
    /// What the ball hits.
    pub target: Target,
    /// Element formulation.
    pub formulation: QuadFormulation,
    /// Penalty factor FKN of the pair contact (k = FKN E A / h); the mirror ball's symmetry
    /// plane carries 2 FKN, as the 3D quarter model's plane does.
    pub fkn: f64,
    /// Hold time of the separation rule as a fraction of the expected (Hertz) duration.
    pub hold_fraction: f64,
    /// History rows over the expected contact duration.
    pub history_rows: usize,
    /// Factor on the stable step (0 < f ≤ 1).
    pub time_step_factor: f64,
    /// Hold time of the separation rule, s; `None`: `hold_fraction` of the Hertz duration.
    pub hold_time: Option<f64>,
    /// Interval between history rows, s; `None`: `history_rows` over the Hertz duration.
    pub history_interval: Option<f64>,
    /// Stop at this time after first touch (s) instead of by the separation rule.
    pub end_time: Option<f64>,
    /// Most steps before the run fails as not separated.
    pub max_steps: u64,
    /// Single-rate or subcycled time integration (subcycled by default).
    pub integration: Integration,
    /// How the mirror plane or the wall takes the boundary.
    pub plane_contact: PlaneContact,
    /// Mass-scaling budget: the added mass over the model's mass that may raise the
    /// smallest quads' steps ([`crate::fe::section::mass_scaling`]; 0, the default: none).
    pub mass_scaling: f64,
    /// The widest lane path of the quads, `None` for scalar updates (the same
    /// bits either way; [`SectionModel::kernel`]).
    pub kernel: Option<KernelPath>,
}

/// One history row (whole system; for [`Target::MirrorBall`] the pair).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ImpactRow {
    /// Time since first touch, s.
    pub t: f64,
    /// Approach of the centres of mass since first touch, m.
    pub delta: f64,
    /// Normal contact force, N.
    pub normal_force: f64,
    /// Approach speed of the centres of mass (of the pair for the mirror ball), m/s.
    pub v_cm: f64,
    /// Axial velocity (along +z, from ball 1 towards the target) of ball 1's centre of mass,
    /// m/s.
    pub v1: f64,
    /// Axial velocity of the target's centre of mass (the mirror image −v1 for the mirror
    /// ball, 0 for the rigid wall, the block's for an elastic wall), m/s.
    pub v2: f64,
    /// Kinetic energy, J.
    pub kinetic: f64,
    /// Elastic strain energy, J.
    pub elastic: f64,
    /// Plastic work, J.
    pub plastic: f64,
    /// Hourglass energy, J.
    pub hourglass: f64,
    /// Energy stored in the contact springs, J.
    pub contact_stored: f64,
    /// Total of the above, J.
    pub total: f64,
    /// Normal impulse since the start, ∫F dt accumulated every step, N·s.
    pub impulse: f64,
}

/// The outcome of a head-on impact.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ImpactResult {
    /// Coefficient of restitution: separation over approach speed of the centres of mass.
    pub e: f64,
    /// Axial velocity of ball 1's centre of mass at the end, m/s.
    pub v1_after: f64,
    /// Axial velocity of the target's centre of mass at the end, m/s.
    pub v2_after: f64,
    /// Maximum approach of the centres of mass, m.
    pub delta_max: f64,
    /// Contact duration (first force to the fitted end of the pulse), s.
    pub contact_duration: f64,
    /// Peak of the smoothed normal force (triangular window of half-width T_c/20 over the
    /// history rows, [`crate::study::run::smoothed_force`]), N.
    pub peak_force: f64,
    /// Peak normal force, raw, of the steps, N.
    pub peak_force_raw: f64,
    /// Largest relative drift of the total energy over the run.
    pub energy_error: f64,
    /// Largest penetration into the plane, m.
    pub max_penetration: f64,
    /// Mass added by mass scaling over the model's mass (0 without).
    pub added_mass_fraction: f64,
    /// Largest contact radius over the run (the current r of the outermost node in contact),
    /// m.
    pub contact_radius_max: f64,
    /// Plastic work at the end (whole system), J.
    pub plastic: f64,
    /// Kinetic energy before the impact (whole system), J.
    pub initial_kinetic: f64,
    /// Quads and nodes of the simulated section.
    pub elements: usize,
    /// Nodes of the simulated section.
    pub nodes: usize,
    /// Steps taken (fine steps with subcycling).
    pub steps: u64,
    /// Quad updates taken (quads × steps single-rate, fewer subcycled).
    pub element_updates: u64,
    /// Initial stable step, s.
    pub dt: f64,
    /// Why the run stopped.
    pub stop_reason: String,
    /// Wall time of the run, s.
    pub wall_time_s: f64,
    /// History rows.
    #[serde(skip)]
    pub history: Vec<ImpactRow>,
    /// The force pulse (t in s, F in N) of the steps with a contact force.
    #[serde(skip)]
    pub pulse: Vec<(f64, f64)>,
}

/// The peak (N) of the rows' normal force smoothed for a contact of `contact_duration` (s).
fn smoothed_peak(rows: &[ImpactRow], contact_duration: f64) -> f64 {
    let t: Vec<f64> = rows.iter().map(|r| r.t).collect();
    let impulse: Vec<f64> = rows.iter().map(|r| r.impulse).collect();
    triangular(&t, &impulse, half_width(contact_duration))
        .into_iter()
        .fold(0.0, f64::max)
}

/// Hertz's contact duration 2.87 (m*²/(R* E*² v))^{1/5} (s) of a ball of radius `radius`
/// (m) and mass `ball_mass` (kg) against the target (the pair for the mirror ball; the
/// second ball's mass `mass2`, kg, for [`Target::Ball`]; a ball on an elastic half-space of
/// the block's material for [`Target::ElasticWall`]): the scale of the stop rule and the
/// history interval.
pub fn hertz_duration(h: &HeadOn, radius: f64, ball_mass: f64, mass2: f64) -> f64 {
    let c1 = (1.0 - h.material.nu * h.material.nu) / h.material.youngs;
    let (e_star, r_star, m_star, v) = match &h.target {
        Target::MirrorBall => (0.5 / c1, radius / 2.0, ball_mass / 2.0, 2.0 * h.speed),
        Target::RigidWall => (1.0 / c1, radius, ball_mass, h.speed),
        Target::ElasticWall(w) => {
            let c2 = (1.0 - w.material.nu * w.material.nu) / w.material.youngs;
            (1.0 / (c1 + c2), radius, ball_mass, h.speed)
        }
        Target::Ball(o) => {
            let c2 = (1.0 - o.material.nu * o.material.nu) / o.material.youngs;
            let r2 = o.mesh.nodes.iter().map(|p| p[1]).fold(f64::MIN, f64::max);
            (
                1.0 / (c1 + c2),
                radius * r2 / (radius + r2),
                ball_mass * mass2 / (ball_mass + mass2),
                h.speed + o.speed,
            )
        }
    };
    2.868 * (m_star * m_star / (r_star * e_star * e_star * v)).powf(0.2)
}

/// One section model of two bodies: `first` (material `mat1`) and `second` (material
/// `mat2`), whose nodes and quads follow the first's; velocities and supports are left to the
/// caller.
fn two_bodies(
    first: &SectionMesh,
    mat1: J2Material,
    second: &SectionMesh,
    mat2: J2Material,
) -> SectionModel {
    let n1 = first.nodes.len() as u32;
    let mut nodes = first.nodes.clone();
    nodes.extend(&second.nodes);
    let mut quads = first.quads.clone();
    quads.extend(second.quads.iter().map(|q| q.map(|i| i + n1)));
    let mut model = SectionModel::new(nodes, quads, mat1);
    model.materials.push(mat2);
    for e in first.quads.len()..model.quads.len() {
        model.material_of[e] = 1;
    }
    model
}

/// `mesh` mirrored about z = 0 and shifted by `shift` along z (m): quads and segments
/// re-ordered to stay counter-clockwise.
fn mirrored(mesh: &SectionMesh, shift: f64) -> SectionMesh {
    let mut m = mesh.clone();
    for p in &mut m.nodes {
        p[1] = shift - p[1];
    }
    for q in &mut m.quads {
        *q = [q[0], q[3], q[2], q[1]];
    }
    for s in m
        .boundary
        .iter_mut()
        .chain(m.segment_sets.values_mut().flatten())
    {
        *s = [s[1], s[0]];
    }
    m
}

impl HeadOn {
    /// The model and contact of the ball against the elastic wall `w`: the block mirrored so
    /// that its face z = 0 lies on the ball's pole z = `radius` (m), its base fixed, its
    /// material second; node-to-segment contact on the smaller Young's modulus.
    fn wall_model(
        &self,
        w: &WallBlock,
        radius: f64,
        mat: J2Material,
    ) -> Result<(SectionModel, Box<dyn Interaction<2>>)> {
        let n1 = self.mesh.nodes.len();
        let base = w.mesh.node_sets.get("base").filter(|b| !b.is_empty());
        let Some(base) = base else {
            return Err(Error::invalid(
                "wall.mesh",
                "no node set base",
                "a block mesh with its base nodes in node_sets[\"base\"]",
            ));
        };
        let m2 = mirrored(&w.mesh, radius);
        let mut model = two_bodies(
            &self.mesh,
            mat,
            &m2,
            J2Material::new(&w.material, w.elastic_only),
        );
        model.velocity = vec![[0.0, self.speed]; n1];
        model.velocity.extend(vec![[0.0, 0.0]; m2.nodes.len()]);
        for &i in base {
            model.fixed[n1 + i as usize] = [true, true];
        }
        let seg1 = self
            .mesh
            .segment_sets
            .get("contact")
            .unwrap_or(&self.mesh.boundary);
        let seg2 = m2.segment_sets.get("contact").unwrap_or(&m2.boundary);
        let pair = SegmentPair::new(
            Boundary {
                mesh: &self.mesh,
                segments: seg1,
                offset: 0,
            },
            Boundary {
                mesh: &m2,
                segments: seg2,
                offset: n1,
            },
            self.fkn,
            self.material.youngs.min(w.material.youngs),
        )?;
        Ok((model, Box::new(pair)))
    }

    /// Defaults around `mesh`, `material` and `speed`: one-point quads, FKN = 10, the 3D
    /// study's hold fraction 0.03, 200 history rows, step factor 0.9, subcycled.
    pub fn new(mesh: SectionMesh, material: Material, speed: f64, target: Target) -> Self {
        HeadOn {
            mesh,
            material,
            elastic_only: false,
            speed,
            target,
            formulation: QuadFormulation::default(),
            fkn: 10.0,
            hold_fraction: 0.03,
            history_rows: 200,
            time_step_factor: 0.9,
            hold_time: None,
            history_interval: None,
            end_time: None,
            max_steps: u64::MAX,
            integration: Integration::subcycled(),
            plane_contact: PlaneContact::default(),
            mass_scaling: 0.0,
            kernel: Some(KernelPath::Avx512),
        }
    }

    /// Runs the impact to separation (or to `end_time`).
    pub fn run(&self) -> Result<ImpactResult> {
        self.run_observed(&mut |_, _| Ok(()))
    }

    /// Runs the impact like [`HeadOn::run`], calling `observe(solver, last)` every
    /// [`OBSERVE_EVERY`] steps with `last` false (the solver's clock is the time since first
    /// touch, s) and once at the end with `last` true; an error from `observe` (an interrupt,
    /// a failed snapshot) stops the run and is returned.
    pub fn run_observed(
        &self,
        observe: &mut dyn FnMut(&SectionSolver, bool) -> Result<()>,
    ) -> Result<ImpactResult> {
        let start = Instant::now();
        if !(self.speed.is_finite() && self.speed > 0.0) {
            return Err(Error::invalid("speed", self.speed, "> 0 m/s, finite"));
        }
        let radius = self
            .mesh
            .nodes
            .iter()
            .map(|p| p[1])
            .fold(f64::MIN, f64::max);
        if radius.is_nan() || radius <= 0.0 {
            return Err(Error::invalid(
                "mesh",
                radius,
                "a ball with its pole at z = R > 0",
            ));
        }
        let mat = J2Material::new(&self.material, self.elastic_only);
        let n1 = self.mesh.nodes.len();
        let contact_of = |m: &SectionMesh| -> Vec<[u32; 2]> {
            m.segment_sets.get("contact").unwrap_or(&m.boundary).clone()
        };
        let seg1 = contact_of(&self.mesh);
        // The penetration limit of the 3D contacts: half the thickness of the thinnest
        // element under a contact node, a quarter on the mirror plane (which sees half the
        // pair's overlap).
        let thinnest = |m: &SectionMesh, seg: &[[u32; 2]]| -> Result<f64> {
            Ok(ring_areas_and_thickness(m, seg)?
                .iter()
                .map(|t| t.2)
                .fold(f64::INFINITY, f64::min))
        };
        let mut thickness = thinnest(&self.mesh, &seg1)?;
        match &self.target {
            Target::Ball(o) => {
                thickness = thickness.min(thinnest(&o.mesh, contact_of(&o.mesh).as_slice())?);
            }
            Target::ElasticWall(w) => {
                thickness = thickness.min(thinnest(&w.mesh, contact_of(&w.mesh).as_slice())?);
            }
            _ => {}
        }
        let limit_fraction = match self.target {
            Target::MirrorBall => 0.25,
            _ => 0.5,
        };
        let penetration_limit = limit_fraction * thickness;
        let (model, contact): (SectionModel, Box<dyn Interaction<2>>) = match &self.target {
            Target::MirrorBall | Target::RigidWall => {
                let mut model =
                    SectionModel::new(self.mesh.nodes.clone(), self.mesh.quads.clone(), mat);
                model.velocity = vec![[0.0, self.speed]; n1];
                // The mirror plane stands for the two-pass pair contact with the mirror ball:
                // the pair's gap is twice the plane's, so the plane carries twice the pair's
                // factor (docs/design.md, the quarter model's penalty); a wall carries it once.
                let fkn = match self.target {
                    Target::MirrorBall => 2.0 * self.fkn,
                    _ => self.fkn,
                };
                let (m, youngs) = (&self.mesh, self.material.youngs);
                let plane: Box<dyn Interaction<2>> = match self.plane_contact {
                    PlaneContact::Nodal => {
                        Box::new(NodalPlane::new(m, &seg1, radius, Side::Below, fkn, youngs)?)
                    }
                    PlaneContact::Segment => Box::new(SegmentPlane::new(
                        m,
                        &seg1,
                        radius,
                        Side::Below,
                        fkn,
                        youngs,
                    )?),
                    PlaneContact::Kinematic => {
                        Box::new(KinematicPlane::new(m, &seg1, radius, Side::Below)?)
                    }
                };
                (model, plane)
            }
            Target::Ball(o) => {
                if !(o.speed.is_finite() && o.speed >= 0.0) {
                    return Err(Error::invalid("ball2.speed", o.speed, ">= 0 m/s, finite"));
                }
                let r2 = o.mesh.nodes.iter().map(|p| p[1]).fold(f64::MIN, f64::max);
                let m2 = mirrored(&o.mesh, radius + r2);
                let mut model = two_bodies(
                    &self.mesh,
                    mat,
                    &m2,
                    J2Material::new(&o.material, o.elastic_only),
                );
                let n2 = m2.nodes.len();
                model.velocity = vec![[0.0, self.speed]; n1];
                model.velocity.extend(vec![[0.0, -o.speed]; n2]);
                let seg2 = contact_of(&m2);
                let pair = SegmentPair::new(
                    Boundary {
                        mesh: &self.mesh,
                        segments: &seg1,
                        offset: 0,
                    },
                    Boundary {
                        mesh: &m2,
                        segments: &seg2,
                        offset: n1,
                    },
                    self.fkn,
                    self.material.youngs.min(o.material.youngs),
                )?;
                (model, Box::new(pair) as Box<dyn Interaction<2>>)
            }
            Target::ElasticWall(w) => self.wall_model(w, radius, mat)?,
        };
        let mut model = model;
        model.formulation = self.formulation;
        model.time_step_factor = self.time_step_factor;
        model.integration = self.integration;
        model.kernel = self.kernel;
        mass_scaling::check_budget(self.mass_scaling)?;
        let mut added_mass_fraction = 0.0;
        if self.mass_scaling > 0.0 {
            let mats = &model.materials;
            let of = &model.material_of;
            let scaling = mass_scaling::within_budget(
                &model.nodes,
                &model.quads,
                |e| mats[of[e]].wave_speed,
                |e| mats[of[e]].rho,
                self.mass_scaling,
            )?;
            added_mass_fraction = scaling.added_fraction;
            model.density_scale = scaling.scale;
        }
        let mut solver = SectionSolver::new(model, vec![contact])?;
        let n = solver.masses().len();
        let ball_mass: f64 = solver.masses()[..n1].iter().sum();
        let mass2: f64 = solver.masses()[n1..].iter().sum();
        let duration = hertz_duration(self, radius, ball_mass, mass2);
        let two = matches!(self.target, Target::Ball(_));
        let block = matches!(self.target, Target::ElasticWall(_));
        let (scale, pair) = match self.target {
            Target::MirrorBall => (2.0, 2.0),
            _ => (1.0, 1.0),
        };
        let mirror = if matches!(self.target, Target::MirrorBall) {
            -1.0
        } else {
            0.0
        };
        // Approach δ (m), approach speed (m/s) and the two axial velocities (m/s) of the
        // centres of mass.
        let approach = |s: &SectionSolver| -> (f64, f64, [f64; 2]) {
            let z1 = s.axial_centre(0..n1);
            let (p1, m1) = s.axial_momentum(0..n1);
            if two {
                let z2 = s.axial_centre(n1..n);
                let (p2, m2) = s.axial_momentum(n1..n);
                (z1 - z2, p1 / m1 - p2 / m2, [p1 / m1, p2 / m2])
            } else if block {
                // The block's base is fixed: the ball's own displacement is its approach to
                // the base (docs/design.md §6).
                let (p2, m2) = s.axial_momentum(n1..n);
                (z1, p1 / m1, [p1 / m1, p2 / m2])
            } else {
                (pair * z1, pair * p1 / m1, [p1 / m1, mirror * p1 / m1])
            }
        };
        let hold = self.hold_time.unwrap_or(self.hold_fraction * duration);
        let interval = self
            .history_interval
            .unwrap_or(duration / self.history_rows.max(2) as f64);
        let (d0, u0, _) = approach(&solver);
        let e0 = solver.energy();
        let dt0 = solver.dt();
        let mut history = Vec::new();
        let mut pulse: Vec<(f64, f64)> = Vec::new();
        let mut impulse = 0.0;
        let mut next_row = 0.0;
        let mut drift: f64 = 0.0;
        let mut apart_since: Option<f64> = None;
        let mut max_pen: f64 = 0.0;
        let mut contact_radius_max: f64 = 0.0;
        let mut delta_max: f64 = 0.0;
        let t_cap = self.end_time.unwrap_or(30.0 * duration);
        let stop_reason;
        loop {
            let t = solver.time();
            if solver.steps() % OBSERVE_EVERY == 0 {
                observe(&solver, false)?;
            }
            let c = solver.contact_states()[0];
            let en = solver.energy();
            drift = drift.max((en.total - e0.total).abs() / e0.total);
            let (d, u, v12) = approach(&solver);
            let delta = d - d0;
            delta_max = delta_max.max(delta);
            max_pen = max_pen.max(c.max_penetration);
            contact_radius_max = contact_radius_max.max(c.contact_radius);
            if c.max_penetration > penetration_limit {
                return Err(Error::Numerical(format!(
                    "contact: a node penetrates {:.3e} m at t = {t:.6e} s, more than \
                     {limit_fraction} of the thinnest contact element's thickness {thickness:.3e} m; \
                     raise the penalty factor or lower the time step",
                    c.max_penetration
                )));
            }
            if c.normal_force > 0.0 {
                pulse.push((t, c.normal_force));
            }
            if t >= next_row {
                let row = ImpactRow {
                    t,
                    delta,
                    normal_force: c.normal_force,
                    v_cm: u,
                    v1: v12[0],
                    v2: v12[1],
                    kinetic: scale * en.solid.kinetic,
                    elastic: scale * (en.solid.internal - en.solid.plastic),
                    plastic: scale * en.solid.plastic,
                    hourglass: scale * en.solid.hourglass,
                    contact_stored: scale * en.interaction_stored,
                    total: scale * en.total,
                    impulse,
                };
                if !en.total.is_finite() || !delta.is_finite() {
                    return Err(Error::Numerical(format!(
                        "non-finite state at t = {t:.6e} s (step {}): lower the time-step factor or the penalty factor",
                        solver.steps()
                    )));
                }
                history.push(row);
                next_row = t + interval;
            }
            if let Some(end) = self.end_time {
                if t >= end && solver.synchronised() {
                    stop_reason = format!("end time {end:.3e} s reached");
                    break;
                }
            } else if !pulse.is_empty() && u < 0.0 && c.normal_force == 0.0 {
                let since = *apart_since.get_or_insert(t);
                if t - since >= hold && solver.synchronised() {
                    stop_reason = format!("separated: contact force zero for {hold:.3e} s");
                    break;
                }
            } else {
                apart_since = None;
            }
            if self.end_time.is_none() && t > t_cap {
                return Err(Error::Numerical(format!(
                    "the ball had not separated after {t:.3e} s (30 Hertz durations)"
                )));
            }
            if solver.steps() >= self.max_steps {
                return Err(Error::Numerical(format!(
                    "the balls had not separated after solver.max_steps = {} steps (t = {t:.6e} s): raise solver.max_steps or set solver.end_time",
                    self.max_steps
                )));
            }
            let t_before = solver.time();
            solver.step()?;
            impulse += c.normal_force * (solver.time() - t_before);
        }
        observe(&solver, true)?;
        let (_, u_end, v_end) = approach(&solver);
        let contact_duration = pulse_duration(&pulse).unwrap_or_else(|| {
            pulse.last().map_or(0.0, |l| l.0) - pulse.first().map_or(0.0, |f| f.0)
        });
        let en = solver.energy();
        Ok(ImpactResult {
            e: -u_end / u0,
            v1_after: v_end[0],
            v2_after: v_end[1],
            delta_max,
            contact_duration,
            peak_force: smoothed_peak(&history, contact_duration),
            peak_force_raw: pulse.iter().map(|p| p.1).fold(0.0, f64::max),
            energy_error: drift,
            max_penetration: max_pen,
            added_mass_fraction,
            contact_radius_max,
            plastic: scale * en.solid.plastic,
            initial_kinetic: scale * e0.solid.kinetic,
            elements: solver.states().len(),
            nodes: n,
            steps: solver.steps(),
            element_updates: solver.element_updates(),
            dt: dt0,
            stop_reason,
            wall_time_s: start.elapsed().as_secs_f64(),
            history,
            pulse,
        })
    }
}
