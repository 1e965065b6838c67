//! The registry of element formulations: the one enum a part names its formulation by, its
//! scene names, and the dispatch from a part's formulation to code compiled for it.
//!
//! Registering a formulation: a variant of [`Formulation`], its name in
//! [`Formulation::NAMES`], and its arm in [`Formulation::with`]; its code implements
//! [`Element`] beside its kernels.

use super::{
    element::{Element, ElementVisitor},
    hex_bbar_lanes::BBarHex,
    hex_one_point_lanes::OnePointHex,
};

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

    /// Whether its elements keep hourglass forces and energy.
    pub fn has_hourglass(self) -> bool {
        self.with(HasHourglass)
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

/// [`Formulation::points`] as a visitor.
struct Points;

impl ElementVisitor for Points {
    type Output = usize;
    fn visit<E: Element>(self) -> usize {
        E::POINTS
    }
}

/// [`Formulation::has_hourglass`] as a visitor.
struct HasHourglass;

impl ElementVisitor for HasHourglass {
    type Output = bool;
    fn visit<E: Element>(self) -> bool {
        E::HOURGLASS
    }
}
