//! Graded all-quad meshes of a block's meridian section: the rectangle r ∈ [0, W],
//! z ∈ [−H, 0] of a cylinder whose face z = 0 is hit at the contact point (0, 0).
//!
//! The mesh is a tensor product of two graded node lines, one along r and one along z: cells
//! of the pole size out to the core distance from the contact point, then cells that grow by
//! [`GROWTH`] per cell up to the far-field size, the graded part scaled down so that the last
//! node falls on the block's edge. Every quad is a rectangle; the cells next to the contact
//! point are squares of the pole size.

use super::geometry::SectionMesh;
use crate::error::{Error, Result};
use std::collections::BTreeMap;

/// Growth of the cell size from one cell to the next outside the core.
pub const GROWTH: f64 = 1.25;

/// Most quads a block mesh may have.
pub const MAX_BLOCK_ELEMENTS: usize = 200_000;

/// What to mesh: the meridian section of a block. Lengths in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockSpec {
    /// Radius W of the block (its extent along r), m.
    pub width: f64,
    /// Depth H of the block (its extent below the face), m.
    pub height: f64,
    /// Far-field element size, m: an upper bound on every cell edge.
    pub size: f64,
    /// Cell size at the contact point, m (≤ `size`).
    pub pole_size: f64,
    /// Distance from the contact point (along r and along z) over which cells keep the pole
    /// size, m (≥ 0).
    pub core: f64,
}

/// Node coordinates (m) of a line from 0 to `length` (m): cells of `pole` (m) up to `core`
/// (m), then growing by `growth` (> 1; the section's [`GROWTH`]) up to `size` (m), the
/// graded part scaled to end at `length`.
pub(crate) fn graded_line(length: f64, size: f64, pole: f64, core: f64, growth: f64) -> Vec<f64> {
    let mut x = vec![0.0];
    let mut h = pole;
    let mut last = 0.0;
    while last < length * (1.0 - 1e-12) {
        if last >= core - 1e-12 * length {
            h = (h * growth).min(size);
        }
        last += h;
        x.push(last);
    }
    // The first node at or past the core: the graded part starts there.
    let start = x
        .iter()
        .position(|&v| v >= core.min(length) - 1e-12 * length)
        .unwrap_or(0);
    let x0 = x[start];
    let scale = if last > x0 {
        (length - x0) / (last - x0)
    } else {
        1.0
    };
    for v in &mut x[start..] {
        *v = x0 + (*v - x0) * scale;
    }
    if let Some(l) = x.last_mut() {
        *l = length;
    }
    x
}

/// Checks `spec` (one-line errors naming the field): the section's block and the 3D wall
/// block ([`crate::mesh::block::wall_block`]) alike.
pub(crate) fn check(spec: &BlockSpec) -> Result<()> {
    let pos = |name: &str, v: f64| -> Result<()> {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(Error::invalid(name, v, "> 0 m, finite"))
        }
    };
    pos("width", spec.width)?;
    pos("height", spec.height)?;
    pos("mesh.size", spec.size)?;
    pos("mesh.pole_size", spec.pole_size)?;
    if spec.pole_size > spec.size {
        return Err(Error::invalid(
            "mesh.pole_size",
            spec.pole_size,
            format!("<= mesh.size = {} m", spec.size),
        ));
    }
    if spec.size > spec.width.min(spec.height) {
        return Err(Error::invalid(
            "mesh.size",
            spec.size,
            format!(
                "<= the block's smaller side {} m",
                spec.width.min(spec.height)
            ),
        ));
    }
    if !(spec.core.is_finite() && spec.core >= 0.0) {
        return Err(Error::invalid("mesh.core", spec.core, ">= 0 m, finite"));
    }
    Ok(())
}

/// Meshes the block section r ∈ [0, W], z ∈ [−H, 0] with counter-clockwise rectangular quads
/// graded towards (0, 0).
///
/// Sets: node set `axis` (r = 0 exactly), node set `base` (z = −H exactly: the nodes to fix),
/// segment and node sets `face` and `contact` (the face z = 0, from the rim to the axis).
/// `boundary` runs counter-clockwise from (0, −H) along the base, up the rim and back along
/// the face to the axis (the block on the left of each segment). Deterministic.
///
/// Errors: non-finite or non-positive lengths, `pole_size` above `size`, `size` above the
/// smaller side, a negative core, or more than [`MAX_BLOCK_ELEMENTS`] quads.
pub fn block(spec: &BlockSpec) -> Result<SectionMesh> {
    check(spec)?;
    let rs = graded_line(spec.width, spec.size, spec.pole_size, spec.core, GROWTH);
    let ds = graded_line(spec.height, spec.size, spec.pole_size, spec.core, GROWTH);
    let (nr, nz) = (rs.len(), ds.len());
    let quads = (nr - 1) * (nz - 1);
    if quads > MAX_BLOCK_ELEMENTS {
        return Err(Error::invalid(
            "mesh.pole_size",
            spec.pole_size,
            format!("a pole size giving at most {MAX_BLOCK_ELEMENTS} block elements (this one gives {quads})"),
        ));
    }
    // Node (i, j): r = rs[i], z = −ds[j] (j = 0 on the face).
    let id = |i: usize, j: usize| (i + nr * j) as u32;
    let mut mesh = SectionMesh::default();
    for d in &ds {
        for r in &rs {
            mesh.nodes.push([*r, -d]);
        }
    }
    for j in 0..nz - 1 {
        for i in 0..nr - 1 {
            // Counter-clockwise in (r, z): z decreases with j.
            mesh.quads
                .push([id(i, j + 1), id(i + 1, j + 1), id(i + 1, j), id(i, j)]);
        }
    }
    let base: Vec<[u32; 2]> = (0..nr - 1)
        .map(|i| [id(i, nz - 1), id(i + 1, nz - 1)])
        .collect();
    let rim: Vec<[u32; 2]> = (0..nz - 1)
        .rev()
        .map(|j| [id(nr - 1, j + 1), id(nr - 1, j)])
        .collect();
    let face: Vec<[u32; 2]> = (0..nr - 1)
        .rev()
        .map(|i| [id(i + 1, 0), id(i, 0)])
        .collect();
    let nodes_of = |es: &[[u32; 2]]| {
        let mut v: Vec<u32> = es.iter().flatten().copied().collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let mut node_sets = BTreeMap::new();
    node_sets.insert("axis".to_string(), (0..nz).map(|j| id(0, j)).collect());
    node_sets.insert("base".to_string(), (0..nr).map(|i| id(i, nz - 1)).collect());
    node_sets.insert("face".to_string(), nodes_of(&face));
    node_sets.insert("contact".to_string(), nodes_of(&face));
    let mut segment_sets = BTreeMap::new();
    segment_sets.insert("face".to_string(), face.clone());
    segment_sets.insert("contact".to_string(), face.clone());
    mesh.boundary = base.into_iter().chain(rim).chain(face).collect();
    mesh.node_sets = node_sets;
    mesh.segment_sets = segment_sets;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_graded_line_starts_at_the_pole_size_and_ends_on_the_edge() {
        let x = graded_line(0.1, 0.005, 1e-4, 5e-4, GROWTH);
        assert_eq!(x[0], 0.0);
        assert!((x[1] - 1e-4).abs() < 1e-15);
        assert_eq!(*x.last().unwrap(), 0.1);
        for w in x.windows(2) {
            assert!(w[1] > w[0]);
            assert!(w[1] - w[0] <= 0.005 * (1.0 + 1e-12));
        }
    }
}
