//! The element loop of `getforce` (Box 6.1): for each element gather nodal coordinates and
//! velocities, compute the deformation measure, update the material, compute internal nodal
//! forces. Element state is stored as structure-of-arrays per part; the loop runs over batches
//! of elements in parallel (rayon) and writes one force block per element, so the result does
//! not depend on the number of threads.

use super::batch::{Batch, BatchResult, BlockState, Forces, StepInput};
pub use super::batch::{ElementFailure, ElementStateMut, IntegrationPoint};
use super::element::{Element, ElementVisitor};
use super::formulation::Formulation;
use crate::fe::{
    materials::{Hardening, J2Material, LawDispatch, LawVisitor},
    simd::{Kernel, KernelPath, LaneIsa, LaneKernel, Vec3},
    tensor::Sym,
};
use rayon::iter::Either;
use rayon::prelude::*;

/// Elements per parallel batch (fixed: results never depend on it, only scheduling does).
pub const BATCH: usize = 64;

/// Fewest element batches one parallel task takes (8 x 64 = 512 elements, about 0.15 ms of
/// one-point work): shorter ranges are not worth a fork-join.
const MIN_BATCHES_PER_TASK: usize = 8;

/// The elements of one part: connectivity, material and their state, structure-of-arrays.
#[derive(Debug, Clone)]
pub struct ElementBlock {
    /// Index of the part.
    pub part: usize,
    /// Global index of the first element.
    pub first: usize,
    /// Formulation.
    pub formulation: Formulation,
    /// Material constants.
    pub material: J2Material,
    /// Hourglass coefficient ε_hg (one-point only).
    pub hourglass_coeff: f64,
    /// Connectivity (global node numbers).
    pub conn: Vec<[u32; 8]>,
    /// Integration points, `points_per_element` per element.
    pub points: Vec<IntegrationPoint>,
    /// The hardening law's history ([`Hardening::HISTORY`] values per point, in the order
    /// of `points`; empty for a law without history).
    pub history: Vec<f64>,
    /// Plastic work per element, J.
    pub plastic_work: Vec<f64>,
    /// Internal energy ∫ V σ:D dt per element (elastic stored + plastic), J.
    pub internal_energy: Vec<f64>,
    /// Hourglass forces per element (empty for a formulation without hourglass modes).
    pub hourglass: Vec<[[f64; 3]; 4]>,
    /// Hourglass energy per element, J (empty as `hourglass`).
    pub hourglass_energy: Vec<f64>,
    /// Volume per element, m³.
    pub volume: Vec<f64>,
    /// Critical time step per element, s (times `step_scale` where mass-scaled).
    pub dt_crit: Vec<f64>,
    /// Factor √s_e on each element's Courant step, s_e its density factor
    /// ([`crate::fe::mass_scaling`]); empty: none (every factor 1).
    pub step_scale: Vec<f64>,
    /// The kernel path of the element loop (the widest the CPU has, within a cap).
    pub kernel: Kernel,
}

impl ElementBlock {
    /// A stress-free block for the elements `conn` starting at global element `first`.
    pub fn new(
        part: usize,
        first: usize,
        conn: Vec<[u32; 8]>,
        formulation: Formulation,
        material: J2Material,
        hourglass_coeff: f64,
    ) -> Self {
        let n = conn.len();
        let npe = Self::points_for(formulation);
        let nhg = if formulation.has_hourglass() { n } else { 0 };
        ElementBlock {
            part,
            first,
            formulation,
            material,
            hourglass_coeff,
            conn,
            points: vec![IntegrationPoint::default(); n * npe],
            history: vec![0.0; n * npe * material.law.history_per_point()],
            plastic_work: vec![0.0; n],
            internal_energy: vec![0.0; n],
            hourglass: vec![[[0.0; 3]; 4]; nhg],
            hourglass_energy: vec![0.0; nhg],
            volume: vec![0.0; n],
            dt_crit: vec![f64::INFINITY; n],
            step_scale: Vec::new(),
            kernel: Kernel::widest(KernelPath::Avx512),
        }
    }

    /// Runs the element loop on the widest kernel path this CPU supports, at most `cap`
    /// (results are the same bits on every path; only the speed differs).
    pub fn set_kernel_cap(&mut self, cap: KernelPath) {
        self.kernel = Kernel::widest(cap);
    }

    /// The block's state arrays, read only, as an element family's kernel timing reads them.
    pub(crate) fn state(&self) -> BlockState<'_> {
        BlockState {
            material: &self.material,
            points: &self.points,
            plastic_work: &self.plastic_work,
            internal_energy: &self.internal_energy,
            hourglass_coeff: self.hourglass_coeff,
            hourglass: &self.hourglass,
            hourglass_energy: &self.hourglass_energy,
        }
    }

    /// Integration points per element of a formulation.
    pub fn points_for(f: Formulation) -> usize {
        f.points()
    }

    /// Integration points per element of this block.
    pub fn points_per_element(&self) -> usize {
        Self::points_for(self.formulation)
    }

    /// History values of the block's hardening law per integration point.
    pub fn history_per_point(&self) -> usize {
        self.material.law.history_per_point()
    }

    /// The history of integration point `p` (`points` index): the law's
    /// [`Hardening::HISTORY`] values. Panics if `p` is out of range.
    pub fn point_history(&self, p: usize) -> &[f64] {
        let nh = self.history_per_point();
        &self.history[p * nh..(p + 1) * nh]
    }

    /// Runs the element loop: advances every element's state with positions `x` = x^{n+1},
    /// velocities `v` = v^{n+1/2} and step `dt` (0: evaluate only), writing each element's
    /// internal forces to `forces[e - first]`. Returns the smallest critical step and its
    /// global element, or the lowest-numbered failing element.
    pub fn update(
        &mut self,
        x: &[[f64; 3]],
        v: &[[f64; 3]],
        dt: f64,
        forces: &mut [[[f64; 3]; 8]],
    ) -> Result<(f64, usize), (usize, ElementFailure)> {
        self.update_range(0..self.conn.len(), x, v, dt, forces)
    }

    /// The element loop over the local elements `range` only (for multi-time-step
    /// integration, where element groups advance with their own steps): as
    /// [`ElementBlock::update`], with `forces[k]` the force block of local element
    /// `range.start + k` (so `forces.len() == range.len()`). Elements outside `range` keep
    /// their state. Panics if `range` is out of bounds or `forces` has the wrong length
    /// (programming errors, not input errors).
    pub fn update_range(
        &mut self,
        range: std::ops::Range<usize>,
        x: &[[f64; 3]],
        v: &[[f64; 3]],
        dt: f64,
        forces: &mut [[[f64; 3]; 8]],
    ) -> Result<(f64, usize), (usize, ElementFailure)> {
        assert_eq!(
            forces.len(),
            range.len(),
            "one force block per element of the range"
        );
        let npe = self.points_per_element();
        let mat = self.material;
        let hg = self.hourglass_coeff;
        let form = self.formulation;
        let kernel = self.kernel;
        let first = self.first + range.start;
        let r = range.clone();
        let rp = range.start * npe..range.end * npe;
        self.assert_nodes_below(r.clone(), x.len().min(v.len()));
        // The law's history and the hourglass state per batch; a law without history, a
        // formulation without hourglass modes, gets an empty slice per batch.
        let nh = self.history_per_point();
        let batches = range.len().div_ceil(BATCH);
        let hist = batches_of(
            &mut self.history,
            rp.start * nh..rp.end * nh,
            BATCH * npe * nh,
            batches,
        );
        let hgq = batches_of(&mut self.hourglass, r.clone(), BATCH, batches);
        let ehg = batches_of(&mut self.hourglass_energy, r.clone(), BATCH, batches);
        let res = (
            self.conn[r.clone()].par_chunks(BATCH),
            self.points[rp].par_chunks_mut(BATCH * npe),
            hist,
            self.plastic_work[r.clone()].par_chunks_mut(BATCH),
            self.internal_energy[r.clone()].par_chunks_mut(BATCH),
            hgq,
            ehg,
            self.volume[r.clone()].par_chunks_mut(BATCH),
            self.dt_crit[r].par_chunks_mut(BATCH),
            forces.par_chunks_mut(BATCH),
        )
            .into_par_iter()
            // Subcycled steps update short same-level ranges: below MIN_BATCHES_PER_TASK
            // batches a range runs on the calling thread (the fork-join would cost more than
            // the work). Each batch writes only its own outputs, so the split does not change
            // any result.
            .with_min_len(MIN_BATCHES_PER_TASK)
            .enumerate()
            .map(|(b, (conn, pts, hist, wp, ie, hgq, ehg, vol, dtc, f))| {
                let base = first + b * BATCH;
                let mut batch = Batch {
                    conn,
                    pts,
                    hist,
                    wp,
                    ie,
                    hgq,
                    ehg,
                    vol,
                    dtc,
                    f: Forces::Blocks(f),
                };
                let inp = StepInput {
                    x,
                    v,
                    dt,
                    mat: &mat,
                    hg,
                    kernel,
                };
                element_batch(&mut batch, inp, form, base)
            })
            .reduce(
                || Ok((f64::INFINITY, usize::MAX)),
                |a, b| match (a, b) {
                    (Err(x), Err(y)) => Err(if x.0 <= y.0 { x } else { y }),
                    (Err(x), _) | (_, Err(x)) => Err(x),
                    (Ok(x), Ok(y)) => Ok(if x.0 < y.0 || (x.0 == y.0 && x.1 <= y.1) {
                        x
                    } else {
                        y
                    }),
                },
            );
        res.map(|best| self.scale_steps(range, best))
    }

    /// Panics unless every node index of the local elements `range` is below `len` (the
    /// length of every nodal array the element loop reads or writes): checked once per call,
    /// so the gathers and scatters of the hot loop need no bounds checks.
    fn assert_nodes_below(&self, range: std::ops::Range<usize>, len: usize) {
        let max_node = max_index(self.conn[range.clone()].as_flattened());
        assert!(
            range.is_empty() || (max_node as usize) < len,
            "node index out of range of the nodal arrays"
        );
    }

    /// [`ElementBlock::update_range`] on the calling thread, adding each element's internal
    /// forces (N) straight into the nodal array `f_int` (indexed like `x`, rows [x, y, z, 0],
    /// not cleared here) instead of writing force blocks. Elements are visited in order, so every node receives
    /// its elements' forces in element order: the same sums, bit for bit, as the force blocks
    /// summed per node in element order, without writing and re-reading the blocks (384 bytes
    /// per element and step). Panics if `f_int` is shorter than `x` (a programming error).
    /// After a failure the block's state is partly advanced (the elements of the failing lane
    /// group, not the later batches), as after a failure of [`ElementBlock::update_range`]:
    /// either way the solver stops.
    pub fn update_range_into_nodes(
        &mut self,
        range: std::ops::Range<usize>,
        x: &[[f64; 3]],
        v: &[[f64; 3]],
        dt: f64,
        f_int: &mut [[f64; 4]],
    ) -> Result<(f64, usize), (usize, ElementFailure)> {
        let npe = self.points_per_element();
        let nh = self.history_per_point();
        self.assert_nodes_below(range.clone(), x.len().min(v.len()).min(f_int.len()));
        let inp = StepInput {
            x,
            v,
            dt,
            mat: &self.material,
            hg: self.hourglass_coeff,
            kernel: self.kernel,
        };
        let form = self.formulation;
        let mut best = (f64::INFINITY, usize::MAX);
        let mut k = range.start;
        while k < range.end {
            let e = (k + BATCH).min(range.end);
            let mut batch = Batch {
                conn: &self.conn[k..e],
                pts: &mut self.points[k * npe..e * npe],
                hist: &mut self.history[k * npe * nh..e * npe * nh],
                wp: &mut self.plastic_work[k..e],
                ie: &mut self.internal_energy[k..e],
                hgq: range_of(&mut self.hourglass, k..e),
                ehg: range_of(&mut self.hourglass_energy, k..e),
                vol: &mut self.volume[k..e],
                dtc: &mut self.dt_crit[k..e],
                f: Forces::Nodes(&mut *f_int),
            };
            let d = element_batch(&mut batch, inp, form, self.first + k)?;
            if d.0 < best.0 {
                best = d;
            }
            k = e;
        }
        Ok(self.scale_steps(range, best))
    }

    /// Multiplies the steps of the local elements `range` by `step_scale` and returns the
    /// smallest with its global element (the lowest-numbered on a tie); `best` unchanged
    /// without mass scaling.
    fn scale_steps(&mut self, range: std::ops::Range<usize>, best: (f64, usize)) -> (f64, usize) {
        if self.step_scale.is_empty() {
            return best;
        }
        let mut best = (f64::INFINITY, usize::MAX);
        for k in range {
            self.dt_crit[k] *= self.step_scale[k];
            if self.dt_crit[k] < best.0 {
                best = (self.dt_crit[k], self.first + k);
            }
        }
        best
    }

    /// Mean stress over the integration points of local element `k`, Pa.
    pub fn element_stress(&self, k: usize) -> Sym {
        let npe = self.points_per_element();
        let mut s = [0.0; 6];
        for p in &self.points[k * npe..(k + 1) * npe] {
            for c in 0..6 {
                s[c] += p.stress[c] / npe as f64;
            }
        }
        s
    }

    /// Mean equivalent plastic strain of local element `k`.
    pub fn element_eps_p(&self, k: usize) -> f64 {
        let npe = self.points_per_element();
        self.points[k * npe..(k + 1) * npe]
            .iter()
            .map(|p| p.eps_p)
            .sum::<f64>()
            / npe as f64
    }

    /// Elastic strain energy of the current stresses in local element `k`, p²/2K + s:s/4G
    /// per unit volume, J (a diagnostic: the hypoelastic update has no exact potential).
    pub fn element_elastic_energy(&self, k: usize) -> f64 {
        let npe = self.points_per_element();
        self.points[k * npe..(k + 1) * npe]
            .iter()
            .map(|p| p.volume * self.material.elastic_energy_density(&p.stress))
            .sum()
    }
}

impl ElementBlock {
    /// Time of the lane kernel's arithmetic alone, ns per element: the block's first lane
    /// group (eight elements on the AVX-512 path, four on the others: [`ElementBlock::kernel`])
    /// with its nodes `x` (m), `v` (m/s)
    /// and state loaded once, then updated `repeats` times with step `dt` (s) while every
    /// input stays in registers and L1 (the state is restored every 64 updates so that it
    /// stays near the block's own). No node gathers, state loads or stores, checks or force
    /// scatter: the element phase of a step minus this is the cost of the data movement
    /// around the arithmetic. The block is not changed. Panics if the block is empty,
    /// `repeats` is zero or a node index is out of range of `x` or `v` (programming errors).
    pub fn time_arithmetic_alone(
        &self,
        x: &[[f64; 3]],
        v: &[[f64; 3]],
        dt: f64,
        repeats: u32,
    ) -> f64 {
        assert!(!self.conn.is_empty(), "empty element block");
        assert!(repeats > 0, "no repeats to time");
        let lanes = self.conn.len().min(8);
        self.assert_nodes_below(0..lanes, x.len().min(v.len()));
        self.kernel.run(ArithmeticAlone {
            b: self,
            x,
            v,
            dt,
            repeats,
        })
    }
}

/// [`ElementBlock::time_arithmetic_alone`] as a lane-generic kernel.
struct ArithmeticAlone<'a> {
    b: &'a ElementBlock,
    x: &'a [[f64; 3]],
    v: &'a [[f64; 3]],
    dt: f64,
    repeats: u32,
}

impl LaneKernel for ArithmeticAlone<'_> {
    type Output = f64;
    #[inline(always)]
    fn run<const W: usize>(self, isa: LaneIsa<W>) -> f64 {
        let b = self.b;
        b.material.law.with(ArithmeticLaw { isa, a: self })
    }
}

/// [`ArithmeticAlone`] on W lanes, for the block's hardening law.
struct ArithmeticLaw<'a, const W: usize> {
    isa: LaneIsa<W>,
    a: ArithmeticAlone<'a>,
}

impl<const W: usize> LawVisitor for ArithmeticLaw<'_, W> {
    type Output = f64;
    #[inline(always)]
    fn visit<H: Hardening>(self, law: &H) -> f64 {
        let a = self.a;
        arithmetic_lanes(self.isa, law, a.b, a.x, a.v, a.dt, a.repeats)
    }
}

/// [`ElementBlock::time_arithmetic_alone`] on W lanes (inlined into its caller's target
/// features, as the element loop is).
#[inline(always)]
fn arithmetic_lanes<H: Hardening, const W: usize>(
    isa: LaneIsa<W>,
    law: &H,
    b: &ElementBlock,
    x: &[[f64; 3]],
    v: &[[f64; 3]],
    dt: f64,
    repeats: u32,
) -> f64 {
    let n = b.conn.len();
    // Set-up by local closures and plain indexing, none shared with the element loop: a
    // shared helper (or one of its closures) would get a second caller, and the compiler
    // could then leave it out of line in the element loop too.
    let idx: [usize; W] = std::array::from_fn(|l| l.min(n - 1));
    let lane = |f: &dyn Fn(usize) -> f64| isa.lanes(std::array::from_fn(f));
    let xe: [Vec3<W>; 8] = std::array::from_fn(|i| {
        std::array::from_fn(|d| lane(&|l| x[b.conn[idx[l]][i] as usize][d]))
    });
    let ve: [Vec3<W>; 8] = std::array::from_fn(|i| {
        std::array::from_fn(|d| lane(&|l| v[b.conn[idx[l]][i] as usize][d]))
    });
    let state = b.state();
    let elapsed = b.formulation.with(TimeArithmetic {
        isa,
        law,
        b: &state,
        xe: &xe,
        ve: &ve,
        idx: &idx,
        dt,
        repeats,
    });
    elapsed.as_secs_f64() * 1e9 / (f64::from(repeats) * W as f64)
}

/// [`Element::time_arithmetic`] of the block's formulation.
struct TimeArithmetic<'a, H, const W: usize> {
    isa: LaneIsa<W>,
    law: &'a H,
    b: &'a BlockState<'a>,
    xe: &'a [Vec3<W>; 8],
    ve: &'a [Vec3<W>; 8],
    idx: &'a [usize; W],
    dt: f64,
    repeats: u32,
}

impl<H: Hardening, const W: usize> ElementVisitor for TimeArithmetic<'_, H, W> {
    type Output = std::time::Duration;
    #[inline(always)]
    fn visit<E: Element>(self) -> std::time::Duration {
        E::time_arithmetic(
            self.isa,
            self.law,
            self.b,
            self.xe,
            self.ve,
            self.idx,
            self.dt,
            self.repeats,
        )
    }
}

/// The largest of `a` (0 if empty). The baseline x86-64 target has no unsigned 32-bit vector
/// maximum, so the loop is compiled for AVX2 where the CPU has it (eight lanes per
/// instruction instead of a compare-and-blend emulation: 1.5 % of a one-point step).
fn max_index(a: &[u32]) -> u32 {
    #[inline(always)]
    fn fold(a: &[u32]) -> u32 {
        a.iter().fold(0, |m, &n| m.max(n))
    }
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx2")]
        unsafe fn fold_avx2(a: &[u32]) -> u32 {
            fold(a)
        }
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            return unsafe { fold_avx2(a) };
        }
    }
    fold(a)
}

/// One batch of elements on the block's kernel path.
fn element_batch(
    b: &mut Batch<'_>,
    inp: StepInput<'_>,
    form: Formulation,
    base: usize,
) -> BatchResult {
    inp.kernel.run(ElementLoop { b, inp, form, base })
}

/// One batch of the element loop as a lane-generic kernel.
struct ElementLoop<'a, 'b> {
    b: &'a mut Batch<'b>,
    inp: StepInput<'a>,
    form: Formulation,
    base: usize,
}

impl LaneKernel for ElementLoop<'_, '_> {
    type Output = BatchResult;
    #[inline(always)]
    fn run<const W: usize>(self, isa: LaneIsa<W>) -> BatchResult {
        let mat = self.inp.mat;
        mat.law.with(LawLoop { isa, lp: self })
    }
}

/// [`ElementLoop`] on W lanes, for the batch's hardening law.
struct LawLoop<'a, 'b, const W: usize> {
    isa: LaneIsa<W>,
    lp: ElementLoop<'a, 'b>,
}

impl<const W: usize> LawVisitor for LawLoop<'_, '_, W> {
    type Output = BatchResult;
    #[inline(always)]
    fn visit<H: Hardening>(self, law: &H) -> BatchResult {
        let form = self.lp.form;
        form.with(FormLoop {
            isa: self.isa,
            law,
            lp: self.lp,
        })
    }
}

/// [`LawLoop`] for the batch's formulation: its lane loop ([`Element::lane_loop`]).
struct FormLoop<'a, 'b, 'h, H, const W: usize> {
    isa: LaneIsa<W>,
    law: &'h H,
    lp: ElementLoop<'a, 'b>,
}

impl<H: Hardening, const W: usize> ElementVisitor for FormLoop<'_, '_, '_, H, W> {
    type Output = BatchResult;
    #[inline(always)]
    fn visit<E: Element>(self) -> BatchResult {
        if H::HISTORY == 0 {
            return E::lane_loop(self.isa, self.law, self.lp.b, self.lp.inp, self.lp.base);
        }
        let start: Vec<f64> = self.lp.b.pts.iter().map(|p| p.eps_p).collect();
        let r = E::lane_loop(self.isa, self.law, self.lp.b, self.lp.inp, self.lp.base);
        if r.is_ok() {
            record_history(self.law, self.lp.b, &start, self.lp.inp.dt);
        }
        r
    }
}

/// Hands every point of the batch `b` its step to the law's history: `start` holds each
/// point's ε_p before the step, `dt` is the step (s).
fn record_history<H: Hardening>(law: &H, b: &mut Batch<'_>, start: &[f64], dt: f64) {
    debug_assert_eq!(b.hist.len(), H::HISTORY * b.pts.len());
    for ((p, h), &e0) in b
        .pts
        .iter()
        .zip(b.hist.chunks_exact_mut(H::HISTORY))
        .zip(start)
    {
        law.update_history(h, e0, p.eps_p - e0, dt);
    }
}

/// The slices of `s[range]` a batch of `per_batch` values at a time, or `batches` empty
/// slices when `s` is empty (a state array the block does not keep).
fn batches_of<T: Send>(
    s: &mut [T],
    range: std::ops::Range<usize>,
    per_batch: usize,
    batches: usize,
) -> impl IndexedParallelIterator<Item = &mut [T]> {
    if s.is_empty() {
        Either::Left((0..batches).into_par_iter().map(|_| <&mut [T]>::default()))
    } else {
        Either::Right(s[range].par_chunks_mut(per_batch))
    }
}

/// `s[range]`, or the empty slice when `s` is empty (a state array the block does not keep).
fn range_of<T>(s: &mut [T], range: std::ops::Range<usize>) -> &mut [T] {
    if s.is_empty() {
        &mut []
    } else {
        &mut s[range]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::{batch::ElementStateMut, hex_one_point};
    use crate::material::Material;
    use crate::mesh::ball::{ball, BallSpec, Cut};

    /// The batched lane loop against the per-element kernel on a real (graded, distorted)
    /// ball mesh with a yielding, spinning, hourglass-exciting velocity field, several steps.
    #[test]
    fn lane_loop_matches_per_element_kernel_on_a_ball_mesh() {
        let (mut blk, x0, v) = yielding_block(Formulation::OnePoint, 3000.0);
        let mat = blk.material;
        let n = blk.conn.len();
        let mut refb = blk.clone();
        let mut x = x0;
        let dt = 1e-8;
        let mut f = vec![[[0.0; 3]; 8]; n];
        for step in 0..30 {
            advance(&mut x, &v, dt);
            let (dmin, _) = blk.update(&x, &v, dt, &mut f).unwrap();
            let mut rmin = f64::INFINITY;
            for k in 0..n {
                let c = refb.conn[k];
                let xe = c.map(|i| x[i as usize]);
                let ve = c.map(|i| v[i as usize]);
                let o = hex_one_point::update(
                    &xe,
                    &ve,
                    dt,
                    &mat,
                    0.05,
                    ElementStateMut {
                        points: &mut refb.points[k..k + 1],
                        plastic_work: &mut refb.plastic_work[k],
                        internal_energy: &mut refb.internal_energy[k],
                        hourglass: &mut refb.hourglass[k],
                        hourglass_energy: &mut refb.hourglass_energy[k],
                    },
                );
                rmin = rmin.min(o.dt_crit);
                let scale = o
                    .force
                    .iter()
                    .flatten()
                    .fold(1e-3f64, |m, c| m.max(c.abs()));
                for i in 0..8 {
                    for d in 0..3 {
                        assert!(
                            (f[k][i][d] - o.force[i][d]).abs() < 1e-10 * scale,
                            "step {step} element {k} node {i}: {} vs {}",
                            f[k][i][d],
                            o.force[i][d]
                        );
                    }
                }
                assert!((blk.points[k].eps_p - refb.points[k].eps_p).abs() < 1e-12);
            }
            assert!((dmin - rmin).abs() < 1e-12 * rmin);
        }
        assert!(
            blk.points.iter().any(|p| p.eps_p > 0.0),
            "must yield somewhere"
        );
    }

    /// x += dt v for every node.
    fn advance(x: &mut [[f64; 3]], v: &[[f64; 3]], dt: f64) {
        for (p, u) in x.iter_mut().zip(v) {
            for c in 0..3 {
                p[c] += dt * u[c];
            }
        }
    }

    /// A graded quarter-ball block of `form` elements (its ragged tail exercises the repeated
    /// lanes), its nodes (m) and a yielding, spinning, hourglass-exciting velocity field
    /// (m/s) stretching along x at `gain` (1/s).
    fn yielding_block(
        form: Formulation,
        gain: f64,
    ) -> (ElementBlock, Vec<[f64; 3]>, Vec<[f64; 3]>) {
        let mesh = ball(&BallSpec {
            diameter: 0.02,
            size: 0.004,
            pole_size: Some(0.001),
            cut: Cut::Quarter,
        })
        .unwrap();
        let mat = J2Material::new(&Material::preset("copper-fe").unwrap(), false);
        // Three elements fewer than the mesh: the last lane group of the last batch is then
        // partial at four and at eight lanes (dead lanes repeat the last element).
        let conn = mesh.hexes[..mesh.hexes.len() - 3].to_vec();
        let n = conn.len();
        assert!(
            !(n % BATCH).is_multiple_of(4) && !(n % BATCH).is_multiple_of(8),
            "want a partial last lane group, n = {n}"
        );
        let blk = ElementBlock::new(0, 0, conn, form, mat, 0.05);
        let v = mesh
            .nodes
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let wob = ((i * 7919) % 13) as f64 / 13.0 - 0.5;
                [
                    gain * p[0] - 400.0 * p[1] + 2.0 * wob,
                    -0.5 * gain * p[1] + 400.0 * p[0],
                    -wob,
                ]
            })
            .collect();
        (blk, mesh.nodes, v)
    }

    /// The history seam: a law with history (the test law [`Counting`], linear hardening
    /// that counts each point's plastic steps and keeps its highest plastic strain rate)
    /// gets a history array sized from its declaration, and the element loop feeds it every
    /// point's step on both update paths, both formulations and every kernel path: the
    /// counts and rates are those of the ε_p path of the same run under the bilinear law,
    /// and the history changes no other bit of the state.
    #[test]
    fn a_law_with_history_keeps_it_per_point_through_the_element_loop() {
        use crate::fe::materials::{counting::Counting, Law};
        let dt = 1e-8;
        for form in [Formulation::OnePoint, Formulation::BBar] {
            let (plain, x0, v) = yielding_block(form, 6000.0);
            let Law::Bilinear(bl) = plain.material.law else {
                panic!("copper-fe hardens linearly")
            };
            let mut counting = plain.clone();
            counting.material.law = Law::Counting(Counting(bl));
            let counting = ElementBlock::new(0, 0, counting.conn, form, counting.material, 0.05);
            assert_eq!(plain.history.len(), 0);
            assert_eq!(counting.history.len(), 2 * plain.points.len());
            let n = plain.conn.len();
            // The bilinear run: its state bits, and per point the plastic steps and the
            // highest Δε_p/Δt.
            let mut a = plain.clone();
            let mut x = x0.clone();
            let mut want = vec![[0.0f64; 2]; a.points.len()];
            for _ in 0..20 {
                advance(&mut x, &v, dt);
                let before: Vec<f64> = a.points.iter().map(|p| p.eps_p).collect();
                a.update(&x, &v, dt, &mut vec![[[0.0; 3]; 8]; n]).unwrap();
                for ((w, p), e0) in want.iter_mut().zip(&a.points).zip(before) {
                    let dp = p.eps_p - e0;
                    w[0] += if dp > 0.0 { 1.0 } else { 0.0 };
                    w[1] = w[1].max(dp / dt);
                }
            }
            // A count that is the same everywhere would not show that each point keeps its own.
            assert!(
                want.iter().any(|w| w[0] > 1.0) && want.iter().any(|w| w[0] != want[0][0]),
                "{form:?}: want points that flowed in several steps, and differing counts"
            );
            for &k in &Kernel::all_supported() {
                let (mut b, mut c) = (counting.clone(), counting.clone());
                b.kernel = k;
                c.kernel = k;
                let mut x = x0.clone();
                for _ in 0..20 {
                    advance(&mut x, &v, dt);
                    b.update(&x, &v, dt, &mut vec![[[0.0; 3]; 8]; n]).unwrap();
                    c.update_range_into_nodes(0..n, &x, &v, dt, &mut vec![[0.0; 4]; x.len()])
                        .unwrap();
                }
                let path = k.path();
                for blk in [&b, &c] {
                    assert!(bits(blk) == bits(&a), "{form:?}, {path:?}: state differs");
                    for (p, w) in want.iter().enumerate() {
                        let h = blk.point_history(p);
                        assert_eq!(h[0], w[0], "{form:?}, {path:?}: point {p} plastic steps");
                        assert_eq!(
                            h[1].to_bits(),
                            w[1].to_bits(),
                            "{form:?}, {path:?}: point {p} rate"
                        );
                    }
                }
            }
        }
    }

    fn bits(b: &ElementBlock) -> Vec<u64> {
        let mut out: Vec<u64> = b
            .points
            .iter()
            .flat_map(|p| p.stress.iter().chain([&p.eps_p, &p.volume]))
            .map(|c| c.to_bits())
            .collect();
        for a in [
            &b.plastic_work,
            &b.internal_energy,
            &b.hourglass_energy,
            &b.volume,
            &b.dt_crit,
        ] {
            out.extend(a.iter().map(|c| c.to_bits()));
        }
        out.extend(b.hourglass.iter().flatten().flatten().map(|c| c.to_bits()));
        out
    }

    /// One thread adding forces straight into the nodes gives the same bits as the force
    /// blocks summed per node in element order (the multi-thread path), for both elements,
    /// over steps in which elements yield (the pad component included: it stays +0).
    #[test]
    fn forces_added_into_nodes_equal_gathered_blocks_bit_for_bit() {
        for form in [Formulation::OnePoint, Formulation::BBar] {
            let (mut a, mut x, v) = yielding_block(form, 6000.0);
            let mut b = a.clone();
            let n = a.conn.len();
            let mut blocks = vec![[[0.0; 3]; 8]; n];
            let dt = 1e-8;
            for _ in 0..20 {
                advance(&mut x, &v, dt);
                let da = a.update(&x, &v, dt, &mut blocks).unwrap();
                let mut gathered = vec![[0.0; 4]; x.len()];
                for (e, c) in a.conn.iter().enumerate() {
                    for (i, &node) in c.iter().enumerate() {
                        for d in 0..3 {
                            gathered[node as usize][d] += blocks[e][i][d];
                        }
                    }
                }
                // Padded rows [x, y, z, 0], as the solver's f_int.
                let mut direct = vec![[0.0; 4]; x.len()];
                let db = b
                    .update_range_into_nodes(0..n, &x, &v, dt, &mut direct)
                    .unwrap();
                assert_eq!(da.0.to_bits(), db.0.to_bits());
                assert_eq!(da.1, db.1);
                let fa: Vec<u64> = gathered.iter().flatten().map(|c| c.to_bits()).collect();
                let fb: Vec<u64> = direct.iter().flatten().map(|c| c.to_bits()).collect();
                assert_eq!(fa, fb, "{form:?}: nodal forces differ");
                assert_eq!(bits(&a), bits(&b), "{form:?}: element state differs");
            }
            assert!(
                a.points.iter().any(|p| p.eps_p > 0.0),
                "{form:?} must yield"
            );
        }
    }

    /// Every kernel path this CPU supports (AVX-512 with eight lanes, AVX2 and portable
    /// with four) computes the same forces (as force blocks and added into nodal rows),
    /// critical steps and state, bit for bit, for both elements over yielding steps. On a
    /// CPU with fewer paths the test compares the ones it has.
    #[test]
    fn every_kernel_path_gives_the_same_bits() {
        let paths = Kernel::all_supported();
        assert_eq!(paths.last().map(|k| k.path()), Some(KernelPath::Portable));
        eprintln!(
            "kernel paths on this CPU: {:?}",
            paths.iter().map(|k| k.path()).collect::<Vec<_>>()
        );
        for form in [Formulation::OnePoint, Formulation::BBar] {
            let (blk, x0, v) = yielding_block(form, 6000.0);
            let n = blk.conn.len();
            let dt = 1e-8;
            // (forces as blocks, forces into nodes, final state bits, critical steps) per path.
            let run = |kernel: Kernel| {
                let (mut a, mut b) = (blk.clone(), blk.clone());
                a.kernel = kernel;
                b.kernel = kernel;
                let mut x = x0.clone();
                let (mut fa, mut fb, mut steps) = (Vec::new(), Vec::new(), Vec::new());
                for _ in 0..20 {
                    advance(&mut x, &v, dt);
                    let mut blocks = vec![[[0.0; 3]; 8]; n];
                    let da = a.update(&x, &v, dt, &mut blocks).unwrap();
                    let mut direct = vec![[0.0; 4]; x.len()];
                    let db = b
                        .update_range_into_nodes(0..n, &x, &v, dt, &mut direct)
                        .unwrap();
                    steps.push((da.0.to_bits(), da.1, db.0.to_bits(), db.1));
                    fa.extend(blocks.iter().flatten().flatten().map(|c| c.to_bits()));
                    fb.extend(direct.iter().flatten().map(|c| c.to_bits()));
                }
                assert!(
                    a.points.iter().any(|p| p.eps_p > 0.0),
                    "{form:?} must yield"
                );
                (fa, fb, bits(&a), bits(&b), steps)
            };
            let want = run(Kernel::Portable(crate::fe::simd::Portable));
            for &k in &paths {
                let got = run(k);
                let path = k.path();
                assert!(got.0 == want.0, "{form:?}, {path:?}: force blocks differ");
                assert!(got.1 == want.1, "{form:?}, {path:?}: nodal forces differ");
                assert!(got.2 == want.2, "{form:?}, {path:?}: state differs");
                assert!(got.3 == want.3, "{form:?}, {path:?}: state (nodes) differs");
                assert_eq!(got.4, want.4, "{form:?}, {path:?}: steps differ");
            }
        }
    }
}
