//! A contact surface: the quads that can touch, their nodes and each node's share of area and
//! of the solid underneath (what the penalty stiffness is scaled by).

use super::law::NodeLaw;
use super::params::ContactParams;
use crate::error::{Error, Result};
use crate::fe::solver::timestep::characteristic_length;
use crate::fe::tensor::{quad_area, sub};
use crate::mesh::topology::HEX_FACES;
use std::collections::HashMap;

/// The candidate contact patch of one body, with per-node geometric weights in the reference
/// configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSurface {
    /// Outward quads (global node numbers), as in the mesh face set.
    pub faces: Vec<[u32; 4]>,
    /// Distinct nodes of `faces`, sorted (global node numbers).
    pub nodes: Vec<u32>,
    /// Tributary area of each node of `nodes` (a quarter of each adjacent quad), m².
    pub area: Vec<f64>,
    /// Thickness h of the solid under each node (element volume / face area, area-weighted
    /// mean over the node's quads), m.
    pub thickness: Vec<f64>,
    /// Volume of the solid under each node (area-weighted mean element volume), m³.
    pub volume: Vec<f64>,
    /// Thickness of the solid element under each quad (volume / face area), m.
    pub face_thickness: Vec<f64>,
    /// Smallest edge length of the quads, m (sets search margins and penetration limits).
    pub min_edge: f64,
    /// Courant length of the solid under each node: the smallest V / (largest face area) of the
    /// elements under the node's quads (the solver's element step is this over the wave speed), m.
    pub courant_length: Vec<f64>,
}

/// Volume of a hexahedron (m³) by the divergence theorem over its
/// six (possibly warped) faces, using each face's diagonal cross product.
fn hex_volume(x: &[[f64; 3]], h: &[u32; 8]) -> f64 {
    let mut v = 0.0;
    for f in HEX_FACES {
        let p = f.map(|i| x[h[i] as usize]);
        let d1 = sub(p[2], p[0]);
        let d2 = sub(p[3], p[1]);
        let n = crate::fe::tensor::cross(d1, d2);
        let c = [0, 1, 2].map(|a| 0.25 * (p[0][a] + p[1][a] + p[2][a] + p[3][a]));
        v += 0.5 * crate::fe::tensor::dot(c, n) / 3.0;
    }
    v
}

impl ContactSurface {
    /// Builds the surface of `faces`: outward quads of the hexahedra `hexes` over the reference
    /// coordinates `nodes` (m), global node numbers.
    ///
    /// Fails with [`Error::Invalid`] when `faces` is empty, names a node outside `nodes`, or
    /// holds a quad that is not the face of a hexahedron of `hexes`.
    pub fn new(
        nodes: &[[f64; 3]],
        hexes: &[[u32; 8]],
        faces: &[[u32; 4]],
        field: &str,
    ) -> Result<ContactSurface> {
        if faces.is_empty() {
            return Err(Error::invalid(
                field,
                "an empty face set",
                "at least one boundary quad",
            ));
        }
        let n = nodes.len() as u32;
        if let Some(q) = faces.iter().find(|q| q.iter().any(|&i| i >= n)) {
            return Err(Error::invalid(
                field,
                format!("{q:?}"),
                format!("node numbers < {n}"),
            ));
        }
        let key = |q: [u32; 4]| {
            let mut k = q;
            k.sort_unstable();
            k
        };
        let wanted: HashMap<[u32; 4], usize> = faces
            .iter()
            .enumerate()
            .map(|(i, &q)| (key(q), i))
            .collect();
        let mut owner = vec![usize::MAX; faces.len()];
        for (e, h) in hexes.iter().enumerate() {
            for f in HEX_FACES {
                if let Some(&i) = wanted.get(&key(f.map(|a| h[a]))) {
                    owner[i] = e;
                }
            }
        }
        if let Some(i) = owner.iter().position(|&e| e == usize::MAX) {
            return Err(Error::invalid(
                field,
                format!("{:?}", faces[i]),
                "quads that are faces of the mesh's hexahedra",
            ));
        }
        let mut list: Vec<u32> = faces.iter().flatten().copied().collect();
        list.sort_unstable();
        list.dedup();
        let index: HashMap<u32, usize> = list.iter().enumerate().map(|(i, &g)| (g, i)).collect();
        let mut area = vec![0.0; list.len()];
        let mut th = vec![0.0; list.len()];
        let mut vol = vec![0.0; list.len()];
        let mut min_edge = f64::INFINITY;
        let mut face_thickness = Vec::with_capacity(faces.len());
        let mut courant = vec![f64::INFINITY; list.len()];
        for (q, &e) in faces.iter().zip(&owner) {
            let p = q.map(|i| nodes[i as usize]);
            let a = quad_area(&p);
            let v = hex_volume(nodes, &hexes[e]);
            face_thickness.push(v / a);
            let l = characteristic_length(&hexes[e].map(|i| nodes[i as usize]), v);
            for k in 0..4 {
                min_edge = min_edge.min(crate::fe::tensor::norm(sub(p[(k + 1) % 4], p[k])));
            }
            for &g in q {
                let i = index[&g];
                area[i] += 0.25 * a;
                th[i] += 0.25 * a * (v / a);
                vol[i] += 0.25 * a * v;
                courant[i] = courant[i].min(l);
            }
        }
        for i in 0..list.len() {
            th[i] /= area[i];
            vol[i] /= area[i];
        }
        if min_edge.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
            || th
                .iter()
                .any(|&t| t.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater))
        {
            return Err(Error::invalid(
                field,
                "degenerate quads or inverted elements",
                "positive areas and volumes",
            ));
        }
        Ok(ContactSurface {
            faces: faces.to_vec(),
            nodes: list,
            area,
            thickness: th,
            volume: vol,
            face_thickness,
            min_edge,
            courant_length: courant,
        })
    }

    /// Total area of the surface, m².
    pub fn total_area(&self) -> f64 {
        self.area.iter().sum()
    }

    /// The penalty law of each node of `nodes`: `weight` (the pass weight) times the
    /// geometric stiffness of `params`'s penalty rule over the solid under the node (Young's
    /// and bulk moduli `youngs`, `bulk`, Pa), stick stiffness `tangential_ratio` times that,
    /// no dashpot, and the element frequency 2 c / L of the dilatational wave speed `wave`
    /// (m/s) over the node's Courant length.
    pub fn node_laws(
        &self,
        params: &ContactParams,
        weight: f64,
        youngs: f64,
        bulk: f64,
        wave: f64,
    ) -> Vec<NodeLaw> {
        (0..self.nodes.len())
            .map(|i| {
                let k = weight
                    * params.penalty.geometric_stiffness(
                        youngs,
                        bulk,
                        self.area[i],
                        self.thickness[i],
                        self.volume[i],
                    );
                NodeLaw {
                    k,
                    kt: params.tangential_ratio * k,
                    c: 0.0,
                    omega_elem: 2.0 * wave / self.courant_length[i],
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::block::block;

    #[test]
    fn tributary_areas_and_thickness_of_a_block_face() {
        // Top face z = 0.3 of a 1 x 2 x 0.3 block cut 2 x 4 x 3: quads 0.5 x 0.5, elements 0.1 deep.
        let m = block([1.0, 2.0, 0.3], [2, 4, 3]);
        let top: Vec<[u32; 4]> = m
            .boundary
            .iter()
            .copied()
            .filter(|q| {
                q.iter()
                    .all(|&i| (m.nodes[i as usize][2] - 0.3).abs() < 1e-12)
            })
            .collect();
        let s = ContactSurface::new(&m.nodes, &m.hexes, &top, "top").unwrap();
        assert_eq!(s.nodes.len(), 15);
        assert!((s.total_area() - 2.0).abs() < 1e-12);
        assert!(s.thickness.iter().all(|&t| (t - 0.1).abs() < 1e-12));
        assert!(s.volume.iter().all(|&v| (v - 0.025).abs() < 1e-12));
        // Corner node: a quarter of one quad; interior node: four quarters.
        let corner = s
            .nodes
            .iter()
            .position(|&g| m.nodes[g as usize][..2] == [0.0, 0.0])
            .unwrap();
        assert!((s.area[corner] - 0.0625).abs() < 1e-12);
        assert!((s.min_edge - 0.5).abs() < 1e-12);
        // Elements 0.5 x 0.5 x 0.1: V / largest face = 0.025 / 0.25.
        assert!(s.courant_length.iter().all(|&l| (l - 0.1).abs() < 1e-12));
    }

    #[test]
    fn foreign_quads_are_rejected() {
        let m = block([1.0; 3], [1, 1, 1]);
        assert!(ContactSurface::new(&m.nodes, &m.hexes, &[], "s").is_err());
        let e = ContactSurface::new(&m.nodes, &m.hexes, &[[0, 1, 2, 7]], "ball1.contact")
            .unwrap_err()
            .to_string();
        assert!(e.contains("ball1.contact"), "{e}");
        assert!(ContactSurface::new(&m.nodes, &m.hexes, &[[0, 1, 2, 99]], "s").is_err());
    }
}
