//! The section's ring elements: 4-node quads of the meridian half-plane r ≥ 0 that stand for
//! whole rings of a body of revolution.
//!
//! - [`shape`]: geometry of the 4-node ring (shape functions, ring volume, the
//!   volume-averaged operator, hourglass vector, characteristic length);
//! - [`mass`]: lumped ring masses;
//! - [`element`]: the seam every formulation implements (scalar update, lane update,
//!   integration points), and [`formulation`]: the registry that names them;
//! - [`one_point`], [`bbar`], [`full`]: the formulations, each with its scalar reference update beside
//!   its lane update (the two four-point ones share theirs, [`four_point`]);
//! - [`state`], [`scalar`], [`lanes`]: the state a quad keeps and what the formulations'
//!   scalar and lane updates share (the lane updates give the scalar bits on every kernel
//!   path).
//!
//! Coordinates map onto the 3D tensor slots as r → x, z → y, θ → z; the objective update and
//! the material seam are the hexahedra's.

pub mod bbar;
pub mod element;
pub mod formulation;
pub mod four_point;
pub mod full;
pub mod lanes;
pub mod mass;
pub mod one_point;
pub mod scalar;
pub mod shape;
pub mod state;

pub use formulation::{update, QuadFormulation};
pub use state::{PointState, QuadOutput, QuadState};
