//! Structured block meshes: bars and cubes for element, wave and material tests, and the
//! graded block of an elastic wall.

use super::cut::Cut;
use super::section::block::{check, graded_line, BlockSpec};
use super::{topology::boundary_faces, Mesh};
use crate::error::{Error, Result};

/// The hexahedra of the tensor product of three increasing node lines (m): nodes ordered x
/// fastest, then y, then z; every hexahedron a right-handed box; boundary faces outward.
fn tensor_mesh([xs, ys, zs]: [&[f64]; 3]) -> Mesh {
    let (nx, ny) = (xs.len(), ys.len());
    let id = |i: usize, j: usize, k: usize| (i + nx * (j + ny * k)) as u32;
    let mut nodes = Vec::with_capacity(nx * ny * zs.len());
    for &z in zs {
        for &y in ys {
            for &x in xs {
                nodes.push([x, y, z]);
            }
        }
    }
    let hexes = super::structured_hexes([nx - 1, ny - 1, zs.len() - 1], id);
    let boundary = boundary_faces(&hexes);
    Mesh {
        nodes,
        hexes,
        boundary,
        ..Default::default()
    }
}

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
    let line = |a: usize, n: usize| -> Vec<f64> {
        (0..=n).map(|i| lengths[a] * i as f64 / n as f64).collect()
    };
    let mut mesh = tensor_mesh([&line(0, nx), &line(1, ny), &line(2, nz)]);
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

/// Growth of the cell size from one cell to the next outside a wall block's core: faster than
/// the section's (1.25), since a tensor-product block carries every line's cells out to its
/// rim (half the hexahedra at 1.5).
pub const WALL_BLOCK_GROWTH: f64 = 1.5;

/// Most hexahedra a graded wall block may have.
pub const MAX_WALL_BLOCK_ELEMENTS: usize = 1_000_000;

/// What to mesh: an elastic wall's block under the contact point at the origin, its face on
/// x = 0 and its body in x > 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallBlockSpec {
    /// The section block's lengths and grading, m: `width` the half-width W of the square face
    /// (y and z in [−W, W]), `height` the depth H below it (x in [0, H]).
    pub block: BlockSpec,
    /// Radius of the face set `contact` about the origin, m (> 0).
    pub contact_radius: f64,
    /// The ball's cut: the block keeps the same side of the planes y = 0 and z = 0.
    pub cut: Cut,
}

/// Node coordinates of a graded line mirrored about 0 (from −length to length), or the
/// line from 0 alone when `half`.
fn mirrored_line(length: f64, spec: &BlockSpec, half: bool) -> Vec<f64> {
    let up = graded_line(
        length,
        spec.size,
        spec.pole_size,
        spec.core,
        WALL_BLOCK_GROWTH,
    );
    if half {
        return up;
    }
    let mut line: Vec<f64> = up.iter().skip(1).rev().map(|v| -v).collect();
    line.extend(up);
    line
}

/// Meshes the block x ∈ [0, H], y and z ∈ [−W, W] (y ≥ 0 on the quarter cut, z ≥ 0 on the
/// half and quarter cuts) as a tensor product of graded lines ([`graded_line`]): cells of
/// the pole size out to the core, then growing to the far-field size. Every hexahedron is a
/// rectangular box.
///
/// Sets: node set `base` (x = H: the nodes to fix), node sets `sym_y` / `sym_z` (on the cut
/// planes; empty without them), face and node sets `contact` (face quads on x = 0 whose nodes
/// all lie within `contact_radius` of the origin).
///
/// Errors: those of the section's block ([`check`]: non-finite or non-positive lengths,
/// `pole_size` above `size`, `size` above the smaller of W and H, a negative core), a
/// non-positive `contact_radius`, or more than [`MAX_WALL_BLOCK_ELEMENTS`] hexahedra.
pub fn wall_block(spec: &WallBlockSpec) -> Result<Mesh> {
    let b = &spec.block;
    check(b)?;
    let r = spec.contact_radius;
    if !(r.is_finite() && r > 0.0) {
        return Err(Error::invalid("contact_radius", r, "> 0 m, finite"));
    }
    let xs = graded_line(b.height, b.size, b.pole_size, b.core, WALL_BLOCK_GROWTH);
    let ys = mirrored_line(b.width, b, spec.cut == Cut::Quarter);
    let zs = mirrored_line(b.width, b, spec.cut != Cut::Full);
    let cells = [xs.len() - 1, ys.len() - 1, zs.len() - 1];
    let count = cells.iter().product::<usize>();
    if count > MAX_WALL_BLOCK_ELEMENTS {
        return Err(Error::invalid(
            "wall.size",
            format!("{count} hexahedra"),
            format!("at most {MAX_WALL_BLOCK_ELEMENTS} (a smaller block, or a coarser ball pole)"),
        ));
    }
    let mut mesh = tensor_mesh([&xs, &ys, &zs]);
    let select = |f: &dyn Fn([f64; 3]) -> bool| -> Vec<u32> {
        (0..mesh.nodes.len() as u32)
            .filter(|&n| f(mesh.nodes[n as usize]))
            .collect()
    };
    let base = select(&|p| p[0] == b.height);
    let sym_y = if spec.cut == Cut::Quarter {
        select(&|p| p[1] == 0.0)
    } else {
        Vec::new()
    };
    let sym_z = if spec.cut == Cut::Full {
        Vec::new()
    } else {
        select(&|p| p[2] == 0.0)
    };
    let r2 = spec.contact_radius * spec.contact_radius;
    let on_face = |n: u32| {
        let p = mesh.nodes[n as usize];
        p[0] == 0.0 && p[1] * p[1] + p[2] * p[2] <= r2
    };
    let contact: Vec<[u32; 4]> = mesh
        .boundary
        .iter()
        .filter(|q| q.iter().all(|&n| on_face(n)))
        .copied()
        .collect();
    let mut contact_nodes: Vec<u32> = contact.iter().flatten().copied().collect();
    contact_nodes.sort_unstable();
    contact_nodes.dedup();
    mesh.node_sets.insert("base".into(), base);
    mesh.node_sets.insert("sym_y".into(), sym_y);
    mesh.node_sets.insert("sym_z".into(), sym_z);
    mesh.node_sets.insert("contact".into(), contact_nodes);
    mesh.face_sets.insert("contact".into(), contact);
    Ok(mesh)
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

    fn spec(cut: Cut) -> WallBlockSpec {
        WallBlockSpec {
            block: BlockSpec {
                width: 0.02,
                height: 0.01,
                size: 0.002,
                pole_size: 2e-4,
                core: 1e-3,
            },
            contact_radius: 0.005,
            cut,
        }
    }

    #[test]
    fn a_wall_block_fills_its_box_and_grades_to_the_pole() {
        for (cut, share) in [(Cut::Full, 1.0), (Cut::Half, 0.5), (Cut::Quarter, 0.25)] {
            let m = wall_block(&spec(cut)).unwrap();
            let volume: f64 = m
                .hexes
                .iter()
                .map(|h| {
                    let (a, b) = (m.nodes[h[0] as usize], m.nodes[h[6] as usize]);
                    (b[0] - a[0]) * (b[1] - a[1]) * (b[2] - a[2])
                })
                .sum();
            let want = share * 0.04 * 0.04 * 0.01;
            assert!((volume / want - 1.0).abs() < 1e-12, "{cut:?}: {volume}");
            // The cell at the contact point is a cube of the pole size.
            let h = m
                .hexes
                .iter()
                .find(|h| m.nodes[h[0] as usize] == [0.0; 3])
                .unwrap();
            let far = m.nodes[h[6] as usize];
            assert!(far.iter().all(|&c| (c - 2e-4).abs() < 1e-15), "{far:?}");
            let faces = &m.face_sets["contact"];
            assert!(!faces.is_empty());
            for q in faces {
                for &n in q {
                    let p = m.nodes[n as usize];
                    assert!(p[0] == 0.0 && p[1].hypot(p[2]) <= 0.005);
                }
            }
            let base = &m.node_sets["base"];
            assert!(base.iter().all(|&n| m.nodes[n as usize][0] == 0.01));
            assert_eq!(m.node_sets["sym_z"].is_empty(), cut == Cut::Full);
            assert_eq!(m.node_sets["sym_y"].is_empty(), cut != Cut::Quarter);
        }
    }

    #[test]
    fn a_wall_blocks_contact_faces_point_out_of_the_block() {
        // Outward normals of the face x = 0 point along −x, towards the ball.
        let m = wall_block(&spec(Cut::Half)).unwrap();
        for q in &m.face_sets["contact"] {
            let p = q.map(|i| m.nodes[i as usize]);
            let d1 = [p[2][1] - p[0][1], p[2][2] - p[0][2]];
            let d2 = [p[3][1] - p[1][1], p[3][2] - p[1][2]];
            assert!(d1[0] * d2[1] - d1[1] * d2[0] < 0.0, "{q:?}");
        }
    }

    #[test]
    fn a_wall_block_refuses_a_far_field_size_above_its_side() {
        let mut s = spec(Cut::Full);
        s.block.size = 0.05;
        let e = wall_block(&s).unwrap_err().to_string();
        assert!(e.contains("mesh.size"), "{e}");
    }
}
