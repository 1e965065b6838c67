//! gmsh MSH files of a meridian section (2D, in the plane z = 0 with x = r and y = z): the
//! quads become a [`SectionMesh`], and the physical line groups its segment sets.
//!
//! The file is read by [`crate::mesh::msh`]'s reader (MSH 4.1 and 2.2, ASCII and binary, checked
//! against hostile input). Every 4-node quadrangle (type 3) is a quad of the section, turned
//! counter-clockwise if gmsh wrote it clockwise; 2-node lines (type 1) in a physical group
//! become the segment set of that group's name (oriented as the boundary: body to the left)
//! and the node set of their nodes. Lines on the axis (a group named `axis`, say) add nodes
//! only, as the axis is not a boundary. Node set `axis` is every node with r = 0 (x within
//! 1e-9 of the section's size of 0, put exactly on it); `surface`, unless the file names
//! one, is the whole boundary off the axis. The file must name a line group `contact`.

use super::geometry::SectionMesh;
use super::geometry::{boundary_edges, corner_jacobians};
use crate::error::{Error, Result};
use crate::mesh::msh::{node_index, parse_raw};
use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::Path;

/// Reads a gmsh MSH file of a meridian section. Errors name the file and the problem:
/// unreadable MSH, hexahedra (a 3D mesh), no quads, a node off the plane z = 0 or at r < 0,
/// a degenerate or partly inverted quad, a grouped line off the boundary and the axis, or no
/// `contact` group.
pub fn read(path: impl AsRef<Path>) -> Result<SectionMesh> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse(&bytes, &path.display().to_string())
}

/// Parses the bytes of a section MSH file; `name` is used in error messages. See [`read`].
pub fn parse(bytes: &[u8], name: &str) -> Result<SectionMesh> {
    let raw = parse_raw(bytes, name)?;
    let fail = |m: String| Error::Parse(format!("{name}: {m}"));
    if !raw.hexes.is_empty() {
        return Err(fail(format!(
            "{} hexahedra: a 3D mesh (the section reader takes 2D quadrangles)",
            raw.hexes.len()
        )));
    }
    if raw.quads.is_empty() {
        return Err(fail(
            "no quadrangles (gmsh: Recombine Surface, or Mesh.RecombineAll = 1)".into(),
        ));
    }
    let index = node_index(&raw, name)?;
    let extent = raw
        .nodes
        .iter()
        .flat_map(|(_, x)| x.iter().map(|v| v.abs()))
        .fold(0.0f64, f64::max);
    let tol = 1e-9 * extent;
    // Nodes used by quads, in file order.
    let mut new_id = vec![u32::MAX; raw.nodes.len()];
    let lookup = |tag: u64, t: u64| -> Result<usize> {
        index.get(&t).copied().ok_or_else(|| {
            fail(format!(
                "element {tag} refers to node {t}, which is not defined"
            ))
        })
    };
    for (tag, q, _) in &raw.quads {
        for &t in q {
            new_id[lookup(*tag, t)?] = 0;
        }
    }
    let mut nodes = Vec::new();
    for (k, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            let (tag, x) = raw.nodes[k];
            if x[2].abs() > tol {
                return Err(fail(format!(
                    "node {tag} at z = {:e} m: a section lies in the plane z = 0",
                    x[2]
                )));
            }
            if x[0] < -tol {
                return Err(fail(format!(
                    "node {tag} at x = r = {:e} m: a section lies at r >= 0",
                    x[0]
                )));
            }
            let r = if x[0].abs() <= tol { 0.0 } else { x[0] };
            *id = nodes.len() as u32;
            nodes.push([r, x[1]]);
        }
    }
    let mut quads = Vec::with_capacity(raw.quads.len());
    for (tag, q, _) in &raw.quads {
        let mut f = [0u32; 4];
        for (v, &t) in f.iter_mut().zip(q) {
            *v = new_id[lookup(*tag, t)?];
        }
        let j = corner_jacobians(&f.map(|i| nodes[i as usize]));
        if j.iter().all(|&v| v < 0.0) {
            f = [f[0], f[3], f[2], f[1]];
        } else if !j.iter().all(|&v| v > 0.0) {
            return Err(fail(format!(
                "quadrangle {tag} is degenerate or partly inverted (corner Jacobians {j:?} m^2)"
            )));
        }
        quads.push(f);
    }
    let on_axis = |i: u32| nodes[i as usize][0] == 0.0;
    let boundary = chain(
        boundary_edges(&quads)
            .into_iter()
            .filter(|e| !(on_axis(e[0]) && on_axis(e[1])))
            .collect(),
    );
    let oriented: HashSet<[u32; 2]> = boundary.iter().copied().collect();
    let group = |p: i32| {
        raw.names
            .get(&(1, p))
            .cloned()
            .unwrap_or_else(|| format!("physical_{p}"))
    };
    let mut segment_sets: BTreeMap<String, Vec<[u32; 2]>> = BTreeMap::new();
    let mut node_sets: BTreeMap<String, Vec<u32>> = BTreeMap::new();
    for (tag, l, phys) in &raw.lines {
        if phys.is_empty() {
            continue;
        }
        let mut s = [0u32; 2];
        for (v, &t) in s.iter_mut().zip(l) {
            *v = new_id[lookup(*tag, t)?];
            if *v == u32::MAX {
                return Err(fail(format!("line {tag} has node {t}, which no quad uses")));
            }
        }
        let seg = if oriented.contains(&s) {
            Some(s)
        } else if oriented.contains(&[s[1], s[0]]) {
            Some([s[1], s[0]])
        } else if on_axis(s[0]) && on_axis(s[1]) {
            None
        } else {
            return Err(fail(format!(
                "line {tag} (group {}) is neither on the boundary nor on the axis",
                group(phys[0])
            )));
        };
        for &p in phys {
            node_sets.entry(group(p)).or_default().extend_from_slice(&s);
            if let Some(seg) = seg {
                segment_sets.entry(group(p)).or_default().push(seg);
            }
        }
    }
    if !segment_sets.contains_key("contact") {
        return Err(fail(
            "no physical line group named \"contact\" on the boundary (gmsh: Physical \
             Curve(\"contact\") = {...})"
                .into(),
        ));
    }
    let order: HashMap<[u32; 2], usize> =
        boundary.iter().enumerate().map(|(k, e)| (*e, k)).collect();
    for v in segment_sets.values_mut() {
        v.sort_by_key(|e| order[e]);
        v.dedup();
    }
    segment_sets
        .entry("surface".into())
        .or_insert_with(|| boundary.clone());
    let surface_nodes: Vec<u32> = segment_sets["surface"].iter().flatten().copied().collect();
    node_sets.entry("surface".into()).or_insert(surface_nodes);
    let axis: Vec<u32> = (0..nodes.len() as u32).filter(|&i| on_axis(i)).collect();
    node_sets.entry("axis".into()).or_default().extend(axis);
    for v in node_sets.values_mut() {
        v.sort_unstable();
        v.dedup();
    }
    Ok(SectionMesh {
        nodes,
        quads,
        boundary,
        node_sets,
        segment_sets,
    })
}

/// The boundary segments in counter-clockwise order: chained end to start, each chain
/// starting where no segment ends (on the axis), chains in order of their first segment.
fn chain(edges: Vec<[u32; 2]>) -> Vec<[u32; 2]> {
    let next: HashMap<u32, [u32; 2]> = edges.iter().map(|e| (e[0], *e)).collect();
    let ends: HashSet<u32> = edges.iter().map(|e| e[1]).collect();
    let mut out = Vec::with_capacity(edges.len());
    let mut used = HashSet::new();
    let starts = edges
        .iter()
        .filter(|e| !ends.contains(&e[0]))
        .chain(edges.iter());
    for start in starts {
        let mut e = *start;
        while used.insert(e) {
            out.push(e);
            match next.get(&e[1]) {
                Some(n) => e = *n,
                None => break,
            }
        }
    }
    out
}
