//! The section mesh ([`SectionMesh`]) and its geometry: signed quad areas, boundary edges, the
//! section's area and the volume of its solid of revolution about the z axis.

use std::collections::BTreeMap;

/// A mesh of 4-node quadrilaterals on the meridian half-plane r ≥ 0. Coordinates in metres.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SectionMesh {
    /// Node coordinates (r, z), m; r ≥ 0, and nodes on the axis have r = 0 exactly.
    pub nodes: Vec<[f64; 2]>,
    /// Quadrilaterals as 4 node indices, counter-clockwise in the (r, z) plane (positive area).
    pub quads: Vec<[u32; 4]>,
    /// Boundary segments off the axis, each listed once, ordered counter-clockwise around the
    /// section (the body lies to the left of each segment, the outward normal to the right).
    pub boundary: Vec<[u32; 2]>,
    /// Named node sets (`axis`: nodes with r = 0; `surface`; `contact`), sorted node indices.
    pub node_sets: BTreeMap<String, Vec<u32>>,
    /// Named segment sets (`surface`: the spherical boundary; `contact`: its part near the
    /// pole), with the orientation of `boundary`.
    pub segment_sets: BTreeMap<String, Vec<[u32; 2]>>,
}

/// Signed area (m²) of a quad with corners `p` (positive when counter-clockwise in (r, z)).
pub fn quad_area(p: &[[f64; 2]; 4]) -> f64 {
    0.5 * (0..4)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % 4]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

/// Corner coordinates (r, z), m, of quad `q` of `mesh`.
pub fn quad_points(mesh: &SectionMesh, q: &[u32; 4]) -> [[f64; 2]; 4] {
    q.map(|i| mesh.nodes[i as usize])
}

/// Area (m²) of the section: the sum of the quads' signed areas.
pub fn area(mesh: &SectionMesh) -> f64 {
    mesh.quads
        .iter()
        .map(|q| quad_area(&quad_points(mesh, q)))
        .sum()
}

/// Volume (m³) swept by revolving the section about the z axis: 2π Σ r̄ A (Pappus), with r̄
/// the exact centroid radius of each straight-sided quad.
pub fn revolved_volume(mesh: &SectionMesh) -> f64 {
    2.0 * std::f64::consts::PI
        * mesh
            .quads
            .iter()
            .map(|q| first_moment_r(&quad_points(mesh, q)))
            .sum::<f64>()
}

/// First moment ∫ r dA (m³) of a straight-sided polygon with counter-clockwise corners `p`
/// (the Green's-theorem polygon formula; negative for a clockwise polygon).
pub fn first_moment_r(p: &[[f64; 2]; 4]) -> f64 {
    (0..4)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % 4]);
            (a[0] * b[1] - b[0] * a[1]) * (a[0] + b[0])
        })
        .sum::<f64>()
        / 6.0
}

/// Jacobian determinants (m²) of the bilinear map at the four corners of a quad: twice the
/// area of the corner triangle (previous, this, next corner); all positive for a convex
/// counter-clockwise quad.
pub fn corner_jacobians(p: &[[f64; 2]; 4]) -> [f64; 4] {
    std::array::from_fn(|i| {
        let (o, a, b) = (p[i], p[(i + 1) % 4], p[(i + 3) % 4]);
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    })
}

/// Boundary edges of counter-clockwise quads (edges used by one quad), oriented as in their
/// quad, so the body lies to their left.
pub fn boundary_edges(quads: &[[u32; 4]]) -> Vec<[u32; 2]> {
    let mut count: BTreeMap<(u32, u32), (usize, [u32; 2])> = BTreeMap::new();
    for q in quads {
        for e in 0..4 {
            let (a, b) = (q[e], q[(e + 1) % 4]);
            let entry = count.entry((a.min(b), a.max(b))).or_insert((0, [a, b]));
            entry.0 += 1;
        }
    }
    count
        .into_values()
        .filter(|(c, _)| *c == 1)
        .map(|(_, e)| e)
        .collect()
}
