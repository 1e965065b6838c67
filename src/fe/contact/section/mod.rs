//! Contacts of the meridian section (r, z; forces of whole rings), on the same
//! [`crate::fe::interaction::Interaction`] seam as the 3D contacts:
//!
//! - [`plane_nodal`]: penalty contact against a rigid plane z = const, a spring per node;
//! - [`plane_segment`]: the same plane with the penalty pressure integrated over each
//!   boundary segment (the contact area grows continuously);
//! - [`plane_kinematic`]: the same plane as a unilateral kinematic constraint (no penalty);
//! - [`segment`]: two-pass node-to-segment penalty contact of two meridian boundaries.

pub mod plane_kinematic;
pub mod plane_nodal;
pub mod plane_segment;
pub mod segment;
