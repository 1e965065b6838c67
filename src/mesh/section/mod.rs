//! Meshes of the section model: the meridian section (r, z) of an axisymmetric body as a
//! [`SectionMesh`], and its geometry (signed quad areas, boundary edges, the section's area and
//! the volume of its solid of revolution about the z axis).
//!
//! The symmetry axis is the z axis (r = 0); a ball is the half-disc r ≥ 0 of its section,
//! centred at the origin, with its contact pole at (r, z) = (0, +R).
//!
//! - [`geometry`]: the mesh type and its measures;
//! - [`ball`]: graded meshes of a ball's section; [`ladder`]: the nested family sized from the
//!   contact radius; [`band`]: finer surface rings at the contact edge;
//! - [`block`]: a block's section (the elastic wall);
//! - [`msh`], [`vtu`]: gmsh files in, ParaView files out.

pub mod ball;
pub mod band;
pub mod block;
pub mod geometry;
pub mod ladder;
pub mod msh;
pub mod vtu;

pub use ball::{ball, SectionSpec};
pub use band::EdgeBand;
pub use block::{block, BlockSpec};
pub use geometry::{
    area, boundary_edges, corner_jacobians, first_moment_r, quad_area, quad_points,
    revolved_volume, SectionMesh,
};
pub use ladder::{ladder_ball, ladder_ball_banded, ladder_pole_size};
