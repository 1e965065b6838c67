//! The two-ball study: FE beside the analytical model for one scene or for a whole sweep.
//!
//! - [`outcome`]: the quantities both models produce, and the analytical answer for a scene;
//! - [`bench`]: run time against error on a mesh/element/time-step ladder;
//! - [`convergence`]: Richardson extrapolation, observed order and error estimates of a ladder;
//! - [`sweep`]: resumable, shardable parameter sweeps (the paper's ANSYS study);
//! - [`cost`]: estimated cost of a case, shards balanced by it;
//! - [`error_estimate`]: a run's own error bar from a mesh ladder (a run closure per level);
//! - [`error_honesty`]: whether the error estimates hold over a set of head-on cases;
//! - [`slurm`]: a sweep as a Slurm job array;
//! - [`sweep_status`]: cases done, failed, running and missing in a sweep folder;
//! - [`simulate`]: the FE run (model, reductions, stop rule, reduction to rigid motion);
//! - [`single`]: one scene, both models side by side, results.json and history.csv;
//! - [`plots`]: SVG charts for the report;
//! - [`figures`]: CSV and SVG files of the paper's parametric figures;
//! - [`snapshots`]: `.vtu` snapshots of a run for ParaView;
//! - [`atomic`]: crash-safe file output;
//! - [`progress`]: progress on stderr (a bar on a terminal, plain lines elsewhere);
//! - [`interrupt`]: Ctrl-C stops a job cleanly;
//! - [`warnings`]: results a user should not trust blindly, each said in one line.

pub mod bench;
pub mod convergence;
pub mod cost;
pub mod error_estimate;
pub mod error_honesty;
pub mod figures;
pub mod interrupt;
pub mod number;
pub mod outcome;
pub mod plots;
pub mod progress;
pub mod report;
pub mod simulate;
pub mod single;
pub mod slurm;
pub mod snapshots;
pub mod stress;
pub mod sweep;
pub mod sweep_status;
pub mod warnings;
