//! What the explicit solver is given: parts (each a mesh with one material and one element
//! formulation) merged into one global node and element numbering, symmetry constraints and
//! initial velocities.

use super::solver::mass::element_lumped_mass;
use super::tensor::cross;
use crate::error::{Error, Result};
use crate::material::Material;
use crate::mesh::Mesh;
use std::collections::BTreeMap;
use std::ops::Range;

pub use super::elements::Formulation;

/// One part: a contiguous range of nodes and elements with one material and formulation.
#[derive(Debug, Clone)]
pub struct Part {
    /// Name for reports (e.g. `ball1`).
    pub name: String,
    /// Material.
    pub material: Material,
    /// Element formulation.
    pub formulation: Formulation,
    /// Skip plasticity (elastic-only fast path).
    pub elastic_only: bool,
    /// Global node indices of this part.
    pub nodes: Range<usize>,
    /// Global element indices of this part.
    pub elements: Range<usize>,
    /// The mesh's node sets in global numbering.
    pub node_sets: BTreeMap<String, Vec<u32>>,
    /// The mesh's face sets (outward quads) in global numbering.
    pub face_sets: BTreeMap<String, Vec<[u32; 4]>>,
    /// The mesh's boundary quads in global numbering.
    pub boundary: Vec<[u32; 4]>,
}

/// The whole model: merged mesh, parts, constraints and initial conditions.
#[derive(Debug, Clone, Default)]
pub struct Model {
    /// Reference nodal coordinates, m.
    pub nodes: Vec<[f64; 3]>,
    /// Hexahedra in global node numbering.
    pub hexes: Vec<[u32; 8]>,
    /// Parts, in the order added; part p owns `parts[p].elements`.
    pub parts: Vec<Part>,
    /// Velocity constraints: (node, axis 0..3) whose velocity component is held at zero
    /// (symmetry planes).
    pub fixed: Vec<(u32, u8)>,
    /// Initial nodal velocities v^0, m/s.
    pub velocity: Vec<[f64; 3]>,
}

impl Model {
    /// An empty model.
    pub fn new() -> Self {
        Self::default()
    }

    /// Appends `mesh` as a new part; returns its index. Node and face sets keep their names,
    /// renumbered globally. Fails if the material is invalid or the mesh is empty.
    pub fn add_part(
        &mut self,
        name: &str,
        mesh: &Mesh,
        material: Material,
        formulation: Formulation,
    ) -> Result<usize> {
        let material = material.validated(&format!("{name}.material"))?;
        if mesh.hexes.is_empty() {
            return Err(Error::invalid(
                format!("{name}.mesh"),
                "0 elements",
                "at least one hexahedron",
            ));
        }
        let n0 = self.nodes.len();
        let e0 = self.hexes.len();
        let off = n0 as u32;
        for h in &mesh.hexes {
            if h.iter().any(|&i| i as usize >= mesh.nodes.len()) {
                return Err(Error::invalid(
                    format!("{name}.mesh.hexes"),
                    format!("{h:?}"),
                    format!("node indices below {}", mesh.nodes.len()),
                ));
            }
        }
        self.nodes.extend_from_slice(&mesh.nodes);
        self.velocity
            .extend(std::iter::repeat_n([0.0; 3], mesh.nodes.len()));
        self.hexes
            .extend(mesh.hexes.iter().map(|h| h.map(|i| i + off)));
        let shift4 = |q: &[u32; 4]| q.map(|i| i + off);
        self.parts.push(Part {
            name: name.to_string(),
            material,
            formulation,
            elastic_only: false,
            nodes: n0..self.nodes.len(),
            elements: e0..self.hexes.len(),
            node_sets: mesh
                .node_sets
                .iter()
                .map(|(k, v)| (k.clone(), v.iter().map(|i| i + off).collect()))
                .collect(),
            face_sets: mesh
                .face_sets
                .iter()
                .map(|(k, v)| (k.clone(), v.iter().map(shift4).collect()))
                .collect(),
            boundary: mesh.boundary.iter().map(shift4).collect(),
        });
        Ok(self.parts.len() - 1)
    }

    /// Holds velocity component `axis` (0 = x, 1 = y, 2 = z) at zero on the part's node set
    /// `set` (a symmetry plane normal to that axis). Fails if the part or set does not exist.
    pub fn fix_set(&mut self, part: usize, set: &str, axis: usize) -> Result<()> {
        let p = self.part(part)?;
        let nodes = p.node_sets.get(set).ok_or_else(|| {
            Error::invalid(
                format!("{}.node_set", p.name),
                set,
                format!("one of {:?}", p.node_sets.keys().collect::<Vec<_>>()),
            )
        })?;
        if axis > 2 {
            return Err(Error::invalid("axis", axis, "0, 1 or 2"));
        }
        let add: Vec<(u32, u8)> = nodes.iter().map(|&n| (n, axis as u8)).collect();
        self.fixed.extend(add);
        Ok(())
    }

    /// Sets the initial velocity of every node of `part` to the rigid field
    /// v = v0 + ω × (x − centre) (m/s, rad/s, m).
    pub fn set_rigid_velocity(
        &mut self,
        part: usize,
        v0: [f64; 3],
        omega: [f64; 3],
        centre: [f64; 3],
    ) -> Result<()> {
        let range = self.part(part)?.nodes.clone();
        for n in range {
            let r = [0, 1, 2].map(|k| self.nodes[n][k] - centre[k]);
            let w = cross(omega, r);
            self.velocity[n] = [v0[0] + w[0], v0[1] + w[1], v0[2] + w[2]];
        }
        Ok(())
    }

    /// Centre of mass (m) of `part` under the lumped masses the explicit solver uses, so a rigid
    /// velocity about it leaves the part's momentum at the translation alone. Errors: an unknown
    /// part, an inverted element.
    pub fn centre_of_mass(&self, part: usize) -> Result<[f64; 3]> {
        let p = self.part(part)?;
        let (mut mass, mut moment) = (0.0, [0.0; 3]);
        for e in p.elements.clone() {
            let x = self.hexes[e].map(|n| self.nodes[n as usize]);
            let m = element_lumped_mass(&x, p.material.rho)?;
            for (xi, mi) in x.iter().zip(m) {
                mass += mi;
                for k in 0..3 {
                    moment[k] += mi * xi[k];
                }
            }
        }
        Ok(moment.map(|c| c / mass))
    }

    /// Sets the initial velocity of every node of `part` from a field `f(x)` (m/s).
    pub fn set_velocity_field(
        &mut self,
        part: usize,
        f: impl Fn([f64; 3]) -> [f64; 3],
    ) -> Result<()> {
        let range = self.part(part)?.nodes.clone();
        for n in range {
            self.velocity[n] = f(self.nodes[n]);
        }
        Ok(())
    }

    /// The part with index `p`, or an error.
    pub fn part(&self, p: usize) -> Result<&Part> {
        self.parts
            .get(p)
            .ok_or_else(|| Error::invalid("part", p, format!("0..{}", self.parts.len())))
    }

    /// Mutable access to part `p` (e.g. to set `elastic_only`).
    pub fn part_mut(&mut self, p: usize) -> Result<&mut Part> {
        let n = self.parts.len();
        self.parts
            .get_mut(p)
            .ok_or_else(|| Error::invalid("part", p, format!("0..{n}")))
    }
}
