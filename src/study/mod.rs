//! The two-ball study: FE beside the analytical model for one scene or for a whole sweep.
//!
//! - [`outcome`]: the quantities both models produce, and the analytical answer for a scene;
//! - [`bench`]: run time against error on a mesh/element/time-step ladder;
//! - [`sweep`]: resumable, shardable parameter sweeps (the paper's ANSYS study);
//! - [`simulate`]: the FE run (model, reductions, stop rule, reduction to rigid motion);
//! - [`single`]: one scene, both models side by side, results.json and history.csv;
//! - [`plots`]: SVG charts for the report;
//! - [`figures`]: CSV and SVG files of the paper's parametric figures;
//! - [`snapshots`]: `.vtu` snapshots of a run for ParaView;
//! - [`atomic`]: crash-safe file output;
//! - [`progress`]: the terminal progress bar.

pub mod bench;
pub mod figures;
pub mod outcome;
pub mod plots;
pub mod progress;
pub mod report;
pub mod simulate;
pub mod single;
pub mod snapshots;
pub mod stress;
pub mod sweep;
