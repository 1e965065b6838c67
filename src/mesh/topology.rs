//! Mesh topology: the faces of a hexahedron and the boundary of a hex mesh.

use std::collections::HashMap;

/// The six faces of an 8-node hexahedron as local node indices, each ordered so that its
/// right-hand-rule normal points out of the element (for a positive-Jacobian hex).
pub const HEX_FACES: [[usize; 4]; 6] = [
    [0, 3, 2, 1], // bottom (-zeta)
    [4, 5, 6, 7], // top (+zeta)
    [0, 1, 5, 4], // -eta
    [2, 3, 7, 6], // +eta
    [1, 2, 6, 5], // +xi
    [3, 0, 4, 7], // -xi
];

/// Boundary quadrilaterals of a hex mesh: faces that belong to exactly one element, with
/// their outward node order. Output order follows element order (deterministic).
pub fn boundary_faces(hexes: &[[u32; 8]]) -> Vec<[u32; 4]> {
    let mut count: HashMap<[u32; 4], u32> = HashMap::with_capacity(hexes.len() * 3);
    let key = |f: [u32; 4]| {
        let mut k = f;
        k.sort_unstable();
        k
    };
    for h in hexes {
        for f in HEX_FACES {
            *count.entry(key(f.map(|i| h[i]))).or_insert(0) += 1;
        }
    }
    let mut out = Vec::new();
    for h in hexes {
        for f in HEX_FACES {
            let q = f.map(|i| h[i]);
            if count[&key(q)] == 1 {
                out.push(q);
            }
        }
    }
    out
}
