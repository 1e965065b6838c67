//! The two-ball study: FE beside the analytical model for one scene or for a whole sweep.
//!
//! - [`outcome`]: the quantities both models produce, and the analytical answer for a scene;
//! - [`bench`]: run time against error on a mesh/element/time-step ladder;
//! - [`bench_kernel`]: the explicit step's cost per element, threads, determinism;
//! - [`bench_profile`]: where a scene's run spends its wall time, phase by phase;
//! - [`bench_machine`]: this machine's ceilings (FMA throughput, memory bandwidth);
//! - [`sweep`]: resumable, shardable parameter sweeps (the paper's ANSYS study);
//! - [`cost`]: estimated cost of a case, shards balanced by it;
//! - [`curves`]: contact-history CSV files of the analytical model and the law integrator;
//! - [`slurm`]: a sweep as a Slurm job array;
//! - [`sweep_status`]: cases done, failed, running and missing in a sweep folder;
//! - [`simulate`]: the FE run (model, reductions, stop rule, reduction to rigid motion);
//! - [`single`]: one scene, both models side by side, results.json and history.csv;
//! - [`plots`]: SVG charts for the report;
//! - [`figures`]: CSV and SVG files of the paper's parametric figures;
//! - [`law_fit_files`]: the files of a contact-law fit (JSON, e(v) table, DEM snippets);
//! - [`snapshots`]: `.vtu` snapshots of a run for ParaView;
//! - [`progress`]: progress on stderr (a bar on a terminal, plain lines elsewhere);
//! - [`interrupt`]: Ctrl-C stops a job cleanly;
//! - [`warnings`]: results a user should not trust blindly, each said in one line.

pub mod bench;
pub mod bench_kernel;
pub mod bench_machine;
pub mod bench_profile;
pub mod cost;
pub mod curves;
pub mod figures;
pub mod interrupt;
pub mod law_fit_files;
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
