//! The two-ball study: FE beside the analytical model for one scene or for a whole sweep.
//!
//! - [`outcome`]: the quantities both models produce, and the analytical answer for a scene;
//! - [`sweep`]: resumable, shardable parameter sweeps (the paper's ANSYS study);
//! - [`atomic`]: crash-safe file output.

pub mod atomic;
pub mod outcome;
pub mod sweep;
