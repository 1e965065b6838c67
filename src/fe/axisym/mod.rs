//! The axisymmetric (meridian-section) model of a head-on impact: the velocities lie on the
//! line of centres, so the two balls (or a ball and a wall) deform as bodies of revolution
//! and the problem is solved on the half-plane r ≥ 0 of the section (r, z).
//!
//! - [`quad`]: geometry of the 4-node ring element (shape functions, ring volume, the
//!   volume-averaged operator, hourglass vector, characteristic length);
//! - [`element`]: its update in two formulations (one point with hourglass control, and
//!   selectively reduced B-bar), through the 3D objective rate and material seam;
//! - [`quad_lanes`]: both updates on W quads at once (SIMD lanes), the same bits;
//! - [`mass`]: lumped ring masses;
//! - [`mass_scaling`]: raised densities of the smallest quads within an added-mass budget;
//! - [`section`]: the model and the explicit loop (Box 6.1), with energy accounting;
//! - [`subcycle`]: multi-time-step integration (power-of-two step classes, nodal partition);
//!
//! The quads run on the lane paths of [`crate::fe::simd`] (eight lanes with AVX-512, four
//! otherwise), W quads of one material and one step at a time; its contacts
//! ([`crate::fe::contact::meridian`]) are scalar.

pub mod element;
pub mod mass;
pub mod mass_scaling;
pub mod quad;
pub mod quad_lanes;
pub mod section;
pub mod subcycle;
