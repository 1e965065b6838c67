//! Structured block meshes: bars and cubes for element, wave and material tests.

use super::{topology::boundary_faces, Mesh};

/// A box [0, lx] x [0, ly] x [0, lz] (m) cut into nx x ny x nz equal hexahedra.
///
/// Node sets `x0`, `x1`, `y0`, `y1`, `z0`, `z1` hold the nodes on each face of the box.
/// Panics only if a count is zero (a programming error, not user input).
pub fn block(lengths: [f64; 3], counts: [usize; 3]) -> Mesh {
    let [nx, ny, nz] = counts;
    assert!(
        nx > 0 && ny > 0 && nz > 0,
        "block needs at least one element per direction"
    );
    let id = |i: usize, j: usize, k: usize| (i + (nx + 1) * (j + (ny + 1) * k)) as u32;
    let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                nodes.push([
                    lengths[0] * i as f64 / nx as f64,
                    lengths[1] * j as f64 / ny as f64,
                    lengths[2] * k as f64 / nz as f64,
                ]);
            }
        }
    }
    let hexes = super::structured_hexes([nx, ny, nz], id);
    let boundary = boundary_faces(&hexes);
    let mut mesh = Mesh {
        nodes,
        hexes,
        boundary,
        ..Default::default()
    };
    let tol = 1e-12 * lengths.iter().cloned().fold(0.0, f64::max);
    for (axis, name) in ["x", "y", "z"].iter().enumerate() {
        for (end, suffix) in [(0.0, "0"), (lengths[axis], "1")] {
            let set: Vec<u32> = (0..mesh.nodes.len() as u32)
                .filter(|&n| (mesh.nodes[n as usize][axis] - end).abs() <= tol)
                .collect();
            mesh.node_sets.insert(format!("{name}{suffix}"), set);
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_boundary_of_a_block() {
        let m = block([1.0, 2.0, 3.0], [2, 3, 4]);
        assert_eq!(m.n_nodes(), 3 * 4 * 5);
        assert_eq!(m.n_elements(), 24);
        // Surface quads: 2(2*3 + 3*4 + 2*4) = 52.
        assert_eq!(m.boundary.len(), 52);
        assert_eq!(m.node_sets["x0"].len(), 4 * 5);
    }

    #[test]
    fn boundary_normals_point_outward() {
        // Divergence theorem: (1/3) sum over faces of x . n dA = V for a closed outward surface.
        let m = block([1.0, 2.0, 3.0], [2, 3, 4]);
        let mut flux = 0.0;
        for q in &m.boundary {
            let p = q.map(|i| m.nodes[i as usize]);
            let d1 = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
            let d2 = [p[3][0] - p[1][0], p[3][1] - p[1][1], p[3][2] - p[1][2]];
            let n = [
                0.5 * (d1[1] * d2[2] - d1[2] * d2[1]),
                0.5 * (d1[2] * d2[0] - d1[0] * d2[2]),
                0.5 * (d1[0] * d2[1] - d1[1] * d2[0]),
            ];
            let c = [0, 1, 2].map(|a| 0.25 * (p[0][a] + p[1][a] + p[2][a] + p[3][a]));
            flux += c[0] * n[0] + c[1] * n[1] + c[2] * n[2];
        }
        assert!((flux / 3.0 - 6.0).abs() < 1e-12, "{flux}");
    }
}
