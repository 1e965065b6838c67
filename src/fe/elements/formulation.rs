//! The registry of element formulations: the one enum a part names its formulation by, its
//! scene names, and the dispatch from a part's formulation to code compiled for it.
//!
//! Registering a formulation: a variant of [`Formulation`], its name in
//! [`Formulation::NAMES`], and its arm in [`Formulation::with`]; its code implements
//! [`Element`] beside its kernels.

use super::{
    block::{Batch, BatchResult, ElementBlock, StepInput},
    hex_bbar_lanes::BBarHex,
    hex_one_point_lanes::OnePointHex,
};
use crate::fe::materials::Hardening;
use crate::fe::simd::{LaneIsa, Vec3};

/// Element formulation of a part. Plain 2x2x2 integration is deliberately absent: it locks
/// in plastic (isochoric) flow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Formulation {
    /// One-point Flanagan-Belytschko hex with stiffness hourglass control (`one-point`).
    #[default]
    OnePoint,
    /// 2x2x2 hex with B-bar (mean dilatation) volumetric strain (`b-bar`).
    BBar,
}

impl Formulation {
    /// Every formulation, in the order of [`Formulation::NAMES`].
    pub const ALL: [Formulation; 2] = [Formulation::OnePoint, Formulation::BBar];

    /// The scene and command-line names, in the order of [`Formulation::ALL`].
    pub const NAMES: [&'static str; 2] = ["one-point", "b-bar"];

    /// The scene name (`one-point`, `b-bar`).
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The formulation named `name`, if any.
    pub fn from_name(name: &str) -> Option<Formulation> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }

    /// Integration points per element.
    pub fn points(self) -> usize {
        self.with(Points)
    }

    /// Runs `v` with this formulation's element type (one match, here, for every generic
    /// caller: the element loop, its kernel timing, the point count).
    #[inline(always)]
    pub(crate) fn with<V: ElementVisitor>(self, v: V) -> V::Output {
        match self {
            Formulation::OnePoint => v.visit::<OnePointHex>(),
            Formulation::BBar => v.visit::<BBarHex>(),
        }
    }
}

/// What the element loop needs of a formulation: its integration points per element, its
/// lane loop over one batch, and the timing of its lane kernel's arithmetic alone. Both
/// lane functions are `#[inline(always)]`, so that they compile with the features of the
/// kernel path that runs them ([`crate::fe::simd::Simd::vectorize`]).
pub(crate) trait Element {
    /// Integration points per element (rows of the block's point array).
    const POINTS: usize;

    /// Advances the batch `b` W elements at a time with hardening law `law`: gathers nodes
    /// and state into lanes, updates, scatters state and forces back, checks each element.
    #[allow(clippy::too_many_arguments)]
    fn lane_loop<H: Hardening, const W: usize>(
        isa: LaneIsa<W>,
        law: &H,
        b: &mut Batch<'_>,
        inp: StepInput<'_>,
        base: usize,
    ) -> BatchResult;

    /// Time of `repeats` updates of the first lane group of `b` (local elements `idx`,
    /// nodal lanes `xe` in m and `ve` in m/s, step `dt` in s), state restarted every 64.
    #[allow(clippy::too_many_arguments)]
    fn time_arithmetic<H: Hardening, const W: usize>(
        isa: LaneIsa<W>,
        law: &H,
        b: &ElementBlock,
        xe: &[Vec3<W>; 8],
        ve: &[Vec3<W>; 8],
        idx: &[usize; W],
        dt: f64,
        repeats: u32,
    ) -> std::time::Duration;
}

/// Code generic over the element type, run by [`Formulation::with`].
pub(crate) trait ElementVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the concrete element type.
    fn visit<E: Element>(self) -> Self::Output;
}

/// [`Formulation::points`] as a visitor.
struct Points;

impl ElementVisitor for Points {
    type Output = usize;
    fn visit<E: Element>(self) -> usize {
        E::POINTS
    }
}
