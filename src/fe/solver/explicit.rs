//! THE LOOP: explicit central-difference time integration, following Box 6.1 of Belytschko,
//! Liu & Moran, *Nonlinear Finite Elements for Continua and Structures* (2000). Each line of
//! [`Solver::step`] is one step of the box.
//!
//! Updated Lagrangian: positions x are current coordinates, stresses are Cauchy stresses in
//! the current frame; every array is allocated once in [`Solver::new`].

use crate::error::{EnergyGrowth, Error, Result};
use crate::fe::mass_scaling::{for_elements, hex_steps_and_masses};
use crate::fe::{
    elements::{ElementBlock, ElementFailure},
    materials::J2Material,
    model::Model,
    simd::rows::Rows4,
    simd::KernelPath,
    solver::central_difference::{self, CentralDifference},
    solver::energy::{EnergyReport, PartEnergy},
    solver::interaction::{Interaction, StepContext},
    solver::mass::element_lumped_mass,
    solver::profile::{Profile, StepPhase},
    solver::subcycle::{
        levels::LevelRule, node_force_sum, with_element_neighbours, SubcycleReport, Subcycler,
        Subcycling, AUTO_MIN_SAVING,
    },
    solver::timestep::StableStep,
    tensor::{cross, dot, inverse, Sym},
};
use rayon::prelude::*;

/// Nodes per chunk of the node loops; fixed so that partial sums never depend on threads.
const NODE_CHUNK: usize = 4096;

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// Time-step factor on the Courant limit (0 < f ≤ 1; default 0.9; the scene's
    /// `solver.time_step_factor`).
    pub time_step_factor: f64,
    /// Hourglass coefficient ε_hg of the one-point hex (0 ≤ ε ≤ 0.5; default 0.05).
    pub hourglass: f64,
    /// Fixed time step (s) instead of the Courant limit; `None` = automatic.
    pub fixed_dt: Option<f64>,
    /// Stop when the step falls below this fraction of the initial step (default 1e-3).
    pub dt_collapse: f64,
    /// Steps between Box 6.1 energy-balance checks (≥ 1; default 100).
    pub energy_interval: u64,
    /// Relative hysteresis of the automatic step (0 ≤ h < 1; default 0.05): the step taken
    /// drops as soon as the stable limit falls below it but grows only when the limit exceeds
    /// it by this fraction. A step that breathes with every vibration cycle pumps energy into
    /// the model (variable-step central differences are not symplectic).
    pub dt_hysteresis: f64,
    /// Stop when the total energy exceeds its start value plus the external work by this
    /// fraction of the start value (default 0.5): energy created from nothing means an
    /// instability, long before values turn non-finite.
    pub energy_growth: f64,
    /// Multi-time-step integration: element groups step with powers of two of the fine step
    /// (see [`crate::fe::solver::subcycle`]); default off. Ignored with `fixed_dt`.
    pub subcycling: Subcycling,
    /// Highest subcycling level: an element steps at most 2^level fine steps (1..=8; default 4).
    pub subcycle_max_level: u32,
    /// The subcycling's level rule (default [`LevelRule::HEXAHEDRA`]; others are for studies
    /// of the rule, docs/design.md §4).
    #[serde(skip)]
    pub level_rule: LevelRule,
    /// Subcycling: also hold at level 0 every node that shares an element with a node an
    /// interaction acts on (default false; for studies of the rule).
    #[serde(skip)]
    pub hold_contact_neighbours: bool,
    /// Geometrically linear (small-displacement) elements: gradients, volumes and forces are
    /// taken on the reference configuration instead of the current one (default false: large
    /// displacements and rotations). For verification against linear-elastic closed forms such
    /// as Hertz's, which neglect the change of geometry; contact still acts on the current
    /// positions. Wrong for large rotations (a rigid rotation strains the elements).
    pub linear_geometry: bool,
    /// The widest element-kernel path to use (default: the widest the CPU has); narrower
    /// paths give the same bits, slower (to measure the paths other CPUs take).
    #[serde(skip)]
    pub kernel_cap: KernelPath,
    /// Time the phases of every step ([`crate::fe::solver::profile`]; default off).
    #[serde(skip)]
    pub profile: bool,
    /// Mass-scaling budget: the added mass over the model's mass that may raise the smallest
    /// elements' steps ([`crate::fe::mass_scaling`]; 0 ≤ budget ≤ 1e-2; default 0: none).
    #[serde(skip_serializing_if = "is_zero")]
    pub mass_scaling: f64,
}

/// True for 0 (a setting at its default is not written).
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            time_step_factor: 0.9,
            hourglass: 0.05,
            fixed_dt: None,
            dt_collapse: 1e-3,
            energy_interval: 100,
            dt_hysteresis: 0.05,
            energy_growth: 0.5,
            subcycling: Subcycling::Off,
            subcycle_max_level: 4,
            level_rule: LevelRule::HEXAHEDRA,
            hold_contact_neighbours: false,
            linear_geometry: false,
            kernel_cap: KernelPath::Avx512,
            profile: false,
            mass_scaling: 0.0,
        }
    }
}

impl Settings {
    /// Checks every field, naming the bad one.
    pub fn validated(self) -> Result<Self> {
        if !(self.time_step_factor > 0.0 && self.time_step_factor <= 1.0) {
            return Err(Error::invalid(
                "solver.time_step_factor",
                self.time_step_factor,
                "0 < time_step_factor <= 1",
            ));
        }
        if !(self.hourglass >= 0.0 && self.hourglass <= 0.5) {
            return Err(Error::invalid(
                "solver.hourglass",
                self.hourglass,
                "0 <= hourglass <= 0.5",
            ));
        }
        if let Some(dt) = self.fixed_dt {
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(Error::invalid("solver.fixed_dt", dt, "dt > 0 s, finite"));
            }
        }
        if !(self.dt_collapse >= 0.0 && self.dt_collapse < 1.0) {
            return Err(Error::invalid(
                "solver.dt_collapse",
                self.dt_collapse,
                "0 <= dt_collapse < 1",
            ));
        }
        if !(self.dt_hysteresis >= 0.0 && self.dt_hysteresis < 1.0) {
            return Err(Error::invalid(
                "solver.dt_hysteresis",
                self.dt_hysteresis,
                "0 <= dt_hysteresis < 1",
            ));
        }
        if !(self.energy_growth > 0.0 && self.energy_growth.is_finite()) {
            return Err(Error::invalid(
                "solver.energy_growth",
                self.energy_growth,
                "energy_growth > 0, finite",
            ));
        }
        if !(1..=8).contains(&self.subcycle_max_level) {
            return Err(Error::invalid(
                "solver.subcycle_max_level",
                self.subcycle_max_level,
                "1 <= subcycle_max_level <= 8",
            ));
        }
        if self.energy_interval == 0 {
            return Err(Error::invalid(
                "solver.energy_interval",
                0,
                "at least 1 step",
            ));
        }
        crate::fe::mass_scaling::check_budget(self.mass_scaling)?;
        Ok(self)
    }
}

/// The explicit solver: model, interactions and the state of the central-difference loop.
pub struct Solver {
    model: Model,
    interactions: Vec<Box<dyn Interaction>>,
    settings: Settings,
    blocks: Vec<ElementBlock>,
    /// Time t^n, s.
    t: f64,
    step: u64,
    /// The step Δt^{n+1/2} to take next, s.
    dt_next: f64,
    dt_initial: f64,
    /// The step Δt^{n-1/2} just taken (0 before the first step), s.
    dt_prev: f64,
    stable: StableStep,
    x: Vec<[f64; 3]>,
    v: Vec<[f64; 3]>,
    a: Vec<[f64; 3]>,
    /// Internal nodal forces f_int, N, as [x, y, z, 0]: padded to four components so that
    /// the one-thread element loop adds each node's force with one 256-bit load, add and
    /// store (src/fe/lanes.rs `add_node_rows`; the fourth component only ever gets −0.0 added
    /// and stays 0).
    f_int: Rows4,
    f_ext: Vec<[f64; 3]>,
    mass: Vec<f64>,
    /// 1/mass per node, 1/kg: the node passes multiply by it (the same value they divided
    /// out at every step before, so the same bits).
    inv_mass: Vec<f64>,
    /// Per node: bit k set when velocity component k is held at zero.
    fixed: Vec<u8>,
    elem_force: Vec<[[f64; 3]; 8]>,
    /// Node → (element·8 + local node) incidence, CSR, in element order.
    inc_ptr: Vec<usize>,
    inc: Vec<u32>,
    w_int: f64,
    w_ext: f64,
    e0: f64,
    max_balance_error: f64,
    profile: Profile,
    /// Element updates taken (all steps, all levels).
    updates: u64,
    /// Multi-time-step bookkeeping when subcycling is in use.
    sub: Option<Subcycler>,
    /// Why subcycling is (not) in use, and what it did.
    sub_report: SubcycleReport,
    /// Subcycling: opening half-kick forces Σ 2^{k_new} f_e (`f_int` holds the closing ones).
    f_open: Vec<[f64; 3]>,
    /// Subcycling: closing accelerations M⁻¹(f_ext − f_int) (`a` holds the opening ones).
    a_close: Vec<[f64; 3]>,
    /// Number in the model given to [`Solver::new`] of each element (identity unless the
    /// elements were renumbered by subcycling level), for messages.
    original_element: Vec<usize>,
    /// Subcycling: the nodes kicked at the last step (due then); every other node has zero
    /// element force and acceleration, so the node loops visit only these.
    kicked: Vec<u32>,
    /// Subcycling: an interaction does not name its nodes, so every node is kicked (with its
    /// external force) at every step.
    every_node_kicked: bool,
    /// The element force blocks must be written by `getforce` (false once the solver is set
    /// up: the set-up of subcycling reads the first blocks, the single-rate steps do not).
    need_force_blocks: bool,
}

/// What a solver's set-up computed at t = 0 that a renumbered copy of it reuses.
struct Start {
    /// The interactions' nodal forces at t = 0, N.
    f_ext: Vec<[f64; 3]>,
    /// The first step, the one the interactions were told of, s.
    dt: f64,
}

impl Solver {
    /// Box 6.1 step 1-3: initial conditions and mass, first `getforce`, initial accelerations.
    ///
    /// With subcycling, the elements of each part are renumbered by their update level
    /// (finest first, mesh order within a level), so that every level is one contiguous run
    /// of elements and the elements due at a fine step are a prefix of each part: the lane
    /// kernel then works on full batches instead of short fragments. [`Solver::model`] is the
    /// renumbered model (element outputs follow it); error messages name elements by their
    /// number in the model given here.
    ///
    /// Fails if settings are invalid, the model is empty, an element is inverted, or the
    /// initial forces are not finite.
    pub fn new(
        model: Model,
        interactions: Vec<Box<dyn Interaction>>,
        settings: Settings,
    ) -> Result<Self> {
        let s = Self::assemble(model, interactions, settings, None)?;
        let Some(order) = s.level_order() else {
            return Ok(s);
        };
        // The renumbered solver starts from the same positions and velocities, so the
        // interactions' forces at t = 0, and the first step they were told of, are those
        // just computed: they are handed over instead of asking every interaction again,
        // which would advance its history (friction, work, force record) by a second step
        // at t = 0.
        let Solver {
            mut model,
            interactions,
            f_ext,
            dt_next,
            ..
        } = s;
        model.hexes = order.iter().map(|&e| model.hexes[e]).collect();
        let start = Start { f_ext, dt: dt_next };
        let mut s = Self::assemble(model, interactions, settings, Some(start))?;
        s.original_element = order;
        Ok(s)
    }

    /// With subcycling in use and elements not already in level order: the stable sort of
    /// each part's elements by update level (entry = old global index). `None` otherwise.
    fn level_order(&self) -> Option<Vec<usize>> {
        let sub = self.sub.as_ref()?;
        let mut order: Vec<usize> = (0..self.model.hexes.len()).collect();
        for part in &self.model.parts {
            order[part.elements.clone()].sort_by_key(|&e| sub.element_level(e));
        }
        let sorted = order.iter().enumerate().all(|(k, &e)| k == e);
        (!sorted).then_some(order)
    }

    /// [`Solver::new`] without the level renumbering. `start`: the interactions' forces at
    /// t = 0 and the first step, if already computed for this state (the interactions are
    /// then not called); `None` computes them.
    fn assemble(
        model: Model,
        interactions: Vec<Box<dyn Interaction>>,
        settings: Settings,
        start: Option<Start>,
    ) -> Result<Self> {
        let settings = settings.validated()?;
        if model.hexes.is_empty() {
            return Err(Error::invalid(
                "model",
                "0 elements",
                "at least one part with elements",
            ));
        }
        let n = model.nodes.len();
        // 1. Initial conditions and lumped mass (densities raised where mass-scaled).
        let density_scale = density_scale(&model, settings.mass_scaling)?;
        let mut mass = vec![0.0; n];
        let mut blocks = Vec::with_capacity(model.parts.len());
        for (p, part) in model.parts.iter().enumerate() {
            let conn: Vec<[u32; 8]> = model.hexes[part.elements.clone()].to_vec();
            let scale = density_scale.as_ref().map(|s| &s[p]);
            for (k, h) in conn.iter().enumerate() {
                let xe = h.map(|i| model.nodes[i as usize]);
                let rho = scale.map_or(part.material.rho, |s| part.material.rho * s[k]);
                let me = element_lumped_mass(&xe, rho).map_err(|e| {
                    Error::Numerical(format!(
                        "part {} element {}: {e}",
                        part.name,
                        part.elements.start + k
                    ))
                })?;
                for (i, m) in h.iter().zip(me) {
                    mass[*i as usize] += m;
                }
            }
            let mat = J2Material::new(&part.material, part.elastic_only);
            let mut block = ElementBlock::new(
                p,
                part.elements.start,
                conn,
                part.formulation,
                mat,
                settings.hourglass,
            );
            block.set_kernel_cap(settings.kernel_cap);
            if let Some(s) = scale {
                block.step_scale = s.iter().map(|f| f.sqrt()).collect();
            }
            blocks.push(block);
        }
        if let Some(i) = mass.iter().position(|m| m.is_nan() || *m <= 0.0) {
            return Err(Error::invalid(
                "model.nodes",
                format!("node {i} belongs to no element"),
                "every node in an element",
            ));
        }
        let mut fixed = vec![0u8; n];
        for &(node, axis) in &model.fixed {
            fixed[node as usize] |= 1 << axis;
        }
        // Node-element incidence for the deterministic gather of element forces.
        let ne = model.hexes.len();
        let mut inc_ptr = vec![0usize; n + 1];
        for h in &model.hexes {
            for &i in h {
                inc_ptr[i as usize + 1] += 1;
            }
        }
        for i in 0..n {
            inc_ptr[i + 1] += inc_ptr[i];
        }
        let mut fill = inc_ptr.clone();
        let mut inc = vec![0u32; inc_ptr[n]];
        for (e, h) in model.hexes.iter().enumerate() {
            for (l, &i) in h.iter().enumerate() {
                inc[fill[i as usize]] = (e * 8 + l) as u32;
                fill[i as usize] += 1;
            }
        }
        let mut v = model.velocity.clone();
        apply_fixed(&mut v, &fixed);
        let x = model.nodes.clone();
        let mut s = Solver {
            interactions,
            settings,
            blocks,
            t: 0.0,
            step: 0,
            dt_next: 0.0,
            dt_initial: 0.0,
            dt_prev: 0.0,
            stable: StableStep {
                dt: 0.0,
                element: None,
                interaction: None,
            },
            a: vec![[0.0; 3]; n],
            f_int: Rows4::zeros(n),
            f_ext: vec![[0.0; 3]; n],
            inv_mass: mass.iter().map(|m| 1.0 / m).collect(),
            mass,
            fixed,
            elem_force: vec![[[0.0; 3]; 8]; ne],
            inc_ptr,
            inc,
            w_int: 0.0,
            w_ext: 0.0,
            e0: 0.0,
            max_balance_error: 0.0,
            profile: Profile::new(ne, settings.profile),
            updates: 0,
            sub: None,
            sub_report: SubcycleReport::default(),
            f_open: Vec::new(),
            a_close: Vec::new(),
            original_element: (0..ne).collect(),
            kicked: Vec::new(),
            every_node_kicked: true,
            need_force_blocks: true,
            x,
            v,
            model,
        };
        // 2. getforce at t = 0 (evaluation only, Δt = 0).
        match start {
            None => s.getforce(0.0)?,
            Some(Start { f_ext, dt }) => {
                s.internal_forces_and_step(0.0)?;
                (s.f_ext, s.dt_next) = (f_ext, dt);
            }
        }
        s.dt_initial = s.dt_next;
        // 3. Accelerations a⁰ = M⁻¹(f_ext − f_int).
        s.accelerations()?;
        // Multi-time-step integration, if asked for and worth it: levels from the limits now.
        s.start_subcycling()?;
        s.need_force_blocks = false;
        s.e0 = s.energy().total;
        Ok(s)
    }

    /// Decides whether to subcycle (setting, fixed step, predicted saving) and, if so, sets
    /// up the levels and replaces the first accelerations by the level-weighted kicks.
    fn start_subcycling(&mut self) -> Result<()> {
        let why_not = match self.settings.subcycling {
            Subcycling::Off => Some("off (setting)".to_string()),
            _ if self.settings.fixed_dt.is_some() => Some("off: fixed time step".to_string()),
            _ => None,
        };
        if let Some(reason) = why_not {
            self.sub_report.reason = reason;
            return Ok(());
        }
        let mut pinned = vec![false; self.x.len()];
        for it in &self.interactions {
            for &i in it.active_nodes().unwrap_or(&[]) {
                pinned[i as usize] = true;
            }
        }
        if self.settings.hold_contact_neighbours {
            pinned = with_element_neighbours(&self.blocks, &pinned);
        }
        let contact_dt = self.contact_limits();
        let mut sub = Subcycler::new(
            &self.blocks,
            &self.x,
            &pinned,
            &contact_dt,
            self.settings.level_rule,
            self.settings.time_step_factor,
            self.dt_next,
            self.settings.subcycle_max_level,
        );
        let saving = sub.report().predicted_saving;
        if self.settings.subcycling == Subcycling::Auto && saving < AUTO_MIN_SAVING {
            self.sub_report = sub.report().clone();
            self.sub_report.used = false;
            self.sub_report.reason =
                format!("off: predicted saving {saving:.2}x below {AUTO_MIN_SAVING}x");
            return Ok(());
        }
        let n = self.x.len();
        self.f_open = vec![[0.0; 3]; n];
        self.a_close = vec![[0.0; 3]; n];
        // Node loops may skip nodes not due only if every interaction names the nodes it
        // acts on (those are held at level 0, so due at every step).
        self.every_node_kicked = self
            .interactions
            .iter()
            .any(|it| it.active_nodes().is_none());
        self.kicked = (0..n as u32).collect();
        self.gather_kicked(&mut sub);
        self.sub = Some(sub);
        self.kick_accelerations()
    }

    /// Gathers the element forces of the kicked nodes into their closing (`f_int`) and
    /// opening (`f_open`) internal forces, N ([`Subcycler::gather_kicks`]).
    fn gather_kicked(&mut self, sub: &mut Subcycler) {
        sub.gather_kicks(
            &self.kicked,
            &self.inc_ptr,
            &self.inc,
            &self.elem_force,
            &mut self.f_int,
            &mut self.f_open,
        );
    }

    /// One time step n → n+1, Box 6.1 steps 4-12 ([`central_difference::step`]). With
    /// subcycling (module [`crate::fe::solver::subcycle`]) the half-kicks split into closing
    /// and opening parts: elements due now act with the weight 2^k of their own step, the
    /// others not at all until their next update.
    pub fn step(&mut self) -> Result<()> {
        central_difference::step(self)
    }

    /// Box 6.1 step 11 for a step of `dt` (s): the work of the internal and external forces
    /// by the trapezoid of their powers (W) at its start `old` and end `new`, the step count,
    /// then the energy balance check.
    fn close_step(&mut self, dt: f64, old: (f64, f64), new: (f64, f64)) -> Result<()> {
        self.w_int += 0.5 * dt * (old.0 + new.0);
        self.w_ext += 0.5 * dt * (old.1 + new.1);
        self.step += 1;
        self.dt_prev = dt;
        self.energy_check()
    }

    /// Box 6.1 step 11: records the balance error and stops when energy is created.
    fn energy_check(&mut self) -> Result<()> {
        self.profile.lap(StepPhase::Nodal);
        if self.step.is_multiple_of(self.settings.energy_interval) {
            let e = self.energy();
            self.max_balance_error = self.max_balance_error.max(e.balance_error);
            // Energy created beyond the external work: kinetic + stored + dissipated above
            // the start value (external work subtracted, so never a false alarm).
            let created = (e.total - self.e0 - self.w_ext.max(0.0)) / self.e0;
            if self.e0 > 0.0 && created > self.settings.energy_growth {
                return Err(self.energy_growth_error(created));
            }
        }
        self.profile.lap(StepPhase::Energy);
        self.profile.end_step(Some(self.updates));
        Ok(())
    }

    /// `getforce` with subcycling at x^{n+1}: the elements due now (each with its own step
    /// and mean velocities over it), the stable limits, the levels and fine step for the
    /// next interval, the level-weighted kick forces, then the interactions (every step).
    fn getforce_subcycled(&mut self, dt: f64) -> Result<()> {
        let mut sub = self.sub.take().expect("subcycling in use");
        let res = self.getforce_with(&mut sub, dt);
        self.sub = Some(sub);
        res
    }

    fn getforce_with(&mut self, sub: &mut Subcycler, dt: f64) -> Result<()> {
        sub.advance(dt);
        let xg = if self.settings.linear_geometry {
            &self.model.nodes
        } else {
            &self.x
        };
        let done =
            sub.update_due_elements(&mut self.blocks, xg, &self.x, &self.v, &mut self.elem_force);
        self.updates += done.map_err(|(e, why)| self.element_error(e, why))?;
        self.profile.lap(StepPhase::Elements);
        // Critical steps: every element's latest Courant limit, and the interactions.
        let best = sub.smallest_limit(&self.blocks);
        self.stable = self.stable_limit(best);
        let interaction_limit = match self.stable.interaction {
            Some(_) => self.stable.dt,
            None => f64::INFINITY,
        };
        let stable_dt = self.stable.dt;
        let h = sub.choose_levels(
            &self.blocks,
            &self.x,
            self.settings.time_step_factor,
            dt,
            interaction_limit,
            || self.contact_limits(),
            |h_taken| self.next_step(h_taken, stable_dt),
        );
        self.dt_next = h;
        self.check_collapse()?;
        self.profile.lap(StepPhase::StableStep);
        // The nodes kicked last step go back to zero force and acceleration; the nodes due
        // now (every node if an interaction may act anywhere) are gathered and kicked.
        for &i in &self.kicked {
            let i = i as usize;
            self.f_int[i] = [0.0; 4];
            self.f_open[i] = [0.0; 3];
            self.a[i] = [0.0; 3];
            self.a_close[i] = [0.0; 3];
        }
        if !self.every_node_kicked {
            self.kicked.clear();
            self.kicked.extend_from_slice(sub.due_nodes());
        }
        self.gather_kicked(sub);
        self.profile.lap(StepPhase::Gather);
        self.external_forces()
    }

    /// Subcycling, Box 6.1 steps 5-7: v += (Δt/2) a (opening accelerations) and the
    /// velocity constraints at the nodes kicked last step (elsewhere a = 0), the power (W)
    /// of the opening internal forces `f_open` and of `f_ext` there (zero elsewhere), then
    /// x += Δt v at every node. Returns (internal, external) power, summed in the order of
    /// the kicked list (thread-count independent).
    fn open_kick_and_drift(&mut self, dt: f64) -> (f64, f64) {
        let h = 0.5 * dt;
        let (mut pi, mut pe) = (0.0, 0.0);
        for &n in &self.kicked {
            let n = n as usize;
            let v = &mut self.v[n];
            let (a, fx) = (self.a[n], self.fixed[n]);
            for d in 0..3 {
                v[d] += h * a[d];
                if fx & (1 << d) != 0 {
                    v[d] = 0.0;
                }
            }
            let (fi, fe) = (self.f_open[n], self.f_ext[n]);
            pi += dot(*v, fi);
            pe += dot(*v, fe);
        }
        self.update_positions(dt);
        (pi, pe)
    }

    /// Subcycling, Box 6.1 steps 9-10 at the nodes due now (the kicked list): opening
    /// accelerations M⁻¹(f_ext − f_open) into `a`, closing ones M⁻¹(f_ext − f_int) into
    /// `a_close` (zero on constrained components), the power (W) of `f_int` and `f_ext` at
    /// v^{n+1/2}, then v += (Δt/2) a_close. Returns (internal, external) power, or the error
    /// for the first listed node with a non-finite acceleration.
    fn accelerate_and_close_kick(&mut self, dt: f64) -> Result<(f64, f64)> {
        let h = 0.5 * dt;
        let (mut pi, mut pe) = (0.0, 0.0);
        for &n in &self.kicked {
            let n = n as usize;
            let (fo, fi, fe) = (self.f_open[n], xyz(self.f_int[n]), self.f_ext[n]);
            let (r, fx) = (self.inv_mass[n], self.fixed[n]);
            let (mut ao, mut ac) = ([0.0; 3], [0.0; 3]);
            for d in 0..3 {
                if fx & (1 << d) == 0 {
                    ao[d] = (fe[d] - fo[d]) * r;
                    ac[d] = (fe[d] - fi[d]) * r;
                }
            }
            if !ao.iter().chain(&ac).all(|x| x.is_finite()) {
                return Err(self.non_finite_error(n));
            }
            let v = &mut self.v[n];
            pi += dot(*v, fi);
            pe += dot(*v, fe);
            for d in 0..3 {
                v[d] += h * ac[d];
                if fx & (1 << d) != 0 {
                    v[d] = 0.0;
                }
            }
            (self.a[n], self.a_close[n]) = (ao, ac);
        }
        Ok((pi, pe))
    }

    /// Subcycling: opening accelerations into `a`, closing ones into `a_close`.
    fn kick_accelerations(&mut self) -> Result<()> {
        let (fe, inv_m, fx) = (&self.f_ext, &self.inv_mass, &self.fixed);
        let bad = accelerations_into(&mut self.a, &self.f_open, fe, inv_m, fx).or(
            accelerations_into(&mut self.a_close, &self.f_int, fe, inv_m, fx),
        );
        match bad {
            Some(n) => Err(self.non_finite_error(n)),
            None => Ok(()),
        }
    }

    /// Steps until `stop(self)` returns true (checked before every step).
    pub fn run_until(&mut self, mut stop: impl FnMut(&Solver) -> bool) -> Result<()> {
        while !stop(self) {
            self.step()?;
        }
        Ok(())
    }

    /// Box 6.1 `getforce` at the current x = x^{n+1}, v = v^{n+1/2}: element loop (gather,
    /// deformation, constitutive update, internal forces, scatter), critical time step, then
    /// every interaction's external forces for the step about to be taken.
    fn getforce(&mut self, dt: f64) -> Result<()> {
        self.internal_forces_and_step(dt)?;
        // External forces from interactions (contact, walls) at t^{n+1}.
        self.external_forces()
    }

    /// `getforce` without the interactions' forces: element loop, internal nodal forces and
    /// the stable step for the next step.
    fn internal_forces_and_step(&mut self, dt: f64) -> Result<()> {
        let mut best = (f64::INFINITY, usize::MAX);
        // Element geometry: current positions, or the reference ones (linear geometry).
        let xg = if self.settings.linear_geometry {
            &self.model.nodes
        } else {
            &self.x
        };
        // On one thread the elements add their forces straight into f_int (same sums in the
        // same order as the force blocks gathered per node, without the blocks' memory
        // traffic); on more, each writes its block and the nodes gather them afterwards. The
        // first call, in `new`, always writes the blocks: subcycling's set-up reads them.
        let direct = rayon::current_num_threads() == 1 && !self.need_force_blocks;
        if direct {
            self.f_int.fill([0.0; 4]);
        }
        for b in &mut self.blocks {
            let range = b.first..b.first + b.conn.len();
            let done = if direct {
                b.update_range_into_nodes(0..b.conn.len(), xg, &self.v, dt, &mut self.f_int)
            } else {
                b.update(xg, &self.v, dt, &mut self.elem_force[range])
            };
            match done {
                Ok(d) => {
                    if d.0 < best.0 {
                        best = d;
                    }
                }
                Err((e, why)) => return Err(self.element_error(e, why)),
            }
        }
        self.profile.lap(StepPhase::Elements);
        if !direct {
            self.gather_internal_forces();
        }
        self.profile.lap(StepPhase::Gather);
        // Critical time step: elements (Courant) and interactions.
        self.stable = self.stable_limit(best);
        self.dt_next = self.next_step(self.dt_next, self.stable.dt);
        self.check_collapse()?;
        self.profile.lap(StepPhase::StableStep);
        Ok(())
    }

    /// The error for a failed element `e` (global index).
    fn element_error(&self, e: usize, why: ElementFailure) -> Error {
        let (b, _) = self.locate(e);
        let part = &self.model.parts[self.blocks[b].part].name;
        let cause = match why {
            ElementFailure::Inverted(j) => format!(
                "inverted (Jacobian {j:.3e}): excessive deformation, time step too large or hourglassing"
            ),
            ElementFailure::NonFinite => "non-finite internal force: instability".to_string(),
        };
        Error::Numerical(format!(
            "element {} (part {part}) at t = {:.6e} s, step {}: {cause}",
            self.original_element[e], self.t, self.step
        ))
    }

    /// The stable step (time-step factor included) from the smallest element Courant limit `best`
    /// (s, global element) and every interaction's limit.
    fn stable_limit(&self, best: (f64, usize)) -> StableStep {
        let mut stable = StableStep {
            dt: self.settings.time_step_factor * best.0,
            element: Some(best.1),
            interaction: None,
        };
        for (k, it) in self.interactions.iter().enumerate() {
            if let Some(d) = it.stable_time_step(&self.mass, &[]) {
                let d = self.settings.time_step_factor * d;
                if d < stable.dt {
                    stable = StableStep {
                        dt: d,
                        element: None,
                        interaction: Some(k),
                    };
                }
            }
        }
        stable
    }

    /// Each node's contact limit (s): the smallest stable step the interactions' springs allow
    /// it ([`Interaction::node_limits`]); ∞ where none acts.
    fn contact_limits(&self) -> Vec<f64> {
        let mut dt = vec![f64::INFINITY; self.x.len()];
        for it in &self.interactions {
            for (i, d) in it.node_limits(&self.mass, &[]) {
                dt[i] = dt[i].min(d);
            }
        }
        dt
    }

    /// The step to take after `dt` given the stable step `stable` (s): the fixed step, or
    /// `stable` with the growth hysteresis.
    fn next_step(&self, dt: f64, stable: f64) -> f64 {
        match self.settings.fixed_dt {
            Some(f) => f,
            None if dt > 0.0
                && stable >= dt
                && stable <= dt * (1.0 + self.settings.dt_hysteresis) =>
            {
                dt
            }
            None => stable,
        }
    }

    /// Stops when the step is not positive and finite, or collapsed below `dt_collapse` of
    /// the initial step.
    fn check_collapse(&self) -> Result<()> {
        if !(self.dt_next > 0.0 && self.dt_next.is_finite())
            || (self.dt_initial > 0.0 && self.dt_next < self.settings.dt_collapse * self.dt_initial)
        {
            return Err(Error::Numerical(format!(
                "time step collapsed to {:.3e} s (initial {:.3e} s) at t = {:.6e} s, controlled by {}: \
                 an element is being crushed or an interaction is too stiff",
                self.dt_next,
                self.dt_initial,
                self.t,
                self.controlling()
            )));
        }
        Ok(())
    }

    /// Every interaction's forces at t^{n+1} for the step about to be taken.
    fn external_forces(&mut self) -> Result<()> {
        for f in &mut self.f_ext {
            *f = [0.0; 3];
        }
        let ctx = StepContext {
            t: self.t,
            dt: self.dt_next,
            x: &self.x,
            v: &self.v,
            mass: &self.mass,
        };
        for it in &mut self.interactions {
            it.add_forces(&ctx, &mut self.f_ext)?;
        }
        self.profile.lap(StepPhase::Contact);
        Ok(())
    }

    /// Scatter: f_int at each node = Σ of its elements' force blocks, in element order.
    fn gather_internal_forces(&mut self) {
        let ef = &self.elem_force;
        let ptr = &self.inc_ptr;
        let inc = &self.inc;
        self.f_int
            .par_chunks_mut(NODE_CHUNK)
            .enumerate()
            .for_each(|(c, fs)| {
                for (k, f) in fs.iter_mut().enumerate() {
                    let g = node_force_sum(ptr, inc, ef, c * NODE_CHUNK + k);
                    *f = [g[0], g[1], g[2], 0.0];
                }
            });
    }

    /// a = M⁻¹ (f_ext − f_int), zero on constrained components; fails on non-finite values.
    fn accelerations(&mut self) -> Result<()> {
        let bad = accelerations_into(
            &mut self.a,
            &self.f_int,
            &self.f_ext,
            &self.inv_mass,
            &self.fixed,
        );
        match bad {
            Some(n) => Err(self.non_finite_error(n)),
            None => Ok(()),
        }
    }

    fn non_finite_error(&self, n: usize) -> Error {
        Error::Numerical(format!(
            "node {n} has a non-finite acceleration at t = {:.6e} s, step {}: force blew up \
             (unstable time step or interaction)",
            self.t, self.step
        ))
    }

    /// Box 6.1 steps 5-7 of a single-rate step, fused into one pass over the nodes (each
    /// node's arithmetic is that of the separate steps): v += (Δt/2) a, zero constrained
    /// velocity components, x += Δt v. Returns the power (W) of f_int and f_ext at the new
    /// velocities, summed in fixed chunks (thread-count independent).
    fn kick_and_drift(&mut self, dt: f64) -> (f64, f64) {
        let h = 0.5 * dt;
        let (a, fixed, f_int, f_ext) = (&self.a, &self.fixed, &self.f_int, &self.f_ext);
        let parts: Vec<(f64, f64)> = self
            .v
            .par_chunks_mut(NODE_CHUNK)
            .zip(self.x.par_chunks_mut(NODE_CHUNK))
            .zip(a.par_chunks(NODE_CHUNK))
            .zip(fixed.par_chunks(NODE_CHUNK))
            .zip(f_int.par_chunks(NODE_CHUNK))
            .zip(f_ext.par_chunks(NODE_CHUNK))
            .map(|(((((vs, xs), acc), fxs), fis), fes)| {
                let (mut pi, mut pe) = (0.0, 0.0);
                let nodes = vs.iter_mut().zip(xs.iter_mut()).zip(acc).zip(fxs);
                for ((((v, x), a), &fx), (fi, fe)) in nodes.zip(fis.iter().zip(fes)) {
                    for d in 0..3 {
                        v[d] += h * a[d];
                    }
                    fix_node(v, fx);
                    pi += dot(*v, xyz(*fi));
                    pe += dot(*v, *fe);
                    for d in 0..3 {
                        x[d] += dt * v[d];
                    }
                }
                (pi, pe)
            })
            .collect();
        parts.iter().fold((0.0, 0.0), |s, p| (s.0 + p.0, s.1 + p.1))
    }

    /// Box 6.1 steps 9-10 of a single-rate step, fused into one pass over the nodes:
    /// a = M⁻¹ (f_ext − f_int) (zero on constrained components), the power (W) of f_int and
    /// f_ext at v^{n+1/2} (summed in fixed chunks), v += (Δt/2) a, constrained components
    /// zeroed. Fails on the lowest node with a non-finite acceleration.
    fn accelerate_and_kick(&mut self, dt: f64) -> Result<(f64, f64)> {
        let h = 0.5 * dt;
        let (inv_m, fixed, f_int, f_ext) = (&self.inv_mass, &self.fixed, &self.f_int, &self.f_ext);
        let parts: Vec<std::result::Result<(f64, f64), usize>> = self
            .a
            .par_chunks_mut(NODE_CHUNK)
            .zip(self.v.par_chunks_mut(NODE_CHUNK))
            .zip(inv_m.par_chunks(NODE_CHUNK))
            .zip(fixed.par_chunks(NODE_CHUNK))
            .zip(f_int.par_chunks(NODE_CHUNK))
            .zip(f_ext.par_chunks(NODE_CHUNK))
            .enumerate()
            .map(|(c, (((((acc, vs), rs), fxs), fis), fes))| {
                let (mut pi, mut pe) = (0.0, 0.0);
                let nodes = acc.iter_mut().zip(vs.iter_mut()).zip(rs).zip(fxs);
                for (k, ((((a, v), &r), &fx), (fi, fe))) in
                    nodes.zip(fis.iter().zip(fes)).enumerate()
                {
                    let fi = xyz(*fi);
                    for d in 0..3 {
                        a[d] = if fx & (1 << d) != 0 {
                            0.0
                        } else {
                            (fe[d] - fi[d]) * r
                        };
                    }
                    if !a.iter().all(|c| c.is_finite()) {
                        return Err(c * NODE_CHUNK + k);
                    }
                    pi += dot(*v, fi);
                    pe += dot(*v, *fe);
                    for d in 0..3 {
                        v[d] += h * a[d];
                    }
                    fix_node(v, fx);
                }
                Ok((pi, pe))
            })
            .collect();
        let mut sum = (0.0, 0.0);
        for p in parts {
            match p {
                Ok((pi, pe)) => sum = (sum.0 + pi, sum.1 + pe),
                // Chunks are in node order: the first failing chunk holds the lowest node.
                Err(n) => return Err(self.non_finite_error(n)),
            }
        }
        Ok(sum)
    }

    fn update_positions(&mut self, dt: f64) {
        self.x
            .par_iter_mut()
            .zip(self.v.par_iter())
            .with_min_len(NODE_CHUNK)
            .for_each(|(x, v)| {
                x[0] += dt * v[0];
                x[1] += dt * v[1];
                x[2] += dt * v[2];
            });
    }

    /// The stop for energy created by the integration (`created`, a fraction of the start
    /// energy): the fastest node (where an instability shows first), the time and what
    /// controls the step, as numbers.
    fn energy_growth_error(&self, created: f64) -> Error {
        let fastest_node = self
            .v
            .iter()
            .enumerate()
            .map(|(i, v)| (i, (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()))
            .fold((0, -1.0), |a, b| if b.1 > a.1 { b } else { a });
        Error::EnergyGrowth(Box::new(EnergyGrowth {
            created,
            limit: self.settings.energy_growth,
            time: self.t,
            step: self.step,
            fastest_node,
            controlled_by: self.controlling(),
        }))
    }

    fn controlling(&self) -> String {
        match (self.stable.element, self.stable.interaction) {
            (_, Some(k)) => format!("interaction '{}'", self.interactions[k].name()),
            (Some(e), _) => format!("element {e}"),
            _ => "nothing".into(),
        }
    }

    /// The energy report now (kinetic from v^n, elastic from current stresses).
    pub fn energy(&self) -> EnergyReport {
        let mut parts: Vec<PartEnergy> = Vec::with_capacity(self.model.parts.len());
        for (p, part) in self.model.parts.iter().enumerate() {
            let mut pe = PartEnergy {
                name: part.name.clone(),
                ..Default::default()
            };
            // Central-difference kinetic energy ½ v^{n−1/2}·M v^{n+1/2}
            // = ½ M (|v^n|² − Δt^{n−1/2} Δt^{n+1/2}/4 |a^n|²): with it the discrete energy of
            // a linear elastic system is conserved exactly by the central-difference scheme;
            // ½ M |v^n|² oscillates about it by O((ω Δt)²/8).
            let c = 0.25 * self.dt_prev * self.dt_next;
            for n in part.nodes.clone() {
                let (v, a) = (self.v[n], self.a[n]);
                let vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
                let aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
                pe.energy.kinetic_central += 0.5 * self.mass[n] * (vv - c * aa);
                pe.energy.kinetic += 0.5 * self.mass[n] * vv;
            }
            if self.sub.is_some() && self.dt_prev > 0.0 {
                // Subcycling: the closing and opening kicks differ where an element changed
                // level, so v^{n∓1/2} = v^n ∓ (Δt^{n∓1/2}/2) a_close/open, each exactly.
                pe.energy.kinetic_central = 0.0;
                let (hm, hp) = (0.5 * self.dt_prev, 0.5 * self.dt_next);
                for n in part.nodes.clone() {
                    let (v, ao, ac) = (self.v[n], self.a[n], self.a_close[n]);
                    let vm = [0, 1, 2].map(|d| v[d] - hm * ac[d]);
                    let vp = [0, 1, 2].map(|d| v[d] + hp * ao[d]);
                    pe.energy.kinetic_central +=
                        0.5 * self.mass[n] * (vm[0] * vp[0] + vm[1] * vp[1] + vm[2] * vp[2]);
                }
            }
            if let Some(sub) = &self.sub {
                // Elements between their updates: the work done on them since.
                pe.energy.internal += sub.pending_work(&self.blocks, &self.x, &self.elem_force)[p];
            }
            let b = &self.blocks[p];
            for k in 0..b.conn.len() {
                pe.energy.internal += b.internal_energy[k];
                pe.energy.elastic_from_stress += b.element_elastic_energy(k);
                pe.energy.plastic += b.plastic_work[k];
            }
            // Empty for a formulation without hourglass modes.
            for e in &b.hourglass_energy {
                pe.energy.hourglass += e;
            }
            pe.energy.elastic = pe.energy.internal - pe.energy.plastic;
            parts.push(pe);
        }
        let mut r = EnergyReport {
            time: self.t,
            step: self.step,
            ..Default::default()
        };
        for pe in &parts {
            r.solid.add(&pe.energy);
        }
        for it in &self.interactions {
            let e = it.energy();
            r.interaction_stored += e.stored;
            r.interaction_dissipated += e.dissipated;
            r.interaction_work += e.work;
        }
        r.internal_work = self.w_int;
        r.external_work = self.w_ext;
        r.total = r.solid.kinetic_central
            + r.solid.internal
            + r.solid.hourglass
            + r.interaction_stored
            + r.interaction_dissipated;
        r.initial_total = if self.step == 0 && self.e0 == 0.0 {
            r.total
        } else {
            self.e0
        };
        r.energy_ratio = if r.initial_total > 0.0 {
            r.total / r.initial_total
        } else {
            1.0
        };
        let e0 = r.initial_total;
        let scale = r
            .solid
            .kinetic
            .max(self.w_int.abs())
            .max(self.w_ext.abs())
            .max(e0);
        r.balance_error = if scale > 0.0 {
            (r.solid.kinetic_central + self.w_int - self.w_ext - e0).abs() / scale
        } else {
            0.0
        };
        r.max_balance_error = self.max_balance_error.max(r.balance_error);
        r.parts = parts;
        r
    }

    /// Centre-of-mass velocity (m/s) and angular velocity (rad/s) of part `p` from its linear
    /// and angular momentum: v_cm = Σ m v / Σ m, ω = I⁻¹ L about the centre of mass.
    pub fn part_motion(&self, p: usize) -> Result<([f64; 3], [f64; 3])> {
        let range = self.model.part(p)?.nodes.clone();
        let (mut m, mut mx, mut mv) = (0.0, [0.0; 3], [0.0; 3]);
        for n in range.clone() {
            m += self.mass[n];
            for k in 0..3 {
                mx[k] += self.mass[n] * self.x[n][k];
                mv[k] += self.mass[n] * self.v[n][k];
            }
        }
        let xc = mx.map(|c| c / m);
        let vc = mv.map(|c| c / m);
        let mut l = [0.0; 3];
        let mut inertia = [[0.0; 3]; 3];
        for n in range {
            let r = [0, 1, 2].map(|k| self.x[n][k] - xc[k]);
            let u = [0, 1, 2].map(|k| self.v[n][k] - vc[k]);
            let h = cross(r, u);
            let rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
            for i in 0..3 {
                l[i] += self.mass[n] * h[i];
                for j in 0..3 {
                    inertia[i][j] += self.mass[n] * (if i == j { rr } else { 0.0 } - r[i] * r[j]);
                }
            }
        }
        let (inv, det) = inverse(&inertia);
        let omega = if det > 0.0 {
            crate::fe::tensor::mat_vec(&inv, l)
        } else {
            [0.0; 3]
        };
        Ok((vc, omega))
    }

    /// Time t^n, s.
    pub fn time(&self) -> f64 {
        self.t
    }
    /// Steps taken (fine steps with subcycling).
    pub fn step_count(&self) -> u64 {
        self.step
    }
    /// Element updates taken so far (elements × steps without subcycling; fewer with it).
    pub fn element_updates(&self) -> u64 {
        self.updates
    }
    /// Whether subcycling is in use, why, and what it did so far.
    pub fn subcycling(&self) -> SubcycleReport {
        match &self.sub {
            Some(s) => {
                let mut r = s.report().clone();
                r.reason = format!("on: predicted saving {:.2}x", r.predicted_saving);
                r
            }
            None => self.sub_report.clone(),
        }
    }
    /// With subcycling: the largest ratio of a node's own step to the Courant limit (no
    /// safety factor) of its elements; above 1 it would be unstable. 0 without subcycling.
    pub fn subcycle_step_ratio(&self) -> f64 {
        self.sub.as_ref().map_or(0.0, |s| {
            s.worst_step_ratio(&self.blocks, &self.inc_ptr, &self.inc, self.dt_next)
        })
    }
    /// The subcycling update level of global element `e` (0 without subcycling).
    pub fn element_level(&self, e: usize) -> u32 {
        self.sub.as_ref().map_or(0, |s| s.element_level(e))
    }
    /// The step Δt that the next call to [`Solver::step`] will take, s (never above the stable
    /// limit [`Solver::stable_step`] unless `fixed_dt` is set).
    pub fn dt(&self) -> f64 {
        self.dt_next
    }
    /// The current stable-step limit and what controls it.
    pub fn stable_step(&self) -> StableStep {
        self.stable
    }
    /// Current nodal coordinates x^n, m.
    pub fn x(&self) -> &[[f64; 3]] {
        &self.x
    }
    /// Nodal velocities v^n, m/s.
    pub fn v(&self) -> &[[f64; 3]] {
        &self.v
    }
    /// Lumped nodal masses, kg.
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }
    /// Internal nodal forces at t^n, N, as [x, y, z, 0] per node (padded, see the field).
    pub fn internal_forces(&self) -> &[[f64; 4]] {
        &self.f_int
    }
    /// The model.
    pub fn model(&self) -> &Model {
        &self.model
    }
    /// The interactions.
    pub fn interactions(&self) -> &[Box<dyn Interaction>] {
        &self.interactions
    }
    /// The settings in use.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }
    /// Mean Cauchy stress of global element `e` (Pa, Voigt [xx, yy, zz, xy, yz, zx]).
    pub fn element_stress(&self, e: usize) -> Sym {
        let (b, k) = self.locate(e);
        self.blocks[b].element_stress(k)
    }
    /// Mean equivalent plastic strain of global element `e`.
    pub fn element_plastic_strain(&self, e: usize) -> f64 {
        let (b, k) = self.locate(e);
        self.blocks[b].element_eps_p(k)
    }
    /// Plastic work dissipated in global element `e`, J.
    pub fn element_plastic_work(&self, e: usize) -> f64 {
        let (b, k) = self.locate(e);
        self.blocks[b].plastic_work[k]
    }
    /// The phase timer (on when [`Settings::profile`] is).
    pub fn profile(&self) -> &Profile {
        &self.profile
    }
    /// Element blocks (one per part), for output and benchmarks.
    pub fn blocks(&self) -> &[ElementBlock] {
        &self.blocks
    }

    fn locate(&self, e: usize) -> (usize, usize) {
        let b = self
            .blocks
            .iter()
            .position(|b| e >= b.first && e < b.first + b.conn.len())
            .expect("element index in range");
        (b, e - self.blocks[b].first)
    }
}

/// The density factors of the elements of each part of `model` (part by part, in the
/// order of the part's elements) within the mass-scaling `budget`
/// ([`crate::fe::mass_scaling`]), `None` for a budget of 0 (no element touched).
fn density_scale(model: &Model, budget: f64) -> Result<Option<Vec<Vec<f64>>>> {
    if budget == 0.0 {
        return Ok(None);
    }
    let mut sm = Vec::with_capacity(model.hexes.len());
    for part in &model.parts {
        let m = part.material;
        sm.extend(hex_steps_and_masses(
            &model.nodes,
            &model.hexes[part.elements.clone()],
            |_| m.dilatational_wave_speed(),
            |_| m.rho,
        )?);
    }
    let scale = for_elements(&sm, budget, "model.hexes")?.scale;
    let mut rest = scale.as_slice();
    let mut per_part = Vec::with_capacity(model.parts.len());
    for part in &model.parts {
        let (this, next) = rest.split_at(part.elements.len());
        per_part.push(this.to_vec());
        rest = next;
    }
    Ok(Some(per_part))
}

/// The 3D model's phases: single rate, or subcycled by element levels.
impl CentralDifference for Solver {
    /// The powers of the internal and external forces (W) at the step's start and end.
    type Carry = [(f64, f64); 2];

    fn time_update(&mut self) -> f64 {
        self.profile.lap(StepPhase::Outside);
        self.dt_next
    }

    /// One pass over the nodes (subcycled: the opening half-kick M⁻¹(f_ext − Σ 2^{k_new}
    /// f_e)^n of the nodes kicked last step), the power of f^n at v^{n+1/2} (step 11's first
    /// trapezoid end), then the drift of every node.
    fn first_partial_update(&mut self, dt: f64) -> Self::Carry {
        let t_new = self.t + dt;
        let old = if self.sub.is_some() {
            self.open_kick_and_drift(dt)
        } else {
            self.kick_and_drift(dt)
        };
        self.t = t_new;
        self.profile.lap(StepPhase::Nodal);
        [old, (0.0, 0.0)]
    }

    /// Element loop (subcycled: the elements due now, with their own steps), interactions,
    /// critical time step.
    fn get_forces(&mut self, dt: f64, carry: Self::Carry) -> Result<Self::Carry> {
        if self.sub.is_some() {
            self.getforce_subcycled(dt)?;
        } else {
            self.getforce(dt)?;
            self.updates += self.model.hexes.len() as u64;
        }
        Ok(carry)
    }

    /// One pass over the nodes (subcycled: those due now, with closing and opening
    /// accelerations of Σ 2^k f_e), with the power of f^{n+1} at v^{n+1/2} taken before the
    /// velocity moves on.
    fn second_partial_update(&mut self, dt: f64, carry: Self::Carry) -> Result<Self::Carry> {
        let new = if self.sub.is_some() {
            self.accelerate_and_close_kick(dt)?
        } else {
            self.accelerate_and_kick(dt)?
        };
        Ok([carry[0], new])
    }

    fn energy_balance(&mut self, dt: f64, carry: Self::Carry) -> Result<()> {
        self.close_step(dt, carry[0], carry[1])
    }
}

/// a = M⁻¹ (f_ext − f_int) into `out` (`inv_m`: 1/mass per node, 1/kg), zero on constrained
/// components; returns the lowest node with a non-finite value, if any.
fn accelerations_into<const N: usize>(
    out: &mut [[f64; 3]],
    fi: &[[f64; N]],
    fe: &[[f64; 3]],
    inv_m: &[f64],
    fx: &[u8],
) -> Option<usize> {
    out.par_chunks_mut(NODE_CHUNK)
        .enumerate()
        .map(|(c, a)| {
            for (k, ak) in a.iter_mut().enumerate() {
                let n = c * NODE_CHUNK + k;
                let r = inv_m[n];
                for d in 0..3 {
                    ak[d] = if fx[n] & (1 << d) != 0 {
                        0.0
                    } else {
                        (fe[n][d] - fi[n][d]) * r
                    };
                }
                if !ak.iter().all(|v| v.is_finite()) {
                    return Some(n);
                }
            }
            None
        })
        .reduce(
            || None,
            |a, b| match (a, b) {
                (Some(x), Some(y)) => Some(x.min(y)),
                (x, None) => x,
                (None, y) => y,
            },
        )
}

fn apply_fixed(v: &mut [[f64; 3]], fixed: &[u8]) {
    for (vi, &f) in v.iter_mut().zip(fixed) {
        fix_node(vi, f);
    }
}

/// Zeroes the velocity components of one node that its constraint bits `f` fix.
#[inline(always)]
fn fix_node(v: &mut [f64; 3], f: u8) {
    if f != 0 {
        for (d, c) in v.iter_mut().enumerate() {
            if f & (1 << d) != 0 {
                *c = 0.0;
            }
        }
    }
}

/// The x, y, z components of a padded nodal vector ([`Solver`]'s `f_int` rows).
#[inline(always)]
fn xyz(p: [f64; 4]) -> [f64; 3] {
    [p[0], p[1], p[2]]
}
