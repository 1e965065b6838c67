//! Graded all-quad meshes of a ball's meridian section (the half-disc r ≥ 0), refined toward
//! the contact pole (r, z) = (0, +R).
//!
//! The section is the meridian slice of the 3D ball mesh ([`crate::mesh::ball`]): the same circle
//! inversion about the antipode (0, −R) maps a quarter-disc O-grid around the pole (a square
//! core of pole-size cells wrapped by layers that grow geometrically) onto the front quarter
//! z ≥ 0, and the back quarter is the mirror image of the unrefined construction, sharing its
//! nodes on z = 0. Unrefined, the section's nodes are exactly the 3D quarter ball's nodes on
//! its cut plane through the axis; refined, the core is scaled so that the quad at the pole
//! has the requested size (the 3D mesher sizes its shortest edge instead, which differs from
//! the pole edge by under 5 % once `pole_size` is below a fifth of the surface facet). The
//! core square has two sides on the
//! axis and the surface and the layers end on the axis with full quads, so no element
//! degenerates into a triangle at r = 0.

use super::geometry::SectionMesh;
use super::geometry::{boundary_edges, quad_area};
use crate::error::{Error, Result};
use crate::mesh::ball::{core_point, invert, Plan, CONTACT_HALF_ANGLE_DEG, MAX_ELEMENTS};
use std::collections::BTreeMap;

/// What to mesh: the meridian section of a ball. Lengths in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionSpec {
    /// Ball diameter D, m.
    pub diameter: f64,
    /// Far-field element size h, m: an upper bound on element edges away from the pole, as
    /// for the 3D mesher (the surface arc is cut into segments of about h / 2).
    pub size: f64,
    /// Element size at the contact pole, m; `None` meshes the section uniformly.
    pub pole_size: Option<f64>,
}

/// Meshes the meridian half-disc of a ball of diameter `spec.diameter` centred at the origin
/// with counter-clockwise 4-node quads, refined toward the pole (0, +R).
///
/// Sets: node set `axis` (every node with r = 0, exactly), segment and node sets `surface`
/// (the whole arc, from the south pole to the north pole) and `contact` (the surface
/// segments with at least one node within [`CONTACT_HALF_ANGLE_DEG`] of +z, seen from the
/// centre, and their nodes). `boundary` is the arc (the axis is not a boundary), ordered from
/// (0, −R) to (0, +R). Surface nodes lie on the circle to rounding. Output is deterministic.
///
/// Errors: non-finite or non-positive sizes, `size` above the radius or below radius / 600,
/// `pole_size` above `size` or below `size / 10^4`, or more than [`MAX_ELEMENTS`] elements.
pub fn ball(spec: &SectionSpec) -> Result<SectionMesh> {
    let (r, n, facet) = crate::mesh::ball::core_cells(spec.diameter, spec.size, spec.pole_size)?;
    let front = match spec.pole_size {
        Some(p) if p < facet => refined(r, n, p),
        _ => Plan::uniform(r, n, facet),
    };
    let back = Plan::uniform(r, n, facet);
    let estimate = quads_of(&front) + quads_of(&back);
    if estimate > MAX_ELEMENTS {
        return Err(Error::invalid(
            "pole_size",
            spec.pole_size.unwrap_or(spec.size),
            format!(
                "a pole size giving at most {MAX_ELEMENTS} elements (this one gives {estimate})"
            ),
        ));
    }
    let mut mesh = SectionMesh::default();
    let dome = build_quarter(&front, &mut mesh, false, None, &uniform_layers(&front));
    build_quarter(&back, &mut mesh, true, Some(&dome), &uniform_layers(&back));
    Ok(with_sets(mesh, r))
}

/// The refined front quarter: the 3D mesher's plan, with its core half-width corrected so
/// that the quad at the pole (rather than the shortest edge of the 3D core, which for a mild
/// refinement lies off the meridian plane) has edges of mean length `h_pole` (m).
fn refined(r: f64, n: usize, h_pole: f64) -> Plan {
    let mut a = Plan::refined(r, n, h_pole).a;
    for _ in 0..50 {
        let next = a * h_pole / pole_edge(r, n, a);
        let done = (next - a).abs() <= 1e-12 * a;
        a = next;
        if done {
            break;
        }
    }
    let mut plan = Plan::with_core(r, n, a);
    plan.deepen = 2.0 * r;
    plan
}

/// Mean edge length (m) of the pole quad of a refined core of half-width `a` (m).
pub(super) fn pole_edge(r: f64, n: usize, a: f64) -> f64 {
    let m = n / 2;
    let corner = |i: usize, j: usize| {
        let x = invert(core_point(i, m + j, m, n, a, 2.0 * r), r);
        [x[1], x[0]]
    };
    let p = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
    (0..4)
        .map(|i| {
            let (s, t) = (p[i], p[(i + 1) % 4]);
            ((s[0] - t[0]).powi(2) + (s[1] - t[1]).powi(2)).sqrt()
        })
        .sum::<f64>()
        / 4.0
}

/// Quads of one quarter: the m × m core and `layers` rings of 2m cells (m = n/2).
fn quads_of(plan: &Plan) -> usize {
    let m = plan.n / 2;
    m * m + plan.layers * 2 * m
}

/// One ring of an O-grid quarter's layers: its layer fraction l/L (0 the core's side, 1 the
/// equator) and the first ray it reaches (0: every ray, from the axis; a ring of an edge band
/// confined to the surface starts at a later ray, [`super::band`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct LayerRing {
    /// Layer fraction, in (0, 1].
    pub frac: f64,
    /// First ray index (0 = the axis, 2m = the surface) the ring reaches.
    pub from: usize,
}

/// The rings l/L, l = 1..=L, of `plan`'s evenly spaced layers, each reaching every ray.
pub(super) fn uniform_layers(plan: &Plan) -> Vec<LayerRing> {
    (1..=plan.layers)
        .map(|l| LayerRing {
            frac: l as f64 / plan.layers as f64,
            from: 0,
        })
        .collect()
}

/// The rest radius (m) of the front quarter's surface ring at layer fraction f (0 the
/// core's outermost surface node, 1 the equator), for [`super::band`].
pub(super) fn surface_ring_radius(plan: &Plan) -> impl Fn(f64) -> f64 {
    let (n, m, r) = (plan.n, plan.n / 2, plan.r);
    let p = core_point(0, 2 * m, m, n, plan.a, plan.deepen);
    let len = p[0].hypot(p[1]);
    move |f: f64| {
        let rad = len.powf(1.0 - f) * (2.0 * r).powf(f);
        invert([p[0] / len * rad, p[1] / len * rad, 0.0], r)[1]
    }
}

/// Appends one quarter (the front z ≥ 0, or with `mirror` the back z ≤ 0) to `mesh`, its
/// layers the rings `layers` (fractions increasing, the last 1 and reaching every ray:
/// [`uniform_layers`], or with an edge band [`super::band::layer_rings`]). `dome`
/// (the front's node ids on z = 0, by ray index) makes the back share them. Returns this
/// quarter's node ids on z = 0, from the axis to the equator.
///
/// A ring that starts at ray p₀ > 0 (a band confined to the surface) splits the interval
/// between its two neighbouring full rings only from ray p₀ on; the quads between rays p₀ − 1
/// and p₀ are a transition: s − 1 such rings in one interval (s odd) meet the two full rings
/// at ray p₀ − 1 through s − 1 interior nodes, s quads along the fine side and (s − 1)/2 on
/// the coarse side, so every quad keeps four corners and no node hangs.
pub(super) fn build_quarter(
    plan: &Plan,
    mesh: &mut SectionMesh,
    mirror: bool,
    dome: Option<&[u32]>,
    layers: &[LayerRing],
) -> Vec<u32> {
    let (n, m, r) = (plan.n, plan.n / 2, plan.r);
    // Local coordinates (u inward from the pole along the axis, v away from the axis) of the
    // core grid: the 3D core's slice w = 0, v >= 0.
    let core_id = |i: usize, j: usize| i + (m + 1) * j;
    let mut local = vec![[0.0; 2]; (m + 1) * (m + 1)];
    for j in 0..=m {
        for i in 0..=m {
            let p = core_point(i, m + j, m, n, plan.a, plan.deepen);
            local[core_id(i, j)] = [p[0], p[1]];
        }
    }
    // The rays start on the core's outer sides: up the deep side u = a from the axis, then
    // along the side v = a to the surface.
    let mut pattern: Vec<usize> = (0..=m).map(|j| core_id(m, j)).collect();
    pattern.extend((0..m).rev().map(|i| core_id(i, m)));
    let np = pattern.len();
    let big_l = layers.len();
    // The point of ray p at layer fraction f.
    let ray_point = |local: &[[f64; 2]], p: usize, f: f64, last: bool| -> [f64; 2] {
        let t = local[pattern[p]];
        let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
        let rad = if last {
            2.0 * r
        } else {
            len.powf(1.0 - f) * (2.0 * r).powf(f)
        };
        t.map(|x| x / len * rad)
    };
    // Ring l's node at ray p is local[offset[l] + p − from]; the dome (the last ring) last.
    let mut offset = vec![0usize; big_l + 1];
    for (l, ring) in layers.iter().enumerate().take(big_l - 1) {
        offset[l + 1] = local.len();
        for p in ring.from..np {
            let y = ray_point(&local, p, ring.frac, false);
            local.push(y);
        }
    }
    // Transition nodes between rays p₀ − 1 and p₀ of each interval of partial rings.
    let mut transitions: Vec<(usize, usize, usize)> = Vec::new();
    let mut l = 0;
    while l < big_l {
        let from = layers[l].from;
        if from == 0 {
            l += 1;
            continue;
        }
        let first = l;
        while l < big_l && layers[l].from == from {
            l += 1;
        }
        let s = l - first + 1;
        debug_assert!(s % 2 == 1 && l < big_l, "an odd split between full rings");
        let start = local.len();
        for k in 1..s {
            let f = layers[first + k - 1].frac;
            let a = ray_point(&local, from - 1, f, false);
            let b = ray_point(&local, from, f, false);
            // At height k/s between the rings, bulging towards the fine ray so that the fan
            // on the coarse side stays convex.
            let x = 0.5 + 0.25 * (std::f64::consts::PI * k as f64 / s as f64).sin();
            local.push([(1.0 - x) * a[0] + x * b[0], (1.0 - x) * a[1] + x * b[1]]);
        }
        transitions.push((first, s, start));
    }
    let dome_start = local.len();
    offset[big_l] = dome_start;
    for p in 0..np {
        let y = ray_point(&local, p, 1.0, true);
        local.push(y);
    }
    let n_core = (m + 1) * (m + 1);
    let mut global = Vec::with_capacity(local.len());
    for (loc, y) in local.iter().enumerate() {
        if loc >= dome_start {
            if let Some(shared) = dome {
                global.push(shared[loc - dome_start]);
                continue;
            }
        }
        let x = invert([y[0], y[1], 0.0], r);
        let (mut rr, mut zz) = (x[1], x[0]);
        if loc < n_core && loc % (m + 1) == 0 {
            // The flat side u = 0 maps onto the circle: put it exactly there.
            let len = (rr * rr + zz * zz).sqrt();
            rr *= r / len;
            zz *= r / len;
        }
        if loc >= dome_start {
            zz = 0.0;
        }
        if y[1] == 0.0 {
            rr = 0.0;
        }
        if mirror {
            zz = -zz;
        }
        global.push(mesh.nodes.len() as u32);
        mesh.nodes.push([rr, zz]);
    }
    // Ring l (0 the core's side, 1..=L the layers) at ray p.
    let from_of = |l: usize| if l == 0 { 0 } else { layers[l - 1].from };
    let layer_node = |l: usize, p: usize| -> u32 {
        if l == 0 {
            global[pattern[p]]
        } else {
            global[offset[l] + p - from_of(l)]
        }
    };
    let start = mesh.quads.len();
    for j in 0..m {
        for i in 0..m {
            let q = [
                core_id(i, j),
                core_id(i + 1, j),
                core_id(i + 1, j + 1),
                core_id(i, j + 1),
            ];
            mesh.quads.push(q.map(|c| global[c]));
        }
    }
    for p in 0..np - 1 {
        // The rings present on both rays of the column, inside out; an interval with rings
        // that start on ray p + 1 is a transition, built below.
        let mut inner = 0;
        let mut transition = false;
        for l in 1..=big_l {
            if from_of(l) > p {
                transition |= from_of(l) == p + 1;
                continue;
            }
            if !transition {
                // Outward along ray p, then around P the same way as the core's (u, v) order.
                mesh.quads.push([
                    layer_node(inner, p),
                    layer_node(l, p),
                    layer_node(l, p + 1),
                    layer_node(inner, p + 1),
                ]);
            }
            inner = l;
            transition = false;
        }
    }
    // The transitions: coarse ray p₀ − 1, fine ray p₀.
    for &(first, s, start_node) in &transitions {
        let p0 = layers[first].from;
        let coarse = [layer_node(first, p0 - 1), layer_node(first + s, p0 - 1)];
        let fine: Vec<u32> = (0..=s).map(|k| layer_node(first + k, p0)).collect();
        let inner: Vec<u32> = (0..s - 1).map(|k| global[start_node + k]).collect();
        mesh.quads.extend(transition(coarse, &fine, &inner));
    }
    // The inversion reverses orientation (and the mirror reverses it back).
    let corners = |q: &[u32; 4]| q.map(|i| mesh.nodes[i as usize]);
    if quad_area(&corners(&mesh.quads[start])) < 0.0 {
        for q in &mut mesh.quads[start..] {
            *q = [q[0], q[3], q[2], q[1]];
        }
    }
    (0..np).map(|p| global[dome_start + p]).collect()
}

/// The quads of a one-cell transition from the `coarse` ray's two nodes (inner, outer ring)
/// to the `fine` ray's s + 1 nodes (inner ring first) through the s − 1 `inner` nodes (s odd),
/// in the layer quads' orientation: s quads on the fine side, a fan of (s − 1)/2 from the
/// coarse inner node on the other.
fn transition(coarse: [u32; 2], fine: &[u32], inner: &[u32]) -> Vec<[u32; 4]> {
    let s = fine.len() - 1;
    let mid = |k: usize| inner[k - 1];
    let mut quads = vec![[coarse[0], mid(1), fine[1], fine[0]]];
    for k in 1..s - 1 {
        quads.push([mid(k), mid(k + 1), fine[k + 1], fine[k]]);
    }
    quads.push([mid(s - 1), coarse[1], fine[s], fine[s - 1]]);
    let mut k = 1;
    while k + 2 < s {
        quads.push([coarse[0], mid(k + 2), mid(k + 1), mid(k)]);
        k += 2;
    }
    quads.push([coarse[0], coarse[1], mid(s - 1), mid(s - 2)]);
    quads
}

/// Adds the boundary and the sets (see [`ball`]).
pub(super) fn with_sets(mut mesh: SectionMesh, r: f64) -> SectionMesh {
    let nodes = &mesh.nodes;
    let on_axis = |i: u32| nodes[i as usize][0] == 0.0;
    let angle = |e: &[u32; 2]| {
        let (a, b) = (nodes[e[0] as usize], nodes[e[1] as usize]);
        (a[1] + b[1]).atan2(a[0] + b[0])
    };
    let mut arc: Vec<[u32; 2]> = boundary_edges(&mesh.quads)
        .into_iter()
        .filter(|e| !(on_axis(e[0]) && on_axis(e[1])))
        .collect();
    arc.sort_by(|a, b| angle(a).total_cmp(&angle(b)));
    let cos_c = CONTACT_HALF_ANGLE_DEG.to_radians().cos();
    let in_contact = |i: u32| nodes[i as usize][1] >= cos_c * r * (1.0 - 1e-12);
    let contact: Vec<[u32; 2]> = arc
        .iter()
        .filter(|e| e.iter().any(|&i| in_contact(i)))
        .copied()
        .collect();
    let nodes_of = |es: &[[u32; 2]]| {
        let mut v: Vec<u32> = es.iter().flatten().copied().collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let axis: Vec<u32> = (0..nodes.len() as u32).filter(|&i| on_axis(i)).collect();
    let mut node_sets = BTreeMap::new();
    node_sets.insert("axis".to_string(), axis);
    node_sets.insert("contact".to_string(), nodes_of(&contact));
    node_sets.insert("surface".to_string(), nodes_of(&arc));
    let mut segment_sets = BTreeMap::new();
    segment_sets.insert("contact".to_string(), contact);
    segment_sets.insert("surface".to_string(), arc.clone());
    mesh.boundary = arc;
    mesh.node_sets = node_sets;
    mesh.segment_sets = segment_sets;
    mesh
}
