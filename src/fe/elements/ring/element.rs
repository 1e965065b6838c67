//! The ring-element seam: what the meridian section's loop needs of an element family (its
//! integration points, its scalar reference update, its update of W quads at once) and the
//! visitor by which [`super::formulation::QuadFormulation::with`] runs code generic over
//! the family.

use super::lanes::{Nodes, RingLaneOutput, RingLaneState};
use super::state::{QuadOutput, QuadState};
use crate::fe::materials::{Hardening, J2Material};

/// The nodal (r, z) pairs of one quad, m or m/s.
pub type Quad = [[f64; 2]; 4];

/// One step of one quad (`N` = [`Quad`]) or of W quads at once (`N` = [`Nodes<W>`]): the
/// nodal coordinates x^{n+1} (m, (r, z)), the mid-step velocities v^{n+1/2} (m/s), the step
/// (s; 0 evaluates the forces of the current state without advancing it) and the material.
#[derive(Clone, Copy)]
pub struct Step<'a, N> {
    /// Nodal coordinates x^{n+1}, m.
    pub x1: &'a N,
    /// Nodal velocities v^{n+1/2}, m/s.
    pub v: &'a N,
    /// The step, s.
    pub dt: f64,
    /// The material.
    pub mat: &'a J2Material,
}

/// A step of W quads with the material's hardening law `law` (the lane kernels are generic
/// over it).
#[derive(Clone, Copy)]
pub struct LaneStep<'a, H, const W: usize> {
    /// The step.
    pub step: Step<'a, Nodes<W>>,
    /// The material's hardening law.
    pub law: &'a H,
}

/// A 4-node ring-element formulation of the section. Both updates advance the element's
/// stress state by the objective rate and the material seam over a [`Step`] and return the
/// whole ring's internal nodal forces at x^{n+1} with the Courant step. They never fail: an
/// inverted element shows as `min_jacobian` ≤ 0, which the loop refuses.
pub trait RingElement: Copy {
    /// Integration points whose state the element keeps (1 to 4, the first ones of
    /// [`QuadState::points`]).
    const POINTS: usize;

    /// Updates one quad; the reference the lane update reproduces to the bit.
    fn update(&self, s: Step<'_, Quad>, st: &mut QuadState) -> QuadOutput;

    /// Updates W quads at once (lane l: quad l); lane by lane the same bits as
    /// [`RingElement::update`]. `#[inline(always)]` in every implementation, so that it
    /// compiles with the features of the kernel path running it.
    fn update_lanes<H: Hardening, const W: usize>(
        &self,
        s: LaneStep<'_, H, W>,
        st: &mut RingLaneState<W>,
    ) -> RingLaneOutput<W>;
}

/// Code generic over the ring-element type, run by
/// [`super::formulation::QuadFormulation::with`].
pub trait RingVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the concrete element `element`.
    fn visit<E: RingElement>(self, element: E) -> Self::Output;
}
