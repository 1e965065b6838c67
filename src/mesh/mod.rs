//! Hexahedral meshes of balls: the data type, generators, gmsh I/O, quality checks, VTU output.
//!
//! Node ordering of an 8-node hexahedron follows gmsh and VTK: nodes 0-1-2-3 form the bottom
//! face counter-clockwise seen from outside the top, nodes 4-5-6-7 the top face above them,
//! so the Jacobian is positive for a right-handed element.

pub mod ball;
pub mod block;
pub mod cut;
pub mod gmsh;
pub mod msh;
pub mod points_vtu;
pub mod quality;
pub mod section;
pub mod topology;
pub mod vtu;

use crate::error::{Error, Result};
use std::collections::BTreeMap;

/// Natural coordinates (ξ, η, ζ) of the eight nodes of a hexahedron, in gmsh/VTK order.
pub const HEX_NODE_XI: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// Fails on the first node of `nodes` (coordinates, m) that is not finite: a mesh file never
/// holds one.
pub(crate) fn check_finite_nodes(nodes: &[[f64; 3]]) -> Result<()> {
    match nodes.iter().position(|p| !p.iter().all(|v| v.is_finite())) {
        Some(i) => Err(Error::Numerical(format!(
            "mesh node {i} is not finite; not written"
        ))),
        None => Ok(()),
    }
}

/// The hexahedra of a structured block of `cells` = [n_i, n_j, n_k] cells, i fastest, with
/// node numbers `id(i, j, k)` for i ≤ n_i, j ≤ n_j, k ≤ n_k (gmsh/VTK node order).
pub(crate) fn structured_hexes(
    cells: [usize; 3],
    id: impl Fn(usize, usize, usize) -> u32,
) -> Vec<[u32; 8]> {
    let mut hexes = Vec::with_capacity(cells.iter().product());
    for k in 0..cells[2] {
        for j in 0..cells[1] {
            for i in 0..cells[0] {
                hexes.push([
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ]);
            }
        }
    }
    hexes
}

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

    /// A copy reflected in the plane x = 0 (x -> -x). A reflection turns every element
    /// inside out, so the hex node order is reversed (0-3-2-1 / 4-7-6-5) to keep the Jacobian
    /// positive, and boundary and face-set quads are reversed to keep pointing outward.
    /// Node sets keep their names and members (node numbering is unchanged).
    pub fn mirrored_x(&self) -> Mesh {
        let flip_quad = |q: &[u32; 4]| [q[0], q[3], q[2], q[1]];
        Mesh {
            nodes: self.nodes.iter().map(|p| [-p[0], p[1], p[2]]).collect(),
            hexes: self
                .hexes
                .iter()
                .map(|h| [h[0], h[3], h[2], h[1], h[4], h[7], h[6], h[5]])
                .collect(),
            boundary: self.boundary.iter().map(flip_quad).collect(),
            node_sets: self.node_sets.clone(),
            face_sets: self
                .face_sets
                .iter()
                .map(|(k, v)| (k.clone(), v.iter().map(flip_quad).collect()))
                .collect(),
        }
    }

    /// A copy moved rigidly by `offset` (m). Topology and sets are unchanged.
    pub fn translated(&self, offset: [f64; 3]) -> Mesh {
        let mut m = self.clone();
        for p in &mut m.nodes {
            for a in 0..3 {
                p[a] += offset[a];
            }
        }
        m
    }

    /// Renames every node and face set `name` to `prefix.name` (e.g. `ball1.contact`), so
    /// two bodies can share one mesh without their sets colliding.
    pub fn prefix_sets(&mut self, prefix: &str) {
        let rename = |k: &String| format!("{prefix}.{k}");
        self.node_sets = std::mem::take(&mut self.node_sets)
            .into_iter()
            .map(|(k, v)| (rename(&k), v))
            .collect();
        self.face_sets = std::mem::take(&mut self.face_sets)
            .into_iter()
            .map(|(k, v)| (rename(&k), v))
            .collect();
    }

    /// Appends `other` as a separate body with one global numbering: its nodes follow ours,
    /// its elements follow ours, its boundary quads join ours, and its sets are added as
    /// `prefix.name` (an empty prefix keeps the names; an existing set of the same name is
    /// extended). Returns `(node_offset, element_offset)`: node `i` of `other` is node
    /// `node_offset + i` of the result, element `e` is element `element_offset + e`.
    ///
    /// Fails if the combined node count no longer fits the `u32` node indices.
    pub fn append(&mut self, other: &Mesh, prefix: &str) -> crate::Result<(usize, usize)> {
        let node_offset = self.nodes.len();
        let element_offset = self.hexes.len();
        if node_offset + other.nodes.len() > u32::MAX as usize {
            return Err(crate::Error::invalid(
                "mesh.nodes",
                node_offset + other.nodes.len(),
                format!("at most {} nodes", u32::MAX),
            ));
        }
        let off = node_offset as u32;
        let shift4 = |q: &[u32; 4]| q.map(|i| i + off);
        self.nodes.extend_from_slice(&other.nodes);
        self.hexes
            .extend(other.hexes.iter().map(|h| h.map(|i| i + off)));
        self.boundary.extend(other.boundary.iter().map(shift4));
        let name = |k: &String| {
            if prefix.is_empty() {
                k.clone()
            } else {
                format!("{prefix}.{k}")
            }
        };
        for (k, v) in &other.node_sets {
            let set = self.node_sets.entry(name(k)).or_default();
            set.extend(v.iter().map(|i| i + off));
            set.sort_unstable();
            set.dedup();
        }
        for (k, v) in &other.face_sets {
            self.face_sets
                .entry(name(k))
                .or_default()
                .extend(v.iter().map(shift4));
        }
        Ok((node_offset, element_offset))
    }
}
