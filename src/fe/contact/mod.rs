//! Penalty frictional contact for the explicit solver.
//!
//! - [`rigid_plane::RigidPlane`]: a deformable surface against a rigid, possibly moving plane
//!   (symmetry-reduced normal impact, ball on a wall, quasi-static compression);
//! - [`node_to_segment::SurfacePair`]: two deformable surfaces, symmetric two-pass
//!   node-to-segment (each surface is slave once and master once, each pass weighted ½).
//!
//! - [`section`]: the meridian section's planes (nodal, segment, kinematic) and its
//!   two-boundary node-to-segment pair.
//!
//! All implement [`crate::fe::interaction::Interaction`]. The normal law is a penalty spring
//! ([`penalty`]), optionally with a dashpot; friction is Coulomb with regularised stick and a
//! return mapping ([`friction`]); candidates come from a bounding-box and bucket search
//! ([`search`]); each step's resultants, area, penetration and energies are in
//! [`output::ContactOutput`], booked by each 3D contact's [`ledger::ContactLedger`]; the contact duration is read from the force pulse
//! ([`duration`]); [`mass_damping`] is the dynamic-relaxation damping that settles a slow
//! load to its static answer.

pub mod duration;
pub mod friction;
pub mod law;
pub mod ledger;
pub mod mass_damping;
pub mod node_to_segment;
pub mod output;
pub mod params;
pub mod penalty;
pub mod projection;
pub mod rigid_plane;
pub mod search;
pub mod section;
pub mod step_cache;
pub mod surface;

pub use friction::CoulombFriction;
pub use node_to_segment::SurfacePair;
pub use output::{ContactOutput, ContactProbe, PressureSample};
pub use params::ContactParams;
pub use penalty::PenaltyRule;
pub use rigid_plane::RigidPlane;
pub use surface::ContactSurface;
