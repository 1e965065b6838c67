//! Multi-time-step integration (subcycling) of the meridian model by nodal partition
//! (Belytschko, Yen & Mullen 1979), the scheme of the 3D solver in its simplest aligned form:
//! power-of-two step classes fixed over a cycle of 2^top fine steps.
//!
//! With fine step h, node i has level L_i (step 2^{L_i} h), the largest k ≤ K with
//! 2^k h ≤ s Δt_i, where s is the step factor and Δt_i the node's limit: the smallest
//! Courant step of its quads and, for a node a contact may act on, its spring's stable step
//! ([`Interaction::node_limits`](crate::fe::interaction::Interaction::node_limits)), at most
//! [`NEIGHBOUR_RATIO`] times the limit of any node it shares a quad with. A quad is
//! updated at the level of its finest node, u_e = min L_i, with step 2^{u_e} h. Every node
//! drifts every fine step with its constant half-step velocity; a node is due (kicked with its
//! element, contact, load and damping forces) at multiples of 2^{L_i} fine steps. Levels and h
//! are chosen again at every synchronisation (all nodes due), from the limits of that instant.

use super::solver::{SectionSolver, StepCarry};
use crate::error::{Error, Result};

/// How the section model is integrated in time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integration {
    /// One global step, the smallest stable step of all quads and contact springs.
    SingleRate,
    /// Power-of-two step classes up to 2^`max_level` times the fine step.
    Subcycled {
        /// Highest level K (0..=[`MAX_LEVEL`]); 0 is single-rate integration.
        max_level: u8,
    },
}

/// The largest allowed subcycling level (steps up to 2^10 times the fine step).
pub const MAX_LEVEL: u8 = 10;

/// Default highest level of [`Integration::Subcycled`].
pub const DEFAULT_MAX_LEVEL: u8 = 2;

/// Margin on a node's limit for the levels above 0: room for its quads to deform during a
/// cycle, whose limits are measured at its start.
pub const LEVEL_MARGIN: f64 = 1.02;

impl Integration {
    /// The default subcycled integration.
    pub fn subcycled() -> Self {
        Integration::Subcycled {
            max_level: DEFAULT_MAX_LEVEL,
        }
    }

    /// Checks the setting: a clear error for a level above [`MAX_LEVEL`].
    pub fn check(&self) -> Result<()> {
        match *self {
            Integration::Subcycled { max_level } if max_level > MAX_LEVEL => Err(Error::invalid(
                "solver.subcycle_max_level",
                max_level,
                format!("0..={MAX_LEVEL}"),
            )),
            _ => Ok(()),
        }
    }
}

/// The step classes of one cycle: node and quad levels, and both sorted by level.
#[derive(Debug, Clone, Default)]
pub struct Schedule {
    /// Level of each node.
    pub node_level: Vec<u8>,
    /// Level of each quad (its finest node's).
    pub element_level: Vec<u8>,
    /// Quads sorted by level (stable: ascending index within a level).
    pub elements: Vec<u32>,
    /// `elements[..element_end[k]]` are the quads of levels ≤ k.
    pub element_end: Vec<usize>,
    /// Nodes sorted by level.
    pub nodes: Vec<u32>,
    /// `nodes[..node_end[k]]` are the nodes of levels ≤ k.
    pub node_end: Vec<usize>,
    /// Highest level in use; a cycle is 2^top fine steps.
    pub top: u8,
    /// Fine steps taken since the last synchronisation.
    pub count: u64,
}

/// Level of a node of limit `limit` (s) for fine step `h` (s), step factor `factor` and cap
/// `max_level`: the largest k ≤ max_level with 2^k h ≤ factor · limit (with
/// [`LEVEL_MARGIN`] for k ≥ 1); 0 when even that fails.
pub fn node_level(limit: f64, h: f64, factor: f64, max_level: u8) -> u8 {
    let room = factor * limit / (LEVEL_MARGIN * h);
    let mut k = 0;
    while k < max_level && f64::from(1u32 << (k + 1)) <= room {
        k += 1;
    }
    k
}

/// Most a node's limit may exceed the own limit of a node it shares a quad with: the
/// neighbour's fastest motion (frequency ω ≤ 1/limit for a contact spring) reaches the node
/// through their quad, and ω H < 2 keeps it inside the node's central-difference step H.
pub const NEIGHBOUR_RATIO: f64 = 2.0;

/// Each node's limit (s): the smallest Courant step `element_dt` (s) of the quads `quads`
/// holding it and its contact limit `contact_dt` (s; ∞ for none), capped at
/// [`NEIGHBOUR_RATIO`] times the own limit of every node it shares a quad with.
pub fn node_limits(quads: &[[u32; 4]], element_dt: &[f64], contact_dt: &[f64]) -> Vec<f64> {
    let mut own = contact_dt.to_vec();
    for (q, &dt) in quads.iter().zip(element_dt) {
        for &i in q {
            let l = &mut own[i as usize];
            *l = l.min(dt);
        }
    }
    let mut lim = own.clone();
    for q in quads {
        let m = q
            .iter()
            .map(|&i| own[i as usize])
            .fold(f64::INFINITY, f64::min);
        for &i in q {
            let l = &mut lim[i as usize];
            *l = l.min(NEIGHBOUR_RATIO * m);
        }
    }
    lim
}

/// Indices `0..levels.len()` sorted by level (stable) and the end of each level's run.
fn sorted_by_level(levels: &[u8], top: u8) -> (Vec<u32>, Vec<usize>) {
    let mut order: Vec<u32> = (0..levels.len() as u32).collect();
    order.sort_by_key(|&i| levels[i as usize]);
    let ends = (0..=top)
        .map(|k| levels.iter().filter(|&&l| l <= k).count())
        .collect();
    (order, ends)
}

impl Schedule {
    /// The schedule of node levels `node_level` on `quads`.
    pub fn new(quads: &[[u32; 4]], node_level: Vec<u8>) -> Self {
        let element_level: Vec<u8> = quads
            .iter()
            .map(|q| q.iter().map(|&i| node_level[i as usize]).min().unwrap_or(0))
            .collect();
        let top = node_level.iter().copied().max().unwrap_or(0);
        let (elements, element_end) = sorted_by_level(&element_level, top);
        let (nodes, node_end) = sorted_by_level(&node_level, top);
        Schedule {
            node_level,
            element_level,
            elements,
            element_end,
            nodes,
            node_end,
            top,
            count: 0,
        }
    }

    /// Fine steps in a cycle.
    pub fn cycle(&self) -> u64 {
        1 << self.top
    }

    /// The highest level due after fine step `count` of the cycle (every level at its end).
    pub fn due_level(&self, count: u64) -> u8 {
        if count >= self.cycle() {
            self.top
        } else {
            (count.trailing_zeros() as u8).min(self.top)
        }
    }

    /// Element updates per fine step, averaged over a cycle: Σ_e 2^{−u_e}.
    pub fn updates_per_step(&self) -> f64 {
        self.element_level
            .iter()
            .map(|&u| 1.0 / f64::from(1u32 << u))
            .sum()
    }
}

/// One fine step's schedule, handed from its forces to its kicks and close: the cycle's
/// schedule, whether the step ends the cycle, the level due now, and the next cycle's fine
/// step (s) and schedule when it ends one (`None` inside: the levels are kept).
pub(crate) struct FineStep {
    sched: Schedule,
    sync: bool,
    level: usize,
    next: Option<(f64, Option<Schedule>)>,
}

impl SectionSolver {
    /// Steps 5-7 of a fine step: drift every node by h v^{n+1/2} (the kicks are the due
    /// nodes', after their forces).
    pub(super) fn drift(&mut self, h: f64) -> StepCarry {
        for (x, v) in self.x.iter_mut().zip(&self.v_half) {
            x[0] += h * v[0];
            x[1] += h * v[1];
        }
        StepCarry {
            ext: 0.0,
            next: 0.0,
            fine: None,
        }
    }

    /// Step 8 of a fine step: update the due quads (step 2^{u_e} h, velocities v^{n+1/2} of
    /// their nodes: constant over that step since u_e ≤ L_i and levels are aligned), evaluate
    /// the contacts, and at the end of a cycle plan the next one.
    pub(super) fn due_forces(&mut self, h: f64, carry: StepCarry) -> Result<StepCarry> {
        let mut sched = std::mem::take(&mut self.schedule);
        sched.count += 1;
        let sync = sched.count >= sched.cycle();
        let level = sched.due_level(sched.count) as usize;
        for &i in &sched.nodes[..sched.node_end[level]] {
            self.f_int[i as usize] = [0.0; 2];
        }
        let due_elements = &sched.elements[..sched.element_end[level]];
        self.update_elements(due_elements, &sched.element_level, h)?;
        self.element_updates += due_elements.len() as u64;
        self.contact_forces()?;
        // At the end of a cycle the next one is planned first: a kinematic contact needs the
        // step each node opens.
        let next = if sync {
            Some(self.plan_cycle(&sched)?)
        } else {
            None
        };
        Ok(StepCarry {
            fine: Some(FineStep {
                sched,
                sync,
                level,
                next,
            }),
            ..carry
        })
    }

    /// Steps 9-10 of a fine step: close and reopen the kicks of the due nodes.
    pub(super) fn due_kicks(&mut self, h: f64, mut carry: StepCarry) -> StepCarry {
        let fine = carry.fine.take().expect("due_forces ran");
        let sched = &fine.sched;
        let alpha = self.model.damping;
        let mut ext = carry.ext;
        for &i in &sched.nodes[..sched.node_end[fine.level]] {
            let i = i as usize;
            let big = f64::from(1u32 << sched.node_level[i]) * h;
            let vh = self.v_half[i];
            for c in 0..2 {
                let f = self.model.loads[i][c] + self.f_c[i][c]
                    - self.f_int[i][c]
                    - alpha * self.mass[i] * vh[c];
                self.a[i][c] = f / self.mass[i];
                ext += big * vh[c] * (self.model.loads[i][c] - alpha * self.mass[i] * vh[c]);
            }
            self.constrain_acceleration(i);
            let open = match &fine.next {
                Some((h2, Some(s2))) => f64::from(1u32 << s2.node_level[i]) * h2,
                Some((h2, None)) => f64::from(1u32 << sched.node_level[i]) * h2,
                None => big,
            };
            ext += self.kick_constraint(i, big, open);
            for c in 0..2 {
                self.v[i][c] = vh[c] + 0.5 * big * self.a[i][c];
            }
            if !fine.sync {
                self.open_kick(i, big);
            }
        }
        StepCarry {
            ext,
            fine: Some(fine),
            ..carry
        }
    }

    /// Step 12 of a fine step: at the end of a cycle choose h and the levels again and
    /// refresh the energies.
    pub(super) fn close_fine_step(&mut self, fine: FineStep) {
        let FineStep { sched, next, .. } = fine;
        match next {
            Some((h2, s2)) => {
                let s2 = s2.unwrap_or(Schedule { count: 0, ..sched });
                self.start_cycle(h2, s2);
            }
            None => self.schedule = sched,
        }
    }

    /// The opening half kick of node `i` with its step `big` (s): v^{n+1/2} = v^n + big/2 a^n.
    fn open_kick(&mut self, i: usize, big: f64) {
        self.v_prev[i] = self.v_half[i];
        self.half_kick(i, big);
    }

    /// The fine step h (s) of the next cycle from the current limits, and its schedule, or
    /// `None` when its levels are `old`'s (which is then reused).
    pub(super) fn plan_cycle(&self, old: &Schedule) -> Result<(f64, Option<Schedule>)> {
        let Integration::Subcycled { max_level } = self.model.integration else {
            unreachable!("plan_cycle is only called by the subcycled integration")
        };
        let lim = node_limits(&self.model.quads, &self.element_dt_of, &self.contact_dt);
        let factor = self.model.time_step_factor;
        let h = factor * lim.iter().copied().fold(f64::INFINITY, f64::min);
        if !h.is_finite() || h <= 0.0 {
            return Err(Error::Numerical(format!(
                "stable step {h:.3e} s at t = {:.6e} s",
                self.time
            )));
        }
        let levels: Vec<u8> = lim
            .iter()
            .map(|&l| node_level(l, h, factor, max_level))
            .collect();
        let sched = (levels != old.node_level).then(|| Schedule::new(&self.model.quads, levels));
        Ok((h, sched))
    }

    /// Starts a cycle of fine step `h` (s) and schedule `sched`: opens every node's kick and
    /// stores the energies of this instant (the central kinetic energy ½ m v^{n−1/2}·v^{n+1/2}).
    pub(super) fn start_cycle(&mut self, h: f64, sched: Schedule) {
        self.dt = h;
        let mut kc = 0.0;
        for i in 0..self.x.len() {
            let big = f64::from(1u32 << sched.node_level[i]) * h;
            self.open_kick(i, big);
            let (p, q) = (self.v_prev[i], self.v_half[i]);
            kc += 0.5 * self.mass[i] * (p[0] * q[0] + p[1] * q[1]);
        }
        self.kinetic_central = if self.steps == 0 { self.kinetic() } else { kc };
        self.schedule = sched;
        self.synced_energy = self.fresh_energy();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_level_is_the_largest_power_of_two_inside_the_limit() {
        // h = 0.9 · 1 (the smallest limit); limit 4.5 allows 2^2 h = 3.6 ≤ 4.05 / 1.02.
        assert_eq!(node_level(4.5, 0.9, 0.9, 6), 2);
        assert_eq!(node_level(1.0, 0.9, 0.9, 6), 0);
        assert_eq!(node_level(1e9, 0.9, 0.9, 6), 6);
        // Just above 2 (within the margin) stays at level 0.
        assert_eq!(node_level(2.01, 0.9, 0.9, 6), 0);
        assert_eq!(node_level(2.1, 0.9, 0.9, 6), 1);
    }

    #[test]
    fn a_node_takes_at_most_twice_the_limit_of_its_quad_neighbours() {
        // Node 0 carries a stiff spring (limit 1); its quad's other nodes would allow 8, the
        // second quad's far nodes 8 too: only the first quad's nodes are capped at 2.
        let quads = [[0, 1, 2, 3], [1, 4, 5, 2]];
        let contact = [
            1.0,
            f64::INFINITY,
            f64::INFINITY,
            f64::INFINITY,
            f64::INFINITY,
            f64::INFINITY,
        ];
        let lim = node_limits(&quads, &[8.0, 8.0], &contact);
        assert_eq!(lim, vec![1.0, 2.0, 2.0, 2.0, 8.0, 8.0]);
    }

    #[test]
    fn quads_take_their_finest_node_and_runs_are_sorted() {
        let quads = [[0, 1, 2, 3], [1, 4, 5, 2]];
        let s = Schedule::new(&quads, vec![2, 1, 3, 3, 3, 3]);
        assert_eq!(s.element_level, vec![1, 1]);
        assert_eq!(s.top, 3);
        assert_eq!(s.element_end, vec![0, 2, 2, 2]);
        assert_eq!(s.nodes[0], 1);
        assert_eq!(s.node_end, vec![0, 1, 2, 6]);
        assert_eq!(s.due_level(1), 0);
        assert_eq!(s.due_level(4), 2);
        assert_eq!(s.due_level(8), 3);
        assert!((s.updates_per_step() - 1.0).abs() < 1e-15);
    }
}
