//! Elements: the element block with its loop ([`block`]), the seam every element family
//! implements with the lane loop written once for all ([`element`]), what the loop hands a
//! family and takes back ([`batch`]: the gather of nodal lanes, the check and scatter of a
//! lane group) and the lane state with its one load and store ([`lane_state`]), and each
//! hexahedron formulation with its scalar reference kernel beside its lane
//! kernel ([`hex_one_point`] and [`hex_one_point_lanes`], [`hex_bbar`] and
//! [`hex_bbar_lanes`]), on the shape functions ([`shape`]) and objective rates
//! ([`objective`]). A formulation is registered in [`formulation`]: the one place that maps
//! its name to its code. Imports run one way: block → formulation → families → element,
//! batch.

pub mod batch;
pub mod block;
pub mod element;
pub mod formulation;
pub mod hex_bbar;
pub mod hex_bbar_lanes;
pub mod hex_one_point;
pub mod hex_one_point_lanes;
pub mod lane_state;
pub mod objective;
pub mod ring;
pub mod shape;

pub use block::*;
pub use formulation::Formulation;
