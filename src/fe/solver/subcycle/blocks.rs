//! The subcycling scheme ([`super`]) on the 3D model's element blocks: the levels of the
//! synchronisations, the element runs of each level, the mean nodal velocities over a
//! level's interval, and the level-weighted half-kick forces of the due nodes.
//!
//! The 3D loop kicks its due nodes inside the single-step Box 6.1 step, with the fine step and
//! their element forces weighted by their own steps: closing 2^{L_old}, opening 2^{L_new}. An
//! element sees its nodes' mean velocity over its own step, v̄ = (x^n − x^{n−2^u})/H
//! (positions kept per level at the last multiple of 2^u). The interactions act every fine
//! step, on nodes held at level 0; levels follow [`LevelRule::HEXAHEDRA`]. Between
//! synchronisations a guard acts: a due node whose elements no longer allow its step drops
//! level(s), and if a due element or an interaction needs less than h, h drops at once; a node
//! then in mid-interval closes it with its actual length A instead of the planned P and adds
//! ½ (A − P) g_open, so its impulse stays the trapezoid ½ A (g_open + g_close).

use super::levels::LevelRule;
use super::report::{predicted_saving, SubcycleReport};
use super::schedule::Schedule;
use crate::fe::elements::{ElementBlock, ElementFailure};
use std::ops::Range;

/// The level bookkeeping of a subcycled run.
#[derive(Debug, Clone)]
pub struct Subcycler {
    cap: u32,
    /// The level rule's constants.
    rule: LevelRule,
    /// The cycle's step classes: each node's level (its own step 2^L h, in units of the
    /// current fine step), each global element's (the smallest of its nodes'), the nodes
    /// ordered by level (mesh order within a level: the nodes due at a fine step are a prefix),
    /// and the highest level in use (everything is updated together every 2^top fine steps).
    sched: Schedule,
    /// Nodes held at level 0 (an interaction may act on them).
    pinned: Vec<bool>,
    /// (block, local index) of every global element.
    locate: Vec<(usize, usize)>,
    /// Fine steps since the last synchronisation.
    j: u64,
    /// Per level: maximal runs (block, local element range) of elements of that level.
    runs: Vec<Vec<(usize, Range<usize>)>>,
    /// Per level k ≥ 1: nodal positions at the last multiple of 2^k fine steps, m.
    snap: Vec<Vec<[f64; 3]>>,
    /// Scratch: mean nodal velocities over one level's interval, m/s.
    vbar: Vec<[f64; 3]>,
    /// Per node: closing / opening half-kick weights at the current step (0: not due), and
    /// the weight of the trapezoid correction with the node's previous force sum.
    w_close: Vec<f64>,
    w_open: Vec<f64>,
    w_corr: Vec<f64>,
    /// Per node: its element force sum at its last kick, N.
    g_last: Vec<[f64; 3]>,
    /// Per level: time since the level's interval opened (its last multiple of 2^k), s.
    span: Vec<f64>,
    /// Per level: the interval planned when it opened, 2^k h, s.
    planned: Vec<f64>,
    /// Per level: whether h changed since the interval opened (then span ≠ planned).
    h_changed: Vec<bool>,
    /// Levels due at the current step (all: `u32::MAX`).
    thr: u32,
    /// Per level k ≥ 1: the nodes of its elements, ascending: the only nodes whose snapshot
    /// `snap[k]` and mean velocity over the level's interval are ever read.
    level_nodes: Vec<Vec<u32>>,
    /// Per level: the smallest Courant limit (s) of its elements and the lowest global
    /// element that has it, from their last update; `None` after the levels changed.
    level_min: Option<Vec<(f64, usize)>>,
    report: SubcycleReport,
}

impl Subcycler {
    /// Levels for elements whose current Courant limits are in `blocks[..].dt_crit` (all
    /// evaluated at the same instant), nodal contact limits `contact_dt` (s, one per node; ∞
    /// for none), the level rule `rule`, step factor `time_step_factor`, fine step `h` (s),
    /// highest level `cap`;
    /// `pinned_nodes[i]` marks nodes an interaction may act on (held at level 0). The state
    /// is a synchronisation: every node and element counts as just updated.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        blocks: &[ElementBlock],
        x: &[[f64; 3]],
        pinned_nodes: &[bool],
        contact_dt: &[f64],
        rule: LevelRule,
        time_step_factor: f64,
        h: f64,
        cap: u32,
    ) -> Subcycler {
        let ne: usize = blocks.iter().map(|b| b.conn.len()).sum();
        let n = x.len();
        let mut s = Subcycler {
            cap,
            rule,
            sched: Schedule {
                node_level: vec![0; n],
                element_level: vec![0; ne],
                ..Schedule::default()
            },
            pinned: pinned_nodes.to_vec(),
            locate: element_locations(blocks),
            j: 0,
            runs: Vec::new(),
            snap: Vec::new(),
            vbar: vec![[0.0; 3]; n],
            w_close: vec![1.0; n],
            w_open: vec![1.0; n],
            w_corr: vec![0.0; n],
            g_last: vec![[0.0; 3]; n],
            span: Vec::new(),
            planned: Vec::new(),
            h_changed: Vec::new(),
            thr: u32::MAX,
            level_nodes: Vec::new(),
            level_min: None,
            report: SubcycleReport {
                used: true,
                max_level: cap,
                ..Default::default()
            },
        };
        s.synchronise(blocks, time_step_factor, h, contact_dt);
        s.open_intervals(x, h, h);
        for (w, &k) in s.w_open.iter_mut().zip(&s.sched.node_level) {
            *w = (1u64 << k) as f64;
        }
        s.report.initial_levels = s.histogram();
        s.report.predicted_saving = predicted_saving(&s.sched.element_level);
        s
    }

    /// The report so far.
    pub fn report(&self) -> &SubcycleReport {
        &self.report
    }

    /// Update level of global element `e`.
    pub fn element_level(&self, e: usize) -> u32 {
        self.sched.element_level[e] as u32
    }

    /// Level of node `i`.
    pub fn node_level(&self, i: usize) -> u32 {
        self.sched.node_level[i] as u32
    }

    /// The nodes due at the current fine step (every node at a synchronisation), finest level
    /// first: the only nodes whose element forces act now.
    pub fn due_nodes(&self) -> &[u32] {
        if self.thr == u32::MAX {
            &self.sched.nodes
        } else {
            &self.sched.nodes
                [..self.sched.node_end[self.thr.min(u32::from(self.sched.top)) as usize]]
        }
    }

    /// Whether node `i` is due at the current fine step.
    fn due(&self, i: usize) -> bool {
        self.thr == u32::MAX || self.sched.node_level[i] as u32 <= self.thr
    }

    /// Elements per update level now (index = level).
    pub fn histogram(&self) -> Vec<usize> {
        let mut h = vec![0; self.sched.top as usize + 1];
        for &k in &self.sched.element_level {
            h[k as usize] += 1;
        }
        h
    }

    /// Advances the fine-step counter by a step of `h_taken` (s): the levels due at the
    /// coming update are those ≤ the number of trailing zero bits of the count (all at a
    /// synchronisation).
    pub fn advance(&mut self, h_taken: f64) {
        for s in &mut self.span {
            *s += h_taken;
        }
        self.j += 1;
        self.thr = if self.j.is_multiple_of(1u64 << self.sched.top) {
            u32::MAX
        } else {
            self.j.trailing_zeros()
        };
    }

    /// The highest level as the level rule takes it (at most 255).
    fn level_cap(&self) -> u8 {
        self.cap.min(u32::from(u8::MAX)) as u8
    }

    /// True when every node and element is due at the current fine step.
    pub fn synchronising(&self) -> bool {
        self.thr == u32::MAX
    }

    /// Updates the elements due now on the nodal coordinates `x` (m; the reference ones for
    /// geometrically linear elements), each with its own step (the time since its level's
    /// interval opened: 2^k h while h holds) and the mean velocities of its nodes over that
    /// step (`v` itself at level 0; else from the current positions `x_now`, m, which the
    /// level snapshots are taken of); writes their force blocks into `elem_force` (global
    /// element index). Returns the number of element updates, or the lowest failing element
    /// (global) and why.
    pub fn update_due_elements(
        &mut self,
        blocks: &mut [ElementBlock],
        x: &[[f64; 3]],
        x_now: &[[f64; 3]],
        v: &[[f64; 3]],
        elem_force: &mut [[[f64; 3]; 8]],
    ) -> Result<u64, (usize, ElementFailure)> {
        let mut count = 0;
        let last = u32::from(self.sched.top).min(self.thr);
        for k in 0..=last as usize {
            if self.runs[k].is_empty() {
                continue;
            }
            let big = self.span[k];
            let vk: &[[f64; 3]] = if k == 0 {
                v
            } else {
                mean_velocity(
                    x_now,
                    &self.snap[k],
                    big,
                    &self.level_nodes[k],
                    &mut self.vbar,
                );
                &self.vbar
            };
            for (b, r) in &self.runs[k] {
                let blk = &mut blocks[*b];
                let g = blk.first + r.start..blk.first + r.end;
                blk.update_range(r.clone(), x, vk, big, &mut elem_force[g])?;
                count += r.len() as u64;
            }
            if let Some(m) = &mut self.level_min {
                m[k] = smallest_limit(blocks, &self.runs[k]);
            }
        }
        self.report.element_updates += count;
        Ok(count)
    }

    /// The smallest current Courant limit (s) of all elements and the lowest global element
    /// that has it ((∞, `usize::MAX`) if no limit is below ∞): the same as a scan of every
    /// element's limit in element order, but from the per-level minima that
    /// [`Subcycler::update_due_elements`] keeps (an element's limit changes only when it is
    /// updated, and all elements of a level are updated together), so a fine step costs a
    /// scan of the elements it updated, not of all (after a level change, one full scan).
    pub fn smallest_limit(&mut self, blocks: &[ElementBlock]) -> (f64, usize) {
        let runs = &self.runs;
        let m = self
            .level_min
            .get_or_insert_with(|| runs.iter().map(|r| smallest_limit(blocks, r)).collect());
        let mut best = (f64::INFINITY, usize::MAX);
        for &(d, e) in m.iter() {
            if d < best.0 || (d == best.0 && e < best.1) {
                best = (d, e);
            }
        }
        best
    }

    /// Chooses the levels for the coming intervals and the fine step, after the due
    /// elements were updated: at a synchronisation h = `choose_h(h_taken)` and every node
    /// takes its level afresh by the scheme's rule, with the nodal contact limits
    /// `contact_dt()` (s); otherwise the levels stay, and h stays unless a due element or
    /// `interaction_limit` (s, time_step_factor included) needs less (then h drops to that,
    /// as the single-step solver's step does). Sets the closing (actual interval, plus the
    /// trapezoid correction if h changed during it) and opening (new level) weights of the
    /// due nodes and opens the intervals of the levels due. Returns the fine step to take (s).
    #[allow(clippy::too_many_arguments)]
    pub fn choose_levels(
        &mut self,
        blocks: &[ElementBlock],
        x: &[[f64; 3]],
        time_step_factor: f64,
        h_taken: f64,
        interaction_limit: f64,
        contact_dt: impl FnOnce() -> Vec<f64>,
        choose_h: impl FnOnce(f64) -> f64,
    ) -> f64 {
        // Weights of the due nodes only (`gather_kicks` never reads the others').
        let n_due = self.due_nodes().len();
        for idx in 0..n_due {
            let i = self.sched.nodes[idx] as usize;
            let l = self.sched.node_level[i] as usize;
            (self.w_close[i], self.w_corr[i]) = if self.h_changed[l] {
                // Impulse ½ A (g_open + g_now) over the actual interval A: the opening kick
                // gave ½ P g_open, so the closing one adds ½ (A − P) g_open.
                (
                    self.span[l] / h_taken,
                    (self.span[l] - self.planned[l]) / h_taken,
                )
            } else {
                ((1u64 << l) as f64, 0.0)
            };
        }
        let h = if self.synchronising() {
            let h = choose_h(h_taken);
            // The nodes a contact limits are held at level 0, so without a neighbour cap its
            // limits change no level and are not computed.
            let contact_dt = if self.rule.neighbour_ratio.is_finite() {
                contact_dt()
            } else {
                vec![f64::INFINITY; self.vbar.len()]
            };
            self.synchronise(blocks, time_step_factor, h, &contact_dt);
            self.report.synchronisations += 1;
            h
        } else {
            self.due_step(blocks, time_step_factor, h_taken, interaction_limit)
        };
        // The due set is unchanged between synchronisations; at one, every node is due.
        for idx in 0..n_due {
            let i = self.sched.nodes[idx] as usize;
            self.w_open[i] = (1u64 << self.sched.node_level[i]) as f64;
        }
        self.open_intervals(x, h_taken, h);
        h
    }

    /// Opens the interval of every level due now (snapshot, span, planned length) and marks
    /// the others if the fine step changed from `h_taken` to `h`.
    fn open_intervals(&mut self, x: &[[f64; 3]], h_taken: f64, h: f64) {
        let levels = self.sched.top as usize + 1;
        self.span.resize(levels, 0.0);
        self.planned.resize(levels, 0.0);
        self.h_changed.resize(levels, false);
        for k in 0..levels {
            if self.j.is_multiple_of(1u64 << k) {
                for &i in &self.level_nodes[k] {
                    self.snap[k][i as usize] = x[i as usize];
                }
                self.span[k] = 0.0;
                self.planned[k] = (1u64 << k) as f64 * h;
                self.h_changed[k] = false;
            } else if h != h_taken {
                self.h_changed[k] = true;
            }
        }
    }

    /// All node levels afresh for fine step `h` (s) by the scheme's rule
    /// ([`super::levels`]: the elements' Courant limits, the nodal contact limits
    /// `contact_dt` (s), the neighbour cap), pinned nodes at level 0; counter reset.
    fn synchronise(
        &mut self,
        blocks: &[ElementBlock],
        time_step_factor: f64,
        h: f64,
        contact_dt: &[f64],
    ) {
        let elements = blocks
            .iter()
            .flat_map(|b| b.conn.iter().zip(b.dt_crit.iter().copied()));
        let rule = self.rule;
        let limits = rule.node_limits(elements, contact_dt);
        let cap = self.level_cap();
        let first = self.runs.is_empty();
        let mut changed = first;
        for (i, &limit) in limits.iter().enumerate() {
            let current = (!first).then_some(self.sched.node_level[i]);
            let new = if self.pinned[i] {
                0
            } else {
                rule.next_level(limit, h, time_step_factor, cap, current)
            };
            if new < self.sched.node_level[i] {
                self.report.level_drops += 1;
            }
            changed |= new != self.sched.node_level[i];
            self.sched.node_level[i] = new;
        }
        self.j = 0;
        self.thr = u32::MAX;
        // Most synchronisations keep every level: the element levels, runs and node lists
        // derived from them then stand.
        if changed {
            self.levels_changed(blocks);
        }
    }

    /// Between synchronisations, the 3D model's guard: h drops if a due element or an
    /// interaction needs it, and due nodes whose elements no longer allow their step drop
    /// level(s) (their elements are all being updated, so the new level starts aligned).
    /// Returns the fine step.
    ///
    /// The elements of the due nodes are exactly the elements updated now (an element is
    /// updated when its finest node is due), so both checks run over the due runs: no
    /// node-incidence walk.
    fn due_step(
        &mut self,
        blocks: &[ElementBlock],
        time_step_factor: f64,
        h_taken: f64,
        interaction_limit: f64,
    ) -> f64 {
        let top = u32::from(self.sched.top);
        let last = top.min(self.thr) as usize;
        let mut need = interaction_limit;
        for runs in &self.runs[..=last] {
            for (b, r) in runs {
                for &d in &blocks[*b].dt_crit[r.clone()] {
                    need = need.min(time_step_factor * d);
                }
            }
        }
        let h = if need < h_taken {
            self.report.fine_step_drops += 1;
            need
        } else {
            h_taken
        };
        // A due node takes the largest level its elements allow. Due nodes have levels ≤
        // `cut`, so only an element that fits less than 2^cut h can drop one, and most
        // elements are settled by that one comparison.
        let cut = self.thr.min(top);
        // The guard's fit is exact: the rule's level without its margin (the limit carries
        // the step factor already).
        let exact = LevelRule {
            margin: 1.0,
            ..self.rule
        };
        let cap = self.level_cap();
        let mut changed = false;
        for runs in &self.runs[..=last] {
            for (b, r) in runs {
                let blk = &blocks[*b];
                for k in r.clone() {
                    let limit = time_step_factor * blk.dt_crit[k];
                    if cut == 0 || (1u64 << cut) as f64 * h <= limit {
                        continue;
                    }
                    let fit = u32::from(exact.level(limit, h, 1.0, cap));
                    if fit >= top {
                        continue;
                    }
                    for &i in &blk.conn[k] {
                        let i = i as usize;
                        if self.due(i) && u32::from(self.sched.node_level[i]) > fit {
                            self.sched.node_level[i] = fit as u8;
                            self.report.level_drops += 1;
                            changed = true;
                        }
                    }
                }
            }
        }
        if changed {
            self.levels_changed(blocks);
        }
        h
    }

    /// Element update levels (smallest of their nodes'), runs, the highest level and the
    /// snapshot arrays after node levels changed.
    fn levels_changed(&mut self, blocks: &[ElementBlock]) {
        let node_level = std::mem::take(&mut self.sched.node_level);
        self.sched = Schedule::new(blocks.iter().flat_map(|b| b.conn.iter()), node_level);
        let levels = self.sched.top as usize + 1;
        let n = self.vbar.len();
        if self.snap.len() < levels {
            self.snap.resize(levels, Vec::new());
        }
        for s in self.snap.iter_mut().skip(1) {
            if s.len() != n {
                *s = vec![[0.0; 3]; n];
            }
        }
        // The nodes of each level's elements (level 0 needs none: its elements use v).
        self.level_nodes = vec![Vec::new(); levels];
        for b in blocks {
            for (k, c) in b.conn.iter().enumerate() {
                let l = self.sched.element_level[b.first + k] as usize;
                if l > 0 {
                    self.level_nodes[l].extend_from_slice(c);
                }
            }
        }
        for list in &mut self.level_nodes {
            list.sort_unstable();
            list.dedup();
        }
        self.level_min = None;
        self.runs = vec![Vec::new(); levels];
        for (bi, b) in blocks.iter().enumerate() {
            let mut start = 0;
            for k in 1..=b.conn.len() {
                let end_run = k == b.conn.len()
                    || self.sched.element_level[b.first + k]
                        != self.sched.element_level[b.first + start];
                if end_run {
                    let l = self.sched.element_level[b.first + start] as usize;
                    self.runs[l].push((bi, start..k));
                    start = k;
                }
            }
        }
    }

    /// The half-kick forces of the nodes in `nodes`, N: at a due node, with g_i = Σ_e f_e
    /// (every element of a due node was updated now), `close` = 2^{L_old} g (closing the
    /// node's interval just ended, to be multiplied by half the step just taken; with the
    /// actual interval and the trapezoid correction if h changed during it) and `open` =
    /// 2^{L_new} g (opening the next); zero at the listed nodes not due. Entries of unlisted
    /// nodes are left alone. Sums run in element order (bitwise identical for any thread
    /// count). `close` rows are [x, y, z, 0], the padded layout of the solver's `f_int`.
    pub fn gather_kicks(
        &mut self,
        nodes: &[u32],
        inc_ptr: &[usize],
        inc: &[u32],
        elem_force: &[[[f64; 3]; 8]],
        close: &mut [[f64; 4]],
        open: &mut [[f64; 3]],
    ) {
        for &n in nodes {
            let n = n as usize;
            if !self.due(n) {
                close[n] = [0.0; 4];
                open[n] = [0.0; 3];
                continue;
            }
            let g = node_force_sum(inc_ptr, inc, elem_force, n);
            let (wc, wr, wo, gl) = (
                self.w_close[n],
                self.w_corr[n],
                self.w_open[n],
                self.g_last[n],
            );
            close[n] = [0, 1, 2, 3].map(|d| if d < 3 { wc * g[d] + wr * gl[d] } else { 0.0 });
            open[n] = g.map(|c| wo * c);
            self.g_last[n] = g;
        }
    }
}

impl Subcycler {
    /// The largest ratio, over nodes, of the node's own step 2^L `h` (s) to the smallest
    /// current Courant limit (no time_step_factor factor) of its elements: above 1 a node would run
    /// unstable. A diagnostic for tests.
    pub fn worst_step_ratio(
        &self,
        blocks: &[ElementBlock],
        inc_ptr: &[usize],
        inc: &[u32],
        h: f64,
    ) -> f64 {
        let mut worst: f64 = 0.0;
        for (i, &l) in self.sched.node_level.iter().enumerate() {
            for &slot in &inc[inc_ptr[i]..inc_ptr[i + 1]] {
                let (b, k) = self.locate[slot as usize / 8];
                worst = worst.max((1u64 << l) as f64 * h / blocks[b].dt_crit[k]);
            }
        }
        worst
    }

    /// Work (J) the internal forces of each element not updated at the current step have
    /// done since its last update, f_e · (x − x_last), summed per block: its internal energy
    /// is that much behind. Added to the energy report so that energies read between
    /// synchronisations are consistent (first order in the element's displacement).
    pub fn pending_work(
        &self,
        blocks: &[ElementBlock],
        x: &[[f64; 3]],
        elem_force: &[[[f64; 3]; 8]],
    ) -> Vec<f64> {
        blocks
            .iter()
            .map(|b| {
                let mut w = 0.0;
                for (k, c) in b.conn.iter().enumerate() {
                    let e = b.first + k;
                    let l = self.sched.element_level[e] as usize;
                    if l == 0 || self.j.is_multiple_of(1u64 << l) {
                        continue;
                    }
                    for (a, &i) in c.iter().enumerate() {
                        let (xi, x0, f) =
                            (x[i as usize], self.snap[l][i as usize], elem_force[e][a]);
                        w += f[0] * (xi[0] - x0[0])
                            + f[1] * (xi[1] - x0[1])
                            + f[2] * (xi[2] - x0[2]);
                    }
                }
                w
            })
            .collect()
    }
}

/// `held` with every node that shares an element of `blocks` with a held node.
pub fn with_element_neighbours(blocks: &[ElementBlock], held: &[bool]) -> Vec<bool> {
    let mut out = held.to_vec();
    for c in blocks.iter().flat_map(|b| &b.conn) {
        if c.iter().any(|&i| held[i as usize]) {
            for &i in c {
                out[i as usize] = true;
            }
        }
    }
    out
}

/// Σ of node `n`'s element force blocks (N), in element order (the incidence `inc_ptr`/`inc`
/// lists element·8 + local node): the same bits for any thread count.
#[inline]
pub fn node_force_sum(
    inc_ptr: &[usize],
    inc: &[u32],
    elem_force: &[[[f64; 3]; 8]],
    n: usize,
) -> [f64; 3] {
    let mut g = [0.0; 3];
    for &slot in &inc[inc_ptr[n]..inc_ptr[n + 1]] {
        let f = elem_force[slot as usize / 8][slot as usize % 8];
        g[0] += f[0];
        g[1] += f[1];
        g[2] += f[2];
    }
    g
}

/// (block, local index) of every global element.
fn element_locations(blocks: &[ElementBlock]) -> Vec<(usize, usize)> {
    let mut loc = Vec::new();
    for (b, blk) in blocks.iter().enumerate() {
        for k in 0..blk.conn.len() {
            loc.push((b, k));
        }
    }
    loc
}

/// v̄ = (x − x_start) / big at the nodes `nodes`: the mean nodal velocity over an element
/// interval of `big` s. Other entries of `out` are left alone.
fn mean_velocity(
    x: &[[f64; 3]],
    start: &[[f64; 3]],
    big: f64,
    nodes: &[u32],
    out: &mut [[f64; 3]],
) {
    let r = if big > 0.0 { 1.0 / big } else { 0.0 };
    for &n in nodes {
        let n = n as usize;
        for d in 0..3 {
            out[n][d] = (x[n][d] - start[n][d]) * r;
        }
    }
}

/// The smallest Courant limit (s) of the elements in `runs` (block, local range) and the
/// lowest global element with it, scanning in element order with a strict comparison, as
/// the single-step solver does; (∞, `usize::MAX`) if none is below ∞.
fn smallest_limit(blocks: &[ElementBlock], runs: &[(usize, Range<usize>)]) -> (f64, usize) {
    let mut best = (f64::INFINITY, usize::MAX);
    for (b, r) in runs {
        let blk = &blocks[*b];
        for k in r.clone() {
            let d = blk.dt_crit[k];
            if d < best.0 {
                best = (d, blk.first + k);
            }
        }
    }
    best
}
