//! The section model's phases of one subcycled fine step: the scheme of
//! [`crate::fe::subcycle`] (its level rule and step classes) applied to the rings: every node
//! drifts, the due quads are updated with their nodes' half-step velocities (constant over
//! the quad's step, since u_e ≤ L_i and levels are aligned), the due nodes are kicked with
//! their own steps, and at the end of a cycle h and the levels are chosen again.

use super::solver::{SectionSolver, StepCarry};
use crate::error::{Error, Result};
use crate::fe::subcycle::levels::LevelRule;
use crate::fe::subcycle::{Integration, Schedule};

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
        let quads = self
            .model
            .quads
            .iter()
            .zip(self.element_dt_of.iter().copied());
        let rule = LevelRule::SECTION;
        let lim = rule.node_limits(quads, &self.contact_dt);
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
            .enumerate()
            .map(|(i, &l)| rule.next_level(l, h, factor, max_level, old.node_level.get(i).copied()))
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
