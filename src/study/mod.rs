//! The two-ball study: FE beside the analytical model for one scene or for a whole sweep.
//!
//! Rooms, each calling only the rooms listed before it:
//! - [`records`]: what every room passes around: an outcome, a case, a value with its error
//!   bar, a run's error estimate, warnings, numbers for people;
//! - [`common`]: progress on stderr, Ctrl-C and SVG charts, for every room;
//! - [`run`]: one scene on one mesh: the model chosen, the FE run, results.json, history.csv;
//! - [`convergence`]: the mesh ladder and its refine loop, phase ensembles, the banded
//!   family (`--tolerance`), a scene's run with its error bar, the honesty check;
//! - [`sweep`]: resumable, shardable parameter sweeps with Slurm, cost and similarity;
//! - [`bench`]: run time against error, kernels, the machine, phase profiles, the
//!   robustness matrix; [`laws_bench`]: every contact law against cached FE;
//! - [`report`]: the verification report, charts and figure files.

pub mod bench;
pub mod common;
pub mod convergence;
pub mod laws_bench;
pub mod records;
pub mod report;
pub mod run;
pub mod sweep;
