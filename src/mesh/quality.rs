//! Mesh quality: volume, edge lengths, scaled Jacobians and aspect ratios of 8-node hexahedra.
//!
//! The explicit solver's stable time step scales with the smallest element edge and its cost
//! with the element count, so both are reported; the scaled Jacobian (1 for a cube, 0 for a
//! degenerate corner, negative for an inverted one) measures how far elements are from cubes.

use super::{Mesh, HEX_NODE_XI};
use serde::Serialize;

/// For each hex corner, its three edge neighbours ordered so that their triple product is
/// positive for a right-handed (gmsh/VTK ordered) element.
const CORNER_NEIGHBOURS: [[usize; 3]; 8] = [
    [1, 3, 4],
    [2, 0, 5],
    [3, 1, 6],
    [0, 2, 7],
    [7, 5, 0],
    [4, 6, 1],
    [5, 7, 2],
    [6, 4, 3],
];

/// The 12 edges of a hexahedron as local node pairs.
pub const HEX_EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [4, 5],
    [5, 6],
    [6, 7],
    [7, 4],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Corner coordinates (m) of hex `h` of `mesh`.
pub fn hex_points(mesh: &Mesh, h: &[u32; 8]) -> [[f64; 3]; 8] {
    h.map(|i| mesh.nodes[i as usize])
}

/// Scaled Jacobian at each of the 8 corners: the triple product of the three unit edge
/// vectors leaving the corner (dimensionless, in [-1, 1]; 1 for a right-angled corner,
/// negative if the corner is inverted). A zero-length edge gives 0.
pub fn corner_scaled_jacobians(p: &[[f64; 3]; 8]) -> [f64; 8] {
    let mut out = [0.0; 8];
    for (c, nb) in CORNER_NEIGHBOURS.iter().enumerate() {
        let e = nb.map(|j| sub(p[j], p[c]));
        let l = e.map(norm);
        let denom = l[0] * l[1] * l[2];
        out[c] = if denom > 0.0 {
            dot(e[0], cross(e[1], e[2])) / denom
        } else {
            0.0
        };
    }
    out
}

/// Minimum corner scaled Jacobian of a hexahedron (see [`corner_scaled_jacobians`]).
pub fn scaled_jacobian(p: &[[f64; 3]; 8]) -> f64 {
    corner_scaled_jacobians(p)
        .into_iter()
        .fold(f64::INFINITY, f64::min)
}

/// Signed volume (m^3) of a trilinear hexahedron, exact: det J of a trilinear map is at most
/// quadratic in each reference coordinate, so 2 x 2 x 2 Gauss points integrate it exactly.
/// Negative for an inverted node order.
pub fn hex_volume(p: &[[f64; 3]; 8]) -> f64 {
    let g = 1.0 / 3f64.sqrt();
    let mut vol = 0.0;
    for gx in [-g, g] {
        for gy in [-g, g] {
            for gz in [-g, g] {
                let q = [gx, gy, gz];
                let mut jac = [[0.0; 3]; 3]; // jac[a][d] = d x_a / d xi_d
                for (n, r) in HEX_NODE_XI.iter().enumerate() {
                    let f = [1.0 + r[0] * q[0], 1.0 + r[1] * q[1], 1.0 + r[2] * q[2]];
                    let dn = [
                        0.125 * r[0] * f[1] * f[2],
                        0.125 * r[1] * f[0] * f[2],
                        0.125 * r[2] * f[0] * f[1],
                    ];
                    for a in 0..3 {
                        for d in 0..3 {
                            jac[a][d] += p[n][a] * dn[d];
                        }
                    }
                }
                let cols = [
                    [jac[0][0], jac[1][0], jac[2][0]],
                    [jac[0][1], jac[1][1], jac[2][1]],
                    [jac[0][2], jac[1][2], jac[2][2]],
                ];
                vol += dot(cols[0], cross(cols[1], cols[2])); // unit Gauss weights
            }
        }
    }
    vol
}

/// Surface integral of x . n dA (m^3) over the boundary quads of `mesh`, each taken as the
/// bilinear patch through its 4 nodes (2 x 2 Gauss points, exact for that patch). For a
/// closed, outward-oriented boundary of trilinear hexes this equals 3 V by the divergence
/// theorem (div x = 3).
pub fn boundary_flux(mesh: &Mesh) -> f64 {
    let g = 1.0 / 3f64.sqrt();
    let mut flux = 0.0;
    for q in &mesh.boundary {
        let p = q.map(|i| mesh.nodes[i as usize]);
        for u in [-g, g] {
            for v in [-g, g] {
                let w = [
                    0.25 * (1.0 - u) * (1.0 - v),
                    0.25 * (1.0 + u) * (1.0 - v),
                    0.25 * (1.0 + u) * (1.0 + v),
                    0.25 * (1.0 - u) * (1.0 + v),
                ];
                let du = [
                    -0.25 * (1.0 - v),
                    0.25 * (1.0 - v),
                    0.25 * (1.0 + v),
                    -0.25 * (1.0 + v),
                ];
                let dv = [
                    -0.25 * (1.0 - u),
                    -0.25 * (1.0 + u),
                    0.25 * (1.0 + u),
                    0.25 * (1.0 - u),
                ];
                let mut x = [0.0; 3];
                let mut xu = [0.0; 3];
                let mut xv = [0.0; 3];
                for n in 0..4 {
                    for a in 0..3 {
                        x[a] += w[n] * p[n][a];
                        xu[a] += du[n] * p[n][a];
                        xv[a] += dv[n] * p[n][a];
                    }
                }
                flux += dot(x, cross(xu, xv));
            }
        }
    }
    flux
}

/// Largest ratio of element sizes (cube root of volume) across a shared face: how smoothly
/// the mesh is graded (1 for a uniform mesh). 1 for a mesh with fewer than two elements.
pub fn max_neighbour_size_ratio(mesh: &Mesh) -> f64 {
    use std::collections::HashMap;
    let size: Vec<f64> = mesh
        .hexes
        .iter()
        .map(|h| hex_volume(&hex_points(mesh, h)).abs().cbrt())
        .collect();
    let mut owner: HashMap<[u32; 4], usize> = HashMap::with_capacity(mesh.hexes.len() * 3);
    let mut worst = 1.0f64;
    for (e, h) in mesh.hexes.iter().enumerate() {
        for f in super::topology::HEX_FACES {
            let mut k = f.map(|i| h[i]);
            k.sort_unstable();
            if let Some(&o) = owner.get(&k) {
                let (a, b) = (size[o], size[e]);
                if a > 0.0 && b > 0.0 {
                    worst = worst.max(a / b).max(b / a);
                }
            } else {
                owner.insert(k, e);
            }
        }
    }
    worst
}

/// Size and shape figures of a hex mesh (all lengths in m, volume in m^3).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeshSummary {
    /// Number of nodes.
    pub nodes: usize,
    /// Number of hexahedra.
    pub elements: usize,
    /// Number of boundary quads.
    pub boundary_faces: usize,
    /// Total volume (sum of signed element volumes), m^3.
    pub volume: f64,
    /// Shortest element edge, m.
    pub min_edge: f64,
    /// Midpoint of the shortest edge, m.
    pub min_edge_at: [f64; 3],
    /// Longest element edge, m.
    pub max_edge: f64,
    /// Smallest corner scaled Jacobian over all elements (1 = cube, <= 0 = degenerate).
    pub min_scaled_jacobian: f64,
    /// Mean over elements of each element's minimum corner scaled Jacobian.
    pub mean_scaled_jacobian: f64,
    /// Largest ratio of longest to shortest edge within one element.
    pub max_aspect_ratio: f64,
    /// Bounding box, lower corner, m.
    pub bbox_min: [f64; 3],
    /// Bounding box, upper corner, m.
    pub bbox_max: [f64; 3],
}

/// Quality summary of `mesh`. An empty mesh gives zero counts and zero figures (never NaN).
pub fn summary(mesh: &Mesh) -> MeshSummary {
    let mut s = MeshSummary {
        nodes: mesh.nodes.len(),
        elements: mesh.hexes.len(),
        boundary_faces: mesh.boundary.len(),
        volume: 0.0,
        min_edge: f64::INFINITY,
        min_edge_at: [0.0; 3],
        max_edge: 0.0,
        min_scaled_jacobian: f64::INFINITY,
        mean_scaled_jacobian: 0.0,
        max_aspect_ratio: 0.0,
        bbox_min: [f64::INFINITY; 3],
        bbox_max: [f64::NEG_INFINITY; 3],
    };
    for p in &mesh.nodes {
        for (a, &c) in p.iter().enumerate() {
            s.bbox_min[a] = s.bbox_min[a].min(c);
            s.bbox_max[a] = s.bbox_max[a].max(c);
        }
    }
    let mut sj_sum = 0.0;
    for h in &mesh.hexes {
        let p = hex_points(mesh, h);
        s.volume += hex_volume(&p);
        let sj = scaled_jacobian(&p);
        s.min_scaled_jacobian = s.min_scaled_jacobian.min(sj);
        sj_sum += sj;
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for [a, b] in HEX_EDGES {
            let l = norm(sub(p[b], p[a]));
            lo = lo.min(l);
            hi = hi.max(l);
            if l < s.min_edge {
                s.min_edge = l;
                s.min_edge_at = [0, 1, 2].map(|k| 0.5 * (p[a][k] + p[b][k]));
            }
        }
        s.max_edge = s.max_edge.max(hi);
        let ar = if lo > 0.0 { hi / lo } else { f64::MAX };
        s.max_aspect_ratio = s.max_aspect_ratio.max(ar);
    }
    if mesh.hexes.is_empty() {
        s.min_edge = 0.0;
        s.min_scaled_jacobian = 0.0;
    } else {
        s.mean_scaled_jacobian = sj_sum / mesh.hexes.len() as f64;
    }
    if mesh.nodes.is_empty() {
        s.bbox_min = [0.0; 3];
        s.bbox_max = [0.0; 3];
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::block::block;

    #[test]
    fn unit_cube_figures() {
        let m = block([1.0, 2.0, 3.0], [1, 2, 3]);
        let s = summary(&m);
        assert!((s.volume - 6.0).abs() < 1e-12);
        assert!((s.min_scaled_jacobian - 1.0).abs() < 1e-12);
        assert!((s.min_edge - 1.0).abs() < 1e-12);
        assert!((s.max_aspect_ratio - 1.0).abs() < 1e-12);
        assert!((boundary_flux(&m) - 18.0).abs() < 1e-12);
    }

    #[test]
    fn sheared_hex_volume_and_jacobian() {
        // A parallelepiped with edge vectors a, b, c has volume det[a b c] and
        // corner scaled Jacobian det / (|a||b||c|) at every corner.
        let (a, b, c) = ([2.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.5, 0.5, 3.0]);
        let corner = |i: f64, j: f64, k: f64| [0, 1, 2].map(|d| i * a[d] + j * b[d] + k * c[d]);
        let p = [
            corner(0., 0., 0.),
            corner(1., 0., 0.),
            corner(1., 1., 0.),
            corner(0., 1., 0.),
            corner(0., 0., 1.),
            corner(1., 0., 1.),
            corner(1., 1., 1.),
            corner(0., 1., 1.),
        ];
        assert!((hex_volume(&p) - 6.0).abs() < 1e-12);
        let expect = 6.0 / (2.0 * 2f64.sqrt() * (0.5f64 + 9.0).sqrt());
        assert!((scaled_jacobian(&p) - expect).abs() < 1e-12);
        // Reversing the order inverts the element.
        let q = [p[0], p[3], p[2], p[1], p[4], p[7], p[6], p[5]];
        assert!((hex_volume(&q) + 6.0).abs() < 1e-12);
        assert!(scaled_jacobian(&q) < 0.0);
    }
}
