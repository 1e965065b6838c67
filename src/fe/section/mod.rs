//! The section model of a head-on impact: the velocities lie on the
//! line of centres, so the two balls (or a ball and a wall) deform as bodies of revolution
//! and the problem is solved on the half-plane r ≥ 0 of the section (r, z).
//!
//! - [`solver`]: the model and its phases of the explicit step (Box 6.1, run by
//!   [`crate::fe::solver::central_difference::step`]), with energy accounting;
//! - [`fine_step`]: its phases of a subcycled fine step (the scheme of [`crate::fe::subcycle`]);
//! - [`mass_scaling`]: raised densities of the smallest quads within an added-mass budget.
//!
//! Its ring elements live with the elements ([`crate::fe::elements::ring`]: geometry, ring
//! masses, the formulations behind one seam, on the lane paths of [`crate::fe::simd`]); its
//! contacts ([`crate::fe::contact::section`]) are scalar.

pub mod fine_step;
pub mod mass_scaling;
pub mod solver;
