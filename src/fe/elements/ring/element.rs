//! The ring-element seam: what the meridian section's loop needs of an element family (its
//! integration points, its scalar reference update, its update of W quads at once) and the
//! visitor by which [`super::formulation::QuadFormulation::with`] runs code generic over
//! the family.

use super::lanes::{Nodes, Output, State};
use super::state::{QuadOutput, QuadState};
use crate::fe::materials::{Hardening, J2Material};

/// A 4-node ring-element formulation of the section. Both updates take the nodal
/// coordinates x^{n+1} (m, (r, z)), the mid-step velocities v^{n+1/2} (m/s) and the step
/// `dt` (s; 0 evaluates the forces of the current state without advancing it), advance the
/// element's stress state by the objective rate and the material seam, and return the
/// whole ring's internal nodal forces at x^{n+1} with the Courant step. They never fail: an
/// inverted element shows as `min_jacobian` ≤ 0, which the loop refuses.
pub trait RingElement: Copy {
    /// Integration points whose state the element keeps (1 to 4, the first ones of
    /// [`QuadState::points`]).
    const POINTS: usize;

    /// Updates one quad; the reference the lane update reproduces to the bit.
    fn update(
        &self,
        x1: &[[f64; 2]; 4],
        v: &[[f64; 2]; 4],
        dt: f64,
        mat: &J2Material,
        st: &mut QuadState,
    ) -> QuadOutput;

    /// Updates W quads at once (lane l: quad l) with hardening law `law` of `mat`; lane by
    /// lane the same bits as [`RingElement::update`]. `#[inline(always)]` in every
    /// implementation, so that it compiles with the features of the kernel path running it.
    fn update_lanes<H: Hardening, const W: usize>(
        &self,
        x1: &Nodes<W>,
        v: &Nodes<W>,
        dt: f64,
        mat: &J2Material,
        law: &H,
        st: &mut State<W>,
    ) -> Output<W>;
}

/// Code generic over the ring-element type, run by
/// [`super::formulation::QuadFormulation::with`].
pub trait RingVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the concrete element `element`.
    fn visit<E: RingElement>(self, element: E) -> Self::Output;
}
