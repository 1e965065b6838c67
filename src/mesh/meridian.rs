//! Meshes of the meridian section (r, z) of an axisymmetric body: the data type the
//! axisymmetric solver takes.
//!
//! The symmetry axis is the z axis (r = 0); a ball is the half-disc r ≥ 0 of its section,
//! centred at the origin, with its contact pole at (r, z) = (0, +R).

use std::collections::BTreeMap;

pub use super::meridian_ball::{ball, SectionSpec};
pub use super::meridian_band::EdgeBand;
pub use super::meridian_block::{block, BlockSpec};
pub use super::meridian_ladder::{ladder_ball, ladder_ball_banded, ladder_pole_size};

/// A mesh of 4-node quadrilaterals on the meridian half-plane r ≥ 0. Coordinates in metres.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeridianMesh {
    /// Node coordinates (r, z), m; r ≥ 0, and nodes on the axis have r = 0 exactly.
    pub nodes: Vec<[f64; 2]>,
    /// Quadrilaterals as 4 node indices, counter-clockwise in the (r, z) plane (positive area).
    pub quads: Vec<[u32; 4]>,
    /// Boundary segments off the axis, each listed once, ordered counter-clockwise around the
    /// section (the body lies to the left of each segment, the outward normal to the right).
    pub boundary: Vec<[u32; 2]>,
    /// Named node sets (`axis`: nodes with r = 0; `surface`; `contact`), sorted node indices.
    pub node_sets: BTreeMap<String, Vec<u32>>,
    /// Named segment sets (`surface`: the spherical boundary; `contact`: its part near the
    /// pole), with the orientation of `boundary`.
    pub segment_sets: BTreeMap<String, Vec<[u32; 2]>>,
}
