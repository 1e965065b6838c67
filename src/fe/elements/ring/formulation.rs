//! The registry of ring-element formulations: the one enum a section model names its
//! element by, the scene names, and the dispatch from a formulation to code compiled for
//! its element type.
//!
//! Registering a formulation: a variant of [`QuadFormulation`], its name in
//! [`QuadFormulation::NAMES`] and its value in [`QuadFormulation::ALL`], and its arm in
//! [`QuadFormulation::with`]; its code implements [`RingElement`] in a file of its own.
//! Every test written against the registry (the lane paths against the scalar update, the
//! patch tests, the thick spheres) then runs it.

use super::bbar::BBarQuad;
use super::element::{RingElement, RingVisitor};
use super::full::FullQuad;
use super::one_point::{OnePointQuad, DEFAULT_HOURGLASS};
use super::state::{QuadOutput, QuadState};
use crate::fe::materials::J2Material;

/// How the section's 4-node ring quad is integrated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum QuadFormulation {
    /// One stress point with stiffness hourglass control of coefficient ε_hg ≥ 0
    /// (`one-point`, [`OnePointQuad`]).
    OnePoint {
        /// Hourglass coefficient ε_hg (dimensionless, 0.03-0.1 usual).
        hourglass: f64,
    },
    /// 2x2 Gauss points for the deviator, mean dilatation for the volume (`b-bar`,
    /// [`BBarQuad`]).
    SelectiveReduced,
    /// 2x2 Gauss points for the whole strain rate (`full`, [`FullQuad`]; locks in plastic
    /// flow).
    Full,
}

impl Default for QuadFormulation {
    fn default() -> Self {
        QuadFormulation::OnePoint {
            hourglass: DEFAULT_HOURGLASS,
        }
    }
}

impl QuadFormulation {
    /// Every formulation with its default parameters, in the order of
    /// [`QuadFormulation::NAMES`].
    pub const ALL: [QuadFormulation; 3] = [
        QuadFormulation::OnePoint {
            hourglass: DEFAULT_HOURGLASS,
        },
        QuadFormulation::SelectiveReduced,
        QuadFormulation::Full,
    ];

    /// The scene names, in the order of [`QuadFormulation::ALL`].
    pub const NAMES: [&'static str; 3] = ["one-point", "b-bar", "full"];

    /// The scene name.
    pub fn name(self) -> &'static str {
        match self {
            QuadFormulation::OnePoint { .. } => Self::NAMES[0],
            QuadFormulation::SelectiveReduced => Self::NAMES[1],
            QuadFormulation::Full => Self::NAMES[2],
        }
    }

    /// The formulation named `name` with its default parameters, if any.
    pub fn from_name(name: &str) -> Option<QuadFormulation> {
        let k = Self::NAMES.iter().position(|n| *n == name)?;
        Some(Self::ALL[k])
    }

    /// Integration points whose state the element keeps.
    pub fn points(self) -> usize {
        self.with(Points)
    }

    /// Runs `v` with this formulation's element (one match, here, for every generic
    /// caller: the section's loop, the scalar update, the point count).
    #[inline(always)]
    pub fn with<V: RingVisitor>(self, v: V) -> V::Output {
        match self {
            QuadFormulation::OnePoint { hourglass } => v.visit(OnePointQuad { hourglass }),
            QuadFormulation::SelectiveReduced => v.visit(BBarQuad),
            QuadFormulation::Full => v.visit(FullQuad),
        }
    }
}

impl serde::Serialize for QuadFormulation {
    /// As its scene name.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

/// Updates one quad of formulation `form` (the scalar reference, [`RingElement::update`]):
/// nodal coordinates `x1` = x^{n+1} (m), velocities `v` = v^{n+1/2} (m/s), step `dt` (s; 0
/// evaluates the forces of the current state without advancing it), material `mat`, state
/// `st`. Never fails: an inverted quad shows as `min_jacobian` ≤ 0.
#[inline]
pub fn update(
    x1: &[[f64; 2]; 4],
    v: &[[f64; 2]; 4],
    dt: f64,
    mat: &J2Material,
    form: QuadFormulation,
    st: &mut QuadState,
) -> QuadOutput {
    form.with(Scalar { x1, v, dt, mat, st })
}

/// [`update`] as a visitor.
struct Scalar<'a> {
    x1: &'a [[f64; 2]; 4],
    v: &'a [[f64; 2]; 4],
    dt: f64,
    mat: &'a J2Material,
    st: &'a mut QuadState,
}

impl RingVisitor for Scalar<'_> {
    type Output = QuadOutput;
    #[inline(always)]
    fn visit<E: RingElement>(self, element: E) -> QuadOutput {
        element.update(self.x1, self.v, self.dt, self.mat, self.st)
    }
}

/// [`QuadFormulation::points`] as a visitor.
struct Points;

impl RingVisitor for Points {
    type Output = usize;
    fn visit<E: RingElement>(self, _: E) -> usize {
        E::POINTS
    }
}
