//! The quasi-static implicit solver of a meridian section: equilibrium f_int(x) = f_ext at
//! each load increment by Newton-Raphson with a backtracking line search, the tangent of
//! every element from its own update ([`super::element_tangent`]), the sparse solve of
//! [`super::system`], and a rigid frictionless plane enforced exactly by an active set
//! ([`super::plane`]). Geometrically nonlinear (updated Lagrangian, the explicit elements'
//! objective update); rate-dependent laws at their reference rate ([`Law::quasi_static`]).
//!
//! An increment is driven by a [`Target`]: the factor on the model's nodal loads, prescribed
//! total displacements of some nodes (a held support pushed towards the plane) and the
//! plane's position. Each increment's relative residual norms are kept, so the quadratic
//! convergence of Newton near the solution can be seen.
//!
//! [`Law::quasi_static`]: crate::material::hardening::Law::quasi_static

use super::element_tangent::{increment_forces, increment_tangent};
use super::plane::ExactPlane;
use super::system::Pattern;
use crate::error::{Error, Result};
use crate::fe::elements::ring::element::Quad;
use crate::fe::elements::ring::shape::characteristic_length;
use crate::fe::elements::ring::{QuadFormulation, QuadState};
use crate::fe::materials::J2Material;
use crate::fe::section::solver::SectionModel;
use rayon::prelude::*;
use std::sync::Arc;

/// A prescribed total displacement of one nodal component from the initial position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prescribed {
    /// Node index.
    pub node: u32,
    /// Component: 0 = r, 1 = z.
    pub dir: usize,
    /// Displacement from the initial position, m.
    pub displacement: f64,
}

/// What an increment drives the model to.
#[derive(Debug, Clone, Default)]
pub struct Target {
    /// Factor on the model's nodal loads (dimensionless).
    pub load_factor: f64,
    /// Prescribed total displacements.
    pub prescribed: Vec<Prescribed>,
    /// The plane's axial position, m (`None`: where it is).
    pub plane_z: Option<f64>,
    /// Displacement control of the loads: the load factor becomes the unknown that brings
    /// this free degree of freedom to its displacement (`load_factor` is then ignored), by
    /// the bordered Newton of Batoz & Dhatt (1979). `None`: the load factor is given.
    pub load_control: Option<Prescribed>,
}

/// Newton and active-set settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Converged when the residual norm on the free degrees of freedom falls below this
    /// fraction of the force scale (the loads' and reactions' norm); default 1e-8.
    pub residual_tol: f64,
    /// Newton iterations allowed per active set (default 40; fewer when the residual is still
    /// above the force scale after 10 of them).
    pub max_iterations: usize,
    /// Active-set changes allowed per increment (default 20).
    pub max_active_changes: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            residual_tol: 1e-8,
            max_iterations: 40,
            max_active_changes: 20,
        }
    }
}

/// How one increment converged.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Increment {
    /// Relative residual norm before each Newton iteration, over every active set tried
    /// (the last one below [`Settings::residual_tol`]).
    pub residuals: Vec<f64>,
    /// Newton iterations taken (tangent solves).
    pub iterations: usize,
    /// Times the contact's active set changed.
    pub active_changes: usize,
    /// Times the increment was cut in half.
    pub cuts: usize,
}

/// The linear solve's relative residual per unit relative residual of Newton (the forcing
/// term of an inexact Newton step, Eisenstat & Walker 1996): proportional to the residual,
/// so the convergence stays quadratic, a tenth of it, so the step is as good as exact
/// where it matters; [`super::system::REFINE_TOL`] at least.
const FORCING: f64 = 0.1;

/// The relative residual an active set that may still change is solved to.
const LOOSE_TOL: f64 = 1e-6;

/// Newton iterations after which a residual still above the force scale itself counts as
/// diverged: the increment is cut at once instead of after every allowed iteration.
const DIVERGED_AFTER: usize = 10;

/// The longest step, relative to the last one, that the last increment predicts.
const MAX_PREDICTION: f64 = 4.0;

/// Halvings of one increment before it is given up.
pub const MAX_CUTS: u32 = 6;

/// The static solver of a section at its last converged state (a clone is a snapshot to
/// solve again from; the tangent's pattern is shared).
#[derive(Clone)]
pub struct StaticSolver {
    model: SectionModel,
    plane: Option<ExactPlane>,
    settings: Settings,
    pattern: Arc<Pattern>,
    x: Vec<[f64; 2]>,
    states: Vec<QuadState>,
    f_int: Vec<[f64; 2]>,
    active: Vec<bool>,
    load_factor: f64,
    gap_tol: f64,
    /// The last committed increment (m per node), its change of load factor and the control
    /// step that drove it ([`StaticSolver::control_step`]), the predictor of the next one.
    last: Option<(Vec<[f64; 2]>, f64, f64)>,
    /// The element tangents taken so far, kept while they hold.
    tangents: TangentCache,
}

/// One Newton system: which degrees of freedom are constrained and to what increments (m),
/// the load-controlling degree of freedom and its increment (m), the relative tolerance.
#[derive(Clone, Copy)]
struct System<'a> {
    constrained: &'a [bool],
    values: &'a [f64],
    control: Option<(usize, f64)>,
    tol: f64,
}

/// A function of one quad over an increment: its formulation, material, nodes at the start
/// (m), nodal increments (m) and committed state.
type QuadOp<T> = fn(QuadFormulation, &J2Material, &Quad, &Quad, &QuadState) -> T;

/// The element tangents the solver keeps from one Newton iteration, active set and increment
/// to the next, where each was taken and whether any of its evaluations flowed plastically.
#[derive(Clone, Default)]
struct TangentCache {
    blocks: Vec<[[f64; 8]; 8]>,
    plastic: Vec<bool>,
    /// The quads' nodal positions (m) where each tangent was taken, and their sizes (m).
    taken_at: Vec<Quad>,
    size: Vec<f64>,
}

impl TangentCache {
    /// A cache of `quads` quads with no tangent taken yet (each marked plastic, so the first
    /// refresh takes them all).
    fn empty(quads: usize) -> Self {
        TangentCache {
            blocks: vec![[[0.0; 8]; 8]; quads],
            plastic: vec![true; quads],
            taken_at: vec![[[0.0; 2]; 4]; quads],
            size: vec![0.0; quads],
        }
    }
}

/// The straining movement of a quad's nodes from `from` to `to` (m): the largest nodal
/// change once the quad's mean axial shift (a rigid translation along the axis, which
/// changes no ring's forces) is taken out.
fn straining_drift(from: &Quad, to: &Quad) -> f64 {
    let shift = 0.25 * (0..4).map(|k| to[k][1] - from[k][1]).sum::<f64>();
    (0..4)
        .map(|k| {
            (to[k][0] - from[k][0])
                .abs()
                .max((to[k][1] - from[k][1] - shift).abs())
        })
        .fold(0.0, f64::max)
}

/// The straining nodal movement (relative to the quad's size) below which an elastic quad's
/// tangent is kept ([`StaticSolver::refresh_tangents`]).
const TANGENT_DRIFT: f64 = 1e-5;

/// The forces and trial states of every quad for one displacement increment.
struct Evaluation {
    f_int: Vec<[f64; 2]>,
    states: Vec<QuadState>,
}

impl StaticSolver {
    /// A solver at the unloaded initial state of `model` (its loads are the reference loads
    /// a [`Target::load_factor`] scales), with an optional rigid plane; nodes touching the
    /// plane start in contact. Fails on an invalid model or a node across the plane.
    pub fn new(
        mut model: SectionModel,
        plane: Option<ExactPlane>,
        settings: Settings,
    ) -> Result<Self> {
        model.check()?;
        if let Some(p) = plane {
            if !(p.z.is_finite() && (p.side == 1.0 || p.side == -1.0)) {
                return Err(Error::invalid(
                    "static.plane",
                    format!("z = {}, side = {}", p.z, p.side),
                    "finite z, side +1 or -1",
                ));
            }
        }
        for m in model.materials.iter_mut() {
            *m = J2Material {
                law: m.law.quasi_static(),
                ..*m
            };
        }
        let size = bounding_size(&model.nodes);
        let gap_tol = 1e-10 * size;
        let n = model.nodes.len();
        let mut active = vec![false; n];
        if let Some(p) = plane {
            for (i, x) in model.nodes.iter().enumerate() {
                let g = p.gap(x[1]);
                if g < -gap_tol {
                    return Err(Error::invalid(
                        format!("static.nodes[{i}].z"),
                        x[1],
                        "on the body's side of the plane",
                    ));
                }
                active[i] = g <= gap_tol;
            }
        }
        Ok(StaticSolver {
            pattern: Arc::new(Pattern::new(n, &model.quads)?),
            x: model.nodes.clone(),
            states: vec![QuadState::default(); model.quads.len()],
            f_int: vec![[0.0; 2]; n],
            active,
            load_factor: 0.0,
            gap_tol,
            last: None,
            tangents: TangentCache::empty(model.quads.len()),
            plane,
            settings,
            model,
        })
    }

    /// Solves the increment from the last converged state to `target` and commits it; an
    /// increment that does not converge is cut in halves (at most [`MAX_CUTS`] times over).
    /// Fails (leaving the last converged state) when it still does not: Newton or the active
    /// set not converging, an element inverting, a singular tangent.
    pub fn solve(&mut self, target: &Target) -> Result<Increment> {
        let start = self.clone();
        let done = self.solve_cut(target, 0);
        if done.is_err() {
            *self = start;
        }
        done
    }

    fn solve_cut(&mut self, target: &Target, depth: u32) -> Result<Increment> {
        match self.solve_once(target) {
            Err(Error::Numerical(why)) if depth < MAX_CUTS => {
                let mid = self.midway(target);
                let mut first = self
                    .solve_cut(&mid, depth + 1)
                    .map_err(|_| Error::Numerical(why))?;
                let second = self.solve_cut(target, depth + 1)?;
                first.residuals.extend(second.residuals);
                first.iterations += second.iterations;
                first.active_changes += second.active_changes;
                first.cuts += 1 + second.cuts;
                Ok(first)
            }
            other => other,
        }
    }

    /// The target halfway from the last converged state to `target`.
    fn midway(&self, target: &Target) -> Target {
        let half = |from: f64, to: f64| from + 0.5 * (to - from);
        Target {
            load_factor: half(self.load_factor, target.load_factor),
            prescribed: target
                .prescribed
                .iter()
                .map(|p| Prescribed {
                    displacement: half(self.displacement(p.node, p.dir), p.displacement),
                    ..*p
                })
                .collect(),
            plane_z: match (self.plane, target.plane_z) {
                (Some(p), Some(z)) => Some(half(p.z, z)),
                _ => target.plane_z,
            },
            load_control: target.load_control.map(|p| Prescribed {
                displacement: half(self.displacement(p.node, p.dir), p.displacement),
                ..p
            }),
        }
    }

    fn solve_once(&mut self, target: &Target) -> Result<Increment> {
        let mut tangents = std::mem::take(&mut self.tangents);
        let done = self.solve_with(target, &mut tangents);
        self.tangents = tangents;
        done
    }

    /// [`StaticSolver::solve_once`] with the element tangents `tangents`.
    fn solve_with(&mut self, target: &Target, tangents: &mut TangentCache) -> Result<Increment> {
        let n = self.x.len();
        for p in target.prescribed.iter().chain(&target.load_control) {
            if p.node as usize >= n || p.dir > 1 || !p.displacement.is_finite() {
                return Err(Error::invalid(
                    "static.prescribed",
                    format!("{p:?}"),
                    format!("node < {n}, dir 0 or 1, finite displacement"),
                ));
            }
        }
        let plane = match (self.plane, target.plane_z) {
            (Some(p), Some(z)) => Some(ExactPlane { z, ..p }),
            (p, _) => p,
        };
        let step = self.control_step(target, plane);
        let (mut du, predicted_load) = self.prediction(step, n);
        let mut active = self.active.clone();
        if let Some(p) = plane {
            self.land_predicted(p, &mut active, &mut du);
        }
        let start_load = match target.load_control {
            Some(_) => predicted_load,
            None => target.load_factor,
        };
        let mut load = start_load;
        let mut report = Increment::default();
        // While the active set moves, each set is solved to a loose tolerance only; the set
        // that stays is solved to the full one (and checked again).
        let mut tol = self.settings.residual_tol.max(LOOSE_TOL);
        let eval = loop {
            let (constrained, values) = self.constraints(target, plane, &active);
            let control = self.control(target, &constrained)?;
            let system = System {
                constrained: &constrained,
                values: &values,
                control,
                tol,
            };
            let (eval, rel) = self.newton(&mut du, &mut load, &system, tangents, &mut report)?;
            let f_ext = self.loads(load);
            let (added, released) = match plane {
                Some(p) => self.settle(p, &mut active, &du, &eval.f_int, &f_ext, tol),
                None => (0, 0),
            };
            let changes = added + released;
            if changes == 0 {
                if rel <= self.settings.residual_tol {
                    break eval;
                }
                // The same state starts the next solve: list its residual once.
                report.residuals.pop();
                tol = self.settings.residual_tol;
                continue;
            }
            report.active_changes += changes;
            // A set that lands nodes starts again from the committed state: from the last
            // set's solution, the nodes it adds can throw Newton into cycles. A set that
            // only releases nodes (whose pull exceeds the tolerance, usually just) goes on
            // from that solution, which releasing them barely moves.
            if added > 0 {
                du.iter_mut().for_each(|d| *d = [0.0; 2]);
                load = match target.load_control {
                    Some(_) => self.load_factor,
                    None => start_load,
                };
            }
            if report.active_changes > self.settings.max_active_changes {
                return Err(Error::Numerical(format!(
                    "static contact: the active set did not settle after {} changes at load \
                     factor {}",
                    report.active_changes, target.load_factor
                )));
            }
        };
        for (x, d) in self.x.iter_mut().zip(&du) {
            x[0] += d[0];
            x[1] += d[1];
        }
        self.states = eval.states;
        self.f_int = eval.f_int;
        self.active = active;
        let dload = load - self.load_factor;
        self.last = step.map(|h| (du, dload, h));
        self.load_factor = load;
        self.plane = plane;
        Ok(report)
    }

    /// The signed step of the one control `target` moves from the committed state (the
    /// first prescribed displacement's, else the load factor's, else the plane's), or `None`
    /// when it moves none.
    fn control_step(&self, target: &Target, plane: Option<ExactPlane>) -> Option<f64> {
        let first = target.load_control.or(target.prescribed.first().copied());
        let step = match (first, plane, self.plane) {
            (Some(p), ..) => p.displacement - self.displacement(p.node, p.dir),
            _ if target.load_factor != self.load_factor => target.load_factor - self.load_factor,
            (None, Some(to), Some(from)) => to.z - from.z,
            _ => 0.0,
        };
        (step != 0.0 && step.is_finite()).then_some(step)
    }

    /// The first guess of an increment of control step `step` over `n` nodes: the last
    /// increment scaled by the ratio of the steps when they go the same way and the new one
    /// is at most [`MAX_PREDICTION`] times longer (loading on, unloading on), else zero.
    fn prediction(&self, step: Option<f64>, n: usize) -> (Vec<[f64; 2]>, f64) {
        match (step, &self.last) {
            (Some(h), Some((du, dload, last))) if h / last > 0.0 && h / last <= MAX_PREDICTION => {
                let r = h / last;
                let du = du.iter().map(|d| [r * d[0], r * d[1]]).collect();
                (du, self.load_factor + r * dload)
            }
            _ => (vec![[0.0; 2]; n], self.load_factor),
        }
    }

    /// The displacement (m) of node `i`'s component `dir` from its initial position.
    fn displacement(&self, i: u32, dir: usize) -> f64 {
        let i = i as usize;
        self.x[i][dir] - self.model.nodes[i][dir]
    }

    /// The external forces (N) of the load factor `load`.
    fn loads(&self, load: f64) -> Vec<[f64; 2]> {
        self.model
            .loads
            .iter()
            .map(|l| [load * l[0], load * l[1]])
            .collect()
    }

    /// The degree of freedom `target` controls the loads by and the increment it takes
    /// there (m), or `None`. A controlled degree of freedom that is also constrained, or
    /// a model without loads, is an error.
    fn control(&self, target: &Target, constrained: &[bool]) -> Result<Option<(usize, f64)>> {
        let Some(p) = target.load_control else {
            return Ok(None);
        };
        let d = 2 * p.node as usize + p.dir;
        if constrained[d] || self.model.loads.iter().all(|l| l == &[0.0; 2]) {
            return Err(Error::invalid(
                "static.load_control",
                format!("{p:?}"),
                "a free degree of freedom of a model with loads",
            ));
        }
        Ok(Some((d, p.displacement - self.displacement(p.node, p.dir))))
    }

    /// The constrained degrees of freedom (2 per node) and the increments they take: the
    /// axis (r), the model's supports, the prescribed displacements and the nodes on the
    /// plane (z).
    fn constraints(
        &self,
        target: &Target,
        plane: Option<ExactPlane>,
        active: &[bool],
    ) -> (Vec<bool>, Vec<f64>) {
        let n = self.x.len();
        let (mut c, mut v) = (vec![false; 2 * n], vec![0.0; 2 * n]);
        for i in 0..n {
            let fx = self.model.fixed[i];
            c[2 * i] = self.model.nodes[i][0] == 0.0 || fx[0];
            c[2 * i + 1] = fx[1];
        }
        for p in &target.prescribed {
            let i = p.node as usize;
            let d = 2 * i + p.dir;
            c[d] = true;
            v[d] = self.model.nodes[i][p.dir] + p.displacement - self.x[i][p.dir];
        }
        if let Some(p) = plane {
            for (i, &a) in active.iter().enumerate() {
                if a {
                    c[2 * i + 1] = true;
                    v[2 * i + 1] = p.z - self.x[i][1];
                }
            }
        }
        (c, v)
    }

    /// Newton-Raphson for the increment `du` (m) and the load factor `load`: the free degrees
    /// of freedom in equilibrium, the constrained ones at their values and, under load
    /// control, the controlled one at its increment. A value not yet reached enters the
    /// linear system as a prescribed correction, so the first iteration is the tangent's
    /// prediction of the whole increment (the displacement a held support or a node landing
    /// on the plane imposes spreads through the body, instead of straining the elements next
    /// to it alone). Under load control the factorisation solves two columns, K a = r and
    /// K b = f_ref, and the load changes by Δλ = (gap − a_c) / b_c so that the controlled
    /// degree of freedom meets its increment (Batoz & Dhatt 1979). A backtracking line search
    /// on the free residual guards the iterations that meet every value. Returns the
    /// evaluation and its relative residual once that is at most the system's tolerance.
    fn newton(
        &self,
        du: &mut [[f64; 2]],
        load: &mut f64,
        sys: &System<'_>,
        cache: &mut TangentCache,
        report: &mut Increment,
    ) -> Result<(Evaluation, f64)> {
        let System {
            constrained,
            values,
            control,
            tol,
        } = *sys;
        let gap = |du: &[[f64; 2]]| -> Vec<f64> {
            (0..values.len())
                .map(|d| {
                    if constrained[d] {
                        values[d] - du[d / 2][d % 2]
                    } else {
                        0.0
                    }
                })
                .collect()
        };
        let control_gap = |du: &[[f64; 2]]| control.map_or(0.0, |(d, v)| v - du[d / 2][d % 2]);
        let reference: Vec<f64> = (0..values.len())
            .map(|d| {
                if constrained[d] {
                    0.0
                } else {
                    self.model.loads[d / 2][d % 2]
                }
            })
            .collect();
        let mut eval = self.evaluate(du)?;
        let f_ext = self.loads(*load);
        let mut r = residual(&eval.f_int, &f_ext, constrained);
        let mut rel = norm(&r) / force_scale(&eval.f_int, &f_ext, constrained);
        for k in 0..self.settings.max_iterations {
            let open = gap(du);
            let limit = 1e-3 * self.gap_tol;
            let met = open.iter().all(|g| g.abs() <= limit) && control_gap(du).abs() <= limit;
            report.residuals.push(rel);
            if met && rel <= tol {
                return Ok((eval, rel));
            }
            if k >= DIVERGED_AFTER && rel > 1.0 {
                break;
            }
            let rhs: Vec<f64> = r.iter().zip(&open).map(|(a, b)| a + b).collect();
            self.refresh_tangents(du, &eval.states, cache);
            let tangents = &cache.blocks;
            let forcing = FORCING * rel;
            let (d, dload) = match control {
                None => (
                    self.pattern.solve(tangents, constrained, &rhs, forcing)?,
                    0.0,
                ),
                Some((c, _)) => {
                    let cols = self.pattern.solve_columns(
                        tangents,
                        constrained,
                        &[&rhs, &reference],
                        forcing,
                    )?;
                    let (a, b) = (&cols[0], &cols[1]);
                    let dload = (control_gap(du) - a[c]) / b[c];
                    if !dload.is_finite() {
                        return Err(Error::Numerical(format!(
                            "static load control: the controlled degree of freedom does not \
                             move with the loads (b = {:.3e} m per unit load)",
                            b[c]
                        )));
                    }
                    let d = a.iter().zip(b).map(|(a, b)| a + dload * b).collect();
                    (d, dload)
                }
            };
            // The identity rows' exact solution is their prescribed correction; a sparse solve
            // returns it only to its round-off against the stiffness (about 1e-14 m), above
            // the check's 1e-3 gap tolerance, and unmet constraints switch the line search off.
            let mut d = d;
            for (k, g) in open.iter().enumerate() {
                if constrained[k] {
                    d[k] = *g;
                }
            }
            report.iterations += 1;
            let mut alpha = 1.0;
            loop {
                let trial: Vec<[f64; 2]> = du
                    .iter()
                    .enumerate()
                    .map(|(i, u)| [u[0] + alpha * d[2 * i], u[1] + alpha * d[2 * i + 1]])
                    .collect();
                let trial_load = *load + alpha * dload;
                match self.evaluate(&trial) {
                    Ok(e) => {
                        let f1 = self.loads(trial_load);
                        let r1 = residual(&e.f_int, &f1, constrained);
                        let rel1 = norm(&r1) / force_scale(&e.f_int, &f1, constrained);
                        if !met || rel1 < rel || alpha < 1.0 / 64.0 {
                            du.copy_from_slice(&trial);
                            *load = trial_load;
                            (eval, r, rel) = (e, r1, rel1);
                            break;
                        }
                    }
                    Err(e) if alpha < 1.0 / 64.0 => return Err(e),
                    // A step that would meet the constraints but inverts a quad: cut the
                    // increment (a partial step leaves them unmet, without a merit to guard).
                    Err(e) if !met => return Err(e),
                    Err(_) => {}
                }
                alpha *= 0.5;
            }
        }
        report.residuals.push(rel);
        Err(Error::Numerical(format!(
            "static Newton: relative residual {rel:.3e} after {} iterations (tolerance {tol:.1e}); \
             take smaller increments",
            report.residuals.len() - 1
        )))
    }

    /// Every quad's forces and trial state for the increment `du` (m); an inverted quad is
    /// an error.
    fn evaluate(&self, du: &[[f64; 2]]) -> Result<Evaluation> {
        let outs: Vec<_> = (0..self.model.quads.len())
            .into_par_iter()
            .map(|e| self.on_quad(e, du, increment_forces))
            .collect();
        let mut f_int = vec![[0.0; 2]; self.x.len()];
        let mut states = Vec::with_capacity(outs.len());
        for (e, (out, st)) in outs.into_iter().enumerate() {
            if out.min_jacobian.is_nan() || out.min_jacobian <= 0.0 {
                return Err(Error::Numerical(format!(
                    "static: quad {e} inverted in the increment; take smaller increments"
                )));
            }
            for (k, &i) in self.model.quads[e].iter().enumerate() {
                f_int[i as usize][0] += out.force[k][0];
                f_int[i as usize][1] += out.force[k][1];
            }
            states.push(st);
        }
        Ok(Evaluation { f_int, states })
    }

    /// Brings every quad's tangent (N/m) in `cache` to the increment `du` whose trial states
    /// are `trial`. A quad's tangent is taken again unless it was taken without plastic flow
    /// in any of its evaluations, the quad does not flow now, and its nodes have strained by
    /// at most [`TANGENT_DRIFT`] of its size since (in this increment or an earlier one): an
    /// elastic quad's tangent changes only through its geometry and stress, by about that
    /// fraction, so Newton keeps its quadratic convergence to residuals far below the
    /// tolerance, and the quads far from the contact keep theirs for many increments.
    fn refresh_tangents(&self, du: &[[f64; 2]], trial: &[QuadState], cache: &mut TangentCache) {
        let now = |e: usize| -> Quad {
            let (x0, d) = self.element_nodes(e, du);
            std::array::from_fn(|k| [x0[k][0] + d[k][0], x0[k][1] + d[k][1]])
        };
        let stale: Vec<usize> = (0..self.model.quads.len())
            .filter(|&e| {
                cache.plastic[e]
                    || trial[e].plastic_work != self.states[e].plastic_work
                    || straining_drift(&cache.taken_at[e], &now(e)) > TANGENT_DRIFT * cache.size[e]
            })
            .collect();
        let fresh: Vec<([[f64; 8]; 8], bool)> = stale
            .par_iter()
            .map(|&e| self.on_quad(e, du, increment_tangent))
            .collect();
        for (&e, (k, flowed)) in stale.iter().zip(fresh) {
            cache.blocks[e] = k;
            cache.plastic[e] = flowed;
            cache.taken_at[e] = now(e);
            cache.size[e] = characteristic_length(&cache.taken_at[e]);
        }
    }

    /// Adds nodes across the plane to the active set and releases nodes the plane pulls by
    /// more than the residual `tol` allows (relative to the largest axial nodal force);
    /// returns the numbers of nodes added and released.
    fn settle(
        &self,
        plane: ExactPlane,
        active: &mut [bool],
        du: &[[f64; 2]],
        f_int: &[[f64; 2]],
        f_ext: &[[f64; 2]],
        tol: f64,
    ) -> (usize, usize) {
        let scale = f_int
            .iter()
            .map(|f| f[1].abs())
            .fold(0.0f64, f64::max)
            .max(1e-300);
        let (mut added, mut released) = (0, 0);
        for i in 0..active.len() {
            let z = self.x[i][1] + du[i][1];
            if active[i] {
                let pressure = plane.pressure_of(f_int[i][1] - f_ext[i][1]);
                if pressure < -tol.max(1e-12) * scale {
                    active[i] = false;
                    released += 1;
                }
            } else if plane.gap(z) < -self.gap_tol {
                active[i] = true;
                added += 1;
            }
        }
        (added, released)
    }

    /// Adds to the active set the nodes the predicted increment `du` (m) carries across the
    /// plane, and puts every active node of the prediction on the plane: a node that the
    /// increment lands is then held from the first iteration, instead of found across after
    /// Newton has converged without it (a second solve from zero), and the first iteration
    /// starts from a state that meets the contact (a node the last increment landed would
    /// else be carried through the plane by its own landing).
    fn land_predicted(&self, plane: ExactPlane, active: &mut [bool], du: &mut [[f64; 2]]) {
        for (i, a) in active.iter_mut().enumerate() {
            if !*a && plane.gap(self.x[i][1] + du[i][1]) < -self.gap_tol {
                *a = true;
            }
            if *a {
                du[i][1] = plane.z - self.x[i][1];
            }
        }
    }

    fn element_nodes(&self, e: usize, du: &[[f64; 2]]) -> (Quad, Quad) {
        let q = self.model.quads[e];
        (q.map(|i| self.x[i as usize]), q.map(|i| du[i as usize]))
    }

    /// `op` (a function of [`super::element_tangent`]) on quad `e` moved by the increment
    /// `du` (m) from its committed state.
    fn on_quad<T>(&self, e: usize, du: &[[f64; 2]], op: QuadOp<T>) -> T {
        let (x0, d) = self.element_nodes(e, du);
        op(
            self.model.formulation,
            self.material(e),
            &x0,
            &d,
            &self.states[e],
        )
    }

    fn material(&self, e: usize) -> &J2Material {
        &self.model.materials[self.model.material_of[e]]
    }

    /// Numeric factorisations of the tangent so far, by this solver and every clone of it
    /// (increments cut, failed or solved again included): the loop's cost.
    pub fn factorisations(&self) -> u64 {
        self.pattern.factorisations()
    }

    /// The plane's normal force on the body, N (whole ring; 0 without a plane).
    pub fn contact_force(&self) -> f64 {
        let Some(p) = self.plane else { return 0.0 };
        let mut f = 0.0;
        for (i, &a) in self.active.iter().enumerate() {
            if a {
                let fe = self.load_factor * self.model.loads[i][1];
                f += p.pressure_of(self.f_int[i][1] - fe);
            }
        }
        f
    }

    /// The radius of the outermost node on the plane, m (0 without contact).
    pub fn contact_radius(&self) -> f64 {
        self.active
            .iter()
            .zip(&self.x)
            .filter(|(a, _)| **a)
            .map(|(_, x)| x[0])
            .fold(0.0, f64::max)
    }

    /// Nodes on the plane.
    pub fn active(&self) -> &[bool] {
        &self.active
    }

    /// The plane at the last converged increment.
    pub fn plane(&self) -> Option<ExactPlane> {
        self.plane
    }

    /// Current coordinates (r, z), m.
    pub fn positions(&self) -> &[[f64; 2]] {
        &self.x
    }

    /// Coordinates at the start, (r, z), m.
    pub fn initial_positions(&self) -> &[[f64; 2]] {
        &self.model.nodes
    }

    /// Internal nodal forces (whole rings), N.
    pub fn internal_forces(&self) -> &[[f64; 2]] {
        &self.f_int
    }

    /// Element states (stresses, plastic strains, energies).
    pub fn states(&self) -> &[QuadState] {
        &self.states
    }

    /// The load factor of the last converged increment.
    pub fn load_factor(&self) -> f64 {
        self.load_factor
    }

    /// Plastic work so far, J.
    pub fn plastic_work(&self) -> f64 {
        self.states.iter().map(|s| s.plastic_work).sum()
    }

    /// Work of the internal forces so far, J: the stress work ∫σ:dε dV (elastic + plastic)
    /// and the energy of the hourglass control.
    pub fn internal_work(&self) -> f64 {
        self.states
            .iter()
            .map(|s| s.internal_energy + s.hourglass_energy)
            .sum()
    }
}

/// f_ext − f_int flattened (N), zero on constrained degrees of freedom.
fn residual(f_int: &[[f64; 2]], f_ext: &[[f64; 2]], constrained: &[bool]) -> Vec<f64> {
    (0..2 * f_int.len())
        .map(|d| {
            if constrained[d] {
                0.0
            } else {
                f_ext[d / 2][d % 2] - f_int[d / 2][d % 2]
            }
        })
        .collect()
}

/// The force scale of a residual (N): the norm of the loads and of the reactions of the
/// constrained degrees of freedom (1 N when both vanish).
fn force_scale(f_int: &[[f64; 2]], f_ext: &[[f64; 2]], constrained: &[bool]) -> f64 {
    let mut s = 0.0;
    for d in 0..2 * f_int.len() {
        let (fi, fe) = (f_int[d / 2][d % 2], f_ext[d / 2][d % 2]);
        s += fe * fe;
        if constrained[d] {
            s += (fi - fe) * (fi - fe);
        }
    }
    if s > 0.0 {
        s.sqrt()
    } else {
        1.0
    }
}

fn norm(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The diagonal of the nodes' bounding box, m.
fn bounding_size(nodes: &[[f64; 2]]) -> f64 {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in nodes {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2)).sqrt()
}
