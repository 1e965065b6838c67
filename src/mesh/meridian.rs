//! Meshes of the meridian section (r, z) of an axisymmetric body: the data type the
//! axisymmetric solver takes.
//!
//! The symmetry axis is the z axis (r = 0); a ball is the half-disc r ≥ 0 of its section,
//! centred at the origin, with its contact pole at (r, z) = (0, +R).

pub use super::meridian_ball::{ball, SectionSpec};
pub use super::meridian_band::EdgeBand;
pub use super::meridian_block::{block, BlockSpec};
pub use super::meridian_ladder::{ladder_ball, ladder_ball_banded, ladder_pole_size};
pub use super::section::MeridianMesh;
