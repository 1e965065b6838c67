//! The records every room of the study passes around.
//!
//! - [`outcome`]: the quantities both models produce, and the analytical answer for a scene;
//! - [`case`]: a finished FE run as sweep and bench records hold it;
//! - [`case_cache`]: the resumable folder of finished cases that sweeps and benches share;
//! - [`estimate`]: a value with its error bar, from a mesh ladder (Richardson, GCI);
//! - [`error_estimate`]: a run's error estimate as results.json writes it;
//! - [`tangential`]: the tangential restitution and the angles of an oblique impact;
//! - [`warnings`]: results a user should not trust blindly, each said in one line;
//! - [`number`]: numbers for people.

pub mod case;
pub mod case_cache;
pub mod error_estimate;
pub mod estimate;
pub mod number;
pub mod outcome;
pub mod tangential;
pub mod warnings;
