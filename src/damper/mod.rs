//! A discrete-element model of the paper's particle damper (Section 6): rigid spheres
//! (translation and rotation) in a closed rectangular box carried by a single-degree-of-freedom
//! frame, M x'' + c x' + k x = F, where F is the horizontal force of the balls on the box.
//!
//! Contacts (ball-ball and ball-wall) use the contact-law seam ([`crate::analytic::laws`]):
//! each contact keeps its own history (loading or unloading with the turn, the approach speed
//! at first touch, the tangential spring). Velocity-Verlet time stepping with the step from the
//! stiffest contact; cell-list contact detection; an energy ledger that accounts for every
//! joule (frame, balls, contacts, friction, structural damping). The frame's damping ratio is
//! read from its free decay by the logarithmic decrement, as the paper does.
//!
//! This module does not use the finite-element solver.

pub mod cells;
pub mod claims;
pub mod contact;
pub mod decay;
pub mod energy;
pub mod file;
pub mod frame;
pub mod neighbours;
pub mod pairs;
pub mod report;
pub mod run;
pub mod scene;
pub mod sim;
pub mod timestep;

pub use decay::{log_decrement, peaks, Decay, Peak};
pub use energy::Ledger;
pub use frame::Frame;
pub use scene::{BoxSpec, DamperBall, DamperScene, FrameSpec, LawChoice};
pub use sim::{DamperSimulation, Sample};
