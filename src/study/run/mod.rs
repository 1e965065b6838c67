//! One scene on one mesh.
//!
//! - [`simulate`]: the FE run (model, reductions, stop rule, reduction to rigid motion);
//! - [`section`]: the run of a head-on scene on the meridian section;
//! - [`section_impact`]: the impact driver and stop rule of a head-on run on the section
//!   (first touch to separation; e, δ_max, duration, peak force, history);
//! - [`force_curve`]: the loading branch F(δ) at equal approach (force_curve.csv);
//! - [`smoothed_force`]: the contact force smoothed in time with its impulse kept;
//! - [`ignored`]: the scene settings the chosen model does not use, one note each;
//! - [`scene`]: one scene, both models side by side, results.json and history.csv;
//! - [`law_compare`]: the scene's `[laws]`, integrated on the run's balls and speeds;
//! - [`quasi_static`]: the static loading-unloading loop of a ball on a rigid plane;
//! - [`snapshots`]: `.vtu` snapshots of a run for ParaView;
//! - [`damper`]: the particle-damper cases of a command, with progress and Ctrl-C.

pub mod damper;
pub mod force_curve;
pub mod history;
pub mod ignored;
pub mod law_compare;
pub mod quasi_static;
pub mod reduction;
pub mod scene;
pub mod section;
pub mod section_impact;
pub mod simulate;
pub mod simulation;
pub mod smoothed_force;
pub mod snapshots;
