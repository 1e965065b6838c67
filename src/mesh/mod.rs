//! Hexahedral meshes of balls: the data type, generators, gmsh I/O, quality checks, VTU output.
//!
//! Node ordering of an 8-node hexahedron follows gmsh and VTK: nodes 0-1-2-3 form the bottom
//! face counter-clockwise seen from outside the top, nodes 4-5-6-7 the top face above them,
//! so the Jacobian is positive for a right-handed element.

pub mod block;
pub mod topology;

use std::collections::BTreeMap;

/// A mesh of 8-node hexahedra with its boundary and named sets. Coordinates in metres.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Node coordinates (x, y, z), m.
    pub nodes: Vec<[f64; 3]>,
    /// Hexahedra as 8 node indices into `nodes` (gmsh/VTK order, positive Jacobian).
    pub hexes: Vec<[u32; 8]>,
    /// Boundary quadrilaterals, each listed once, node order giving an outward normal
    /// by the right-hand rule.
    pub boundary: Vec<[u32; 4]>,
    /// Named node sets (e.g. `contact`, `sym_y`, `sym_z`), sorted node indices.
    pub node_sets: BTreeMap<String, Vec<u32>>,
    /// Named face sets (outward quads), e.g. the contact-candidate patch `contact`.
    pub face_sets: BTreeMap<String, Vec<[u32; 4]>>,
}

impl Mesh {
    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Number of hexahedra.
    pub fn n_elements(&self) -> usize {
        self.hexes.len()
    }
}
