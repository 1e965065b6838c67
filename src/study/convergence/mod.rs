//! Convergence: how far a run is from the converged answer.
//!
//! - [`ladder`]: the mesh ladder of a scene and the loop that refines it to a plan;
//! - [`bulk_share`]: the floor of a 3D bar on e whose bulk is short of e's knee;
//! - [`phase_ensemble`]: the section model's converged head-on answer, a mean over ring phases;
//! - [`phase_band`]: the banded family of the converged answers;
//! - [`converged_scene`]: `--tolerance` on a head-on section scene, on the banded family;
//! - [`scene_estimate`]: a scene's run with its error bar (default levels, plan, tolerance);
//! - [`static_ladder`]: a quasi-static loop's numbers with their error bars from a ladder;
//! - [`dynamic_static`]: a head-on impact beside its quasi-static loop, the gap in energies;
//! - [`honesty`]: whether the error estimates hold over a set of head-on cases.

pub mod bulk_share;
pub mod converged_scene;
pub mod dynamic_static;
pub mod honesty;
pub mod ladder;
pub mod phase_band;
pub mod phase_ensemble;
pub mod scene_estimate;
pub mod static_ladder;
