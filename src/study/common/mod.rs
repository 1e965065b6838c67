//! What every room of the study uses.
//!
//! - [`progress`]: progress on stderr (a bar on a terminal, plain lines elsewhere);
//! - [`interrupt`]: Ctrl-C stops a job cleanly;
//! - [`plots`]: small SVG line and point charts;
//! - [`scoped`]: a thread-local value for the length of a call.

pub mod interrupt;
pub mod plots;
pub mod progress;
pub mod scoped;
