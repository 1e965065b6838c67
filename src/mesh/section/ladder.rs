//! The section model's mesh family: meridian meshes of a ball sized from the predicted
//! contact radius, nested so that each ladder level halves every length.
//!
//! Construction (the O-grid and inversion of [`super::ball`]): the front quarter
//! (z ≥ 0) has a refined core of m × m pole-size cells of half-width
//! [`REFINED_HALF_WIDTH_PER_RADIUS`] contact radii around the pole, wrapped by L layers of 2m
//! cells whose radii (before the inversion) grow geometrically to the equator, with the
//! growth per layer (1 + 0.946/m) that keeps the cells square; the back quarter is an
//! unrefined O-grid with the same 2m cells along the equator. Level 0 has m₀ = 9 core cells
//! ([`LEVEL0_ELEMENTS_PER_RADIUS`] pole cells across the contact radius) and its layer counts
//! fixed by the ratio R / a; level k has m = 2ᵏ m₀ and 2ᵏ times the layers of level 0. Every
//! grid coordinate of level k is then a grid coordinate of level k + 1 (the core spacing is a
//! function of i/m, the layer radii of l/L), so the meshes are nested: each quad of level k
//! is split into four by level k + 1 in the mapping's parameter space, the refinement ratio
//! is exactly 2 there, and the element counts grow by exactly 4. Surface nodes lie on the
//! circle at every level.

use super::ball::{build_quarter, pole_edge, surface_ring_radius, uniform_layers, with_sets};
use super::band::{layer_rings, EdgeBand};
use super::geometry::SectionMesh;
use crate::error::{Error, Result};
use crate::mesh::ball::{Plan, MAX_ELEMENTS};

/// Half-width of the refined core around the pole, in predicted contact radii: the plastic
/// zone of an impact reaches about one contact radius under the surface and the core's
/// square cells keep their size there; outside it the cells grow linearly with the distance
/// from the pole.
pub const REFINED_HALF_WIDTH_PER_RADIUS: f64 = 1.5;

/// Pole cells across the predicted contact radius at level 0 (nominal: the level-0 core has
/// 9 cells across 1.5 contact radii).
pub const LEVEL0_ELEMENTS_PER_RADIUS: f64 = 6.0;

/// Core cells along each side of the level-0 refined core.
const LEVEL0_CORE_CELLS: usize = 9;

/// Core half-width of the unrefined back quarter, in ball radii (before the inversion).
const BACK_CORE_PER_RADIUS: f64 = 1.0;

/// Deepest ladder level accepted.
pub const MAX_LEVEL: u32 = 7;

/// Smallest and largest contact radius accepted, as fractions of the diameter.
pub const CONTACT_RADIUS_RANGE_PER_D: (f64, f64) = (1e-4, 0.25);

/// Slope of the core spacing at the centre of the core (cell size over a / m at the pole).
fn core_slope() -> f64 {
    0.75 + 0.25 * 0.25 * std::f64::consts::PI
}

/// Layers spanning the radius ratio `span_ratio` (> 1) at the square-cell growth of a core
/// of `m` cells per side.
fn layers_for(span_ratio: f64, m: usize) -> usize {
    let growth = 1.0 + core_slope() / m as f64;
    ((span_ratio.ln() / growth.ln()).round() as usize).max(1)
}

/// The front (refined) and back (unrefined) plans of `level` for a ball of radius `r` (m)
/// and predicted contact radius `contact_radius` (m).
fn plans(r: f64, contact_radius: f64, level: u32) -> (Plan, Plan) {
    let scale = 1usize << level;
    let core = REFINED_HALF_WIDTH_PER_RADIUS * contact_radius;
    let m = LEVEL0_CORE_CELLS * scale;
    let mut front = Plan::with_core(r, 2 * m, core);
    front.layers = layers_for(2.0 * r / core, LEVEL0_CORE_CELLS) * scale;
    front.deepen = 2.0 * r;
    let back_core = BACK_CORE_PER_RADIUS * r;
    let mut back = Plan::with_core(r, 2 * m, back_core);
    back.layers = layers_for(2.0 * r / back_core, LEVEL0_CORE_CELLS) * scale;
    (front, back)
}

/// Quads of one quarter: the m × m core and `layers` rings of 2m cells.
fn quads_of(plan: &Plan) -> usize {
    let m = plan.n / 2;
    m * m + plan.layers * 2 * m
}

/// Checks the arguments of [`ladder_ball`].
fn check(diameter: f64, contact_radius: f64, level: u32) -> Result<()> {
    if !(diameter.is_finite() && diameter > 0.0) {
        return Err(Error::invalid(
            "diameter",
            diameter,
            "a finite length > 0 m",
        ));
    }
    let (lo, hi) = CONTACT_RADIUS_RANGE_PER_D;
    if !(contact_radius.is_finite()
        && contact_radius >= lo * diameter
        && contact_radius <= hi * diameter)
    {
        return Err(Error::invalid(
            "contact_radius",
            contact_radius,
            format!(
                "[{:e}, {:e}] m ({lo:e} to {hi:.4} of the diameter)",
                lo * diameter,
                hi * diameter
            ),
        ));
    }
    if level > MAX_LEVEL {
        return Err(Error::invalid(
            "level",
            level,
            format!("an integer in [0, {MAX_LEVEL}]"),
        ));
    }
    Ok(())
}

/// The meridian mesh of ladder `level` (0 = the default, coarsest) for a ball of diameter
/// `diameter` (m) whose impact has the predicted contact radius `contact_radius` (m): a
/// refined core of half-width 1.5 contact radii with nominally
/// [`LEVEL0_ELEMENTS_PER_RADIUS`] · 2^level pole cells across the contact radius, graded
/// outside it; level k + 1 halves every length of level k and has 4 times its quads (see the
/// module doc). Same conventions and sets as [`super::ball::ball`] (half-disc
/// centred at the origin, pole at (0, +R), sets `axis`, `surface`, `contact`).
///
/// Errors: a diameter that is not finite and positive, a contact radius outside
/// [`CONTACT_RADIUS_RANGE_PER_D`] of the diameter, a level above [`MAX_LEVEL`], or more than
/// [`MAX_ELEMENTS`] quads.
pub fn ladder_ball(diameter: f64, contact_radius: f64, level: u32) -> Result<SectionMesh> {
    build(diameter, contact_radius, level, None)
}

/// [`ladder_ball`] with an edge band: the layer intervals whose surface rings overlap
/// [`EdgeBand::inner`, `outer`] split into `band.split` shells each, so that the rings at
/// the contact edge are `band.split` times closer ([`super::band`]); the shells
/// reach the share `band.depth` of each layer's rays from the surface (1: to the axis). Every
/// node of the mesh without the band is a node of this one.
///
/// Errors: those of [`ladder_ball`]; a band out of range, or starting inside the refined core
/// (size the mesh from a contact radius below `band.inner` / 1.5).
pub fn ladder_ball_banded(
    diameter: f64,
    contact_radius: f64,
    level: u32,
    band: &EdgeBand,
) -> Result<SectionMesh> {
    build(diameter, contact_radius, level, Some(band))
}

/// The ladder mesh, with or without a band.
fn build(
    diameter: f64,
    contact_radius: f64,
    level: u32,
    band: Option<&EdgeBand>,
) -> Result<SectionMesh> {
    check(diameter, contact_radius, level)?;
    let r = 0.5 * diameter;
    if let Some(b) = band {
        b.check(r)?;
    }
    let (front, back) = plans(r, contact_radius, level);
    let m = front.n / 2;
    let first_ray = band.map_or(0, |b| b.first_ray(2 * m));
    let layers = layer_rings(front.layers, band, surface_ring_radius(&front), first_ray)?;
    // Exact through the depth, an upper bound for a band confined to the surface.
    let quads = quads_of(&front) + quads_of(&back) + (layers.len() - front.layers) * 2 * m;
    if quads > MAX_ELEMENTS {
        return Err(Error::invalid(
            "level",
            level,
            format!("a level giving at most {MAX_ELEMENTS} elements (this one gives {quads})"),
        ));
    }
    let mut mesh = SectionMesh::default();
    let dome = build_quarter(&front, &mut mesh, false, None, &layers);
    build_quarter(&back, &mut mesh, true, Some(&dome), &uniform_layers(&back));
    Ok(with_sets(mesh, r))
}

/// The pole size (m) of [`ladder_ball`] at `level`: the mean edge of the quad at the pole.
/// Same arguments and errors as [`ladder_ball`], without building the mesh.
pub fn ladder_pole_size(diameter: f64, contact_radius: f64, level: u32) -> Result<f64> {
    check(diameter, contact_radius, level)?;
    let r = 0.5 * diameter;
    let (front, _) = plans(r, contact_radius, level);
    Ok(pole_edge(r, front.n, front.a))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::ring::shape::gauss_points;
    use crate::mesh::section::quad_area;

    const D: f64 = 0.02;
    const A: f64 = 4.7e-4;

    fn area(m: &SectionMesh, q: &[u32; 4]) -> f64 {
        quad_area(&q.map(|i| m.nodes[i as usize]))
    }

    #[test]
    fn levels_are_valid_meshes_with_surface_on_the_circle_and_sets() {
        let r = 0.5 * D;
        for level in 0..3 {
            let m = ladder_ball(D, A, level).unwrap();
            assert!(m.quads.iter().all(|q| area(&m, q) > 0.0), "level {level}");
            // The quads tile the half-disc to the arc's chord error, which falls 4× per level
            // (1.24e-3 of π R² / 2 at level 0).
            let total: f64 = m.quads.iter().map(|q| area(&m, q)).sum();
            let half_disc = 0.5 * std::f64::consts::PI * r * r;
            let tol = 1.5e-3 / 4f64.powi(level as i32);
            assert!((total / half_disc - 1.0).abs() < tol, "{total} {half_disc}");
            for &i in &m.node_sets["surface"] {
                let p = m.nodes[i as usize];
                assert!((p[0].hypot(p[1]) - r).abs() < 1e-12 * r, "{p:?}");
            }
            // The arc runs from the south pole to the north pole.
            let first = m.nodes[m.boundary[0][0] as usize];
            let last = m.nodes[m.boundary.last().unwrap()[1] as usize];
            assert_eq!((first[0], last[0]), (0.0, 0.0));
            assert!(first[1] < 0.0 && last[1] > 0.0);
            let axis = &m.node_sets["axis"];
            assert!(axis.iter().all(|&i| m.nodes[i as usize][0] == 0.0));
            assert!(m.nodes.iter().all(|p| p[0] >= 0.0));
            assert!(m.segment_sets["contact"].len() > 4);
        }
    }

    #[test]
    fn each_level_halves_the_sizes_and_quadruples_the_quads() {
        let mut last: Option<(SectionMesh, f64)> = None;
        for level in 0..4 {
            let m = ladder_ball(D, A, level).unwrap();
            let pole = ladder_pole_size(D, A, level).unwrap();
            if let Some((coarse, coarse_pole)) = &last {
                assert_eq!(m.quads.len(), 4 * coarse.quads.len(), "level {level}");
                let ratio = coarse_pole / pole;
                assert!((ratio - 2.0).abs() < 0.02, "pole ratio {ratio}");
                // Nested: every coarse node is a node of the finer mesh.
                let mut fine: Vec<[f64; 2]> = m.nodes.clone();
                fine.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
                for p in &coarse.nodes {
                    let near = fine.partition_point(|q| q[0] < p[0] - 1e-12);
                    let found = fine[near..]
                        .iter()
                        .take_while(|q| q[0] <= p[0] + 1e-12)
                        .any(|q| (q[1] - p[1]).abs() < 1e-12);
                    assert!(found, "level {level}: {p:?} missing");
                }
            }
            last = Some((m, pole));
        }
    }

    #[test]
    fn the_level0_pole_resolves_the_contact_radius() {
        let pole = ladder_pole_size(D, A, 0).unwrap();
        let per_radius = A / pole;
        assert!(
            (per_radius / LEVEL0_ELEMENTS_PER_RADIUS - 1.0).abs() < 0.1,
            "{per_radius}"
        );
        // The pole follows the contact radius.
        let small = ladder_pole_size(D, A / 4.0, 0).unwrap();
        assert!((pole / small / 4.0 - 1.0).abs() < 0.02, "{}", pole / small);
    }

    /// Rest radii of the front surface rings (z > 0), increasing.
    fn rings(m: &SectionMesh) -> Vec<f64> {
        let mut r: Vec<f64> = m.node_sets["surface"]
            .iter()
            .map(|&i| m.nodes[i as usize])
            .filter(|p| p[1] > 0.0)
            .map(|p| p[0])
            .collect();
        r.sort_by(f64::total_cmp);
        r
    }

    #[test]
    fn an_edge_band_splits_the_rings_at_the_edge_and_keeps_every_other_node() {
        let edge = 2.0 * A;
        // Even splits run through the depth, odd ones end in a transition below the surface.
        for (level, split) in [(0, 4), (1, 2), (0, 5), (1, 3)] {
            let plain = ladder_ball(D, A, level).unwrap();
            let band = EdgeBand::around(edge, split);
            let m = ladder_ball_banded(D, A, level, &band).unwrap();
            assert!(m.quads.iter().all(|q| area(&m, q) > 0.0), "level {level}");
            assert!(
                m.quads
                    .iter()
                    .all(|q| gauss_points(&q.map(|i| m.nodes[i as usize]))
                        .iter()
                        .all(|p| p.det_j > 0.0)),
                "level {level}, split {split}: an inverted Gauss point"
            );
            assert_conforming(&m);
            // Confined shells leave the axis alone; through-depth ones reach it.
            let axis = |m: &SectionMesh| m.node_sets["axis"].len();
            if split % 2 == 1 {
                assert_eq!(axis(&m), axis(&plain), "split {split}");
            } else {
                assert!(axis(&m) > axis(&plain), "split {split}");
            }
            let r = 0.5 * D;
            for &i in &m.node_sets["surface"] {
                let p = m.nodes[i as usize];
                assert!((p[0].hypot(p[1]) - r).abs() < 1e-12 * r, "{p:?}");
            }
            // Every node of the plain mesh is a node of the banded one.
            for p in &plain.nodes {
                let found = m
                    .nodes
                    .iter()
                    .any(|q| (q[0] - p[0]).abs() < 1e-12 && (q[1] - p[1]).abs() < 1e-12);
                assert!(found, "level {level}: {p:?} missing");
            }
            // The ring spacing at the edge is split times the plain mesh's; outside the band
            // the rings are the plain ones.
            let spacing = |rings: &[f64], at: f64| {
                let k = rings.partition_point(|&x| x < at);
                rings[k] - rings[k - 1]
            };
            let (pr, br) = (rings(&plain), rings(&m));
            let ratio = spacing(&pr, edge) / spacing(&br, edge);
            assert!((ratio / split as f64 - 1.0).abs() < 0.05, "{ratio}");
            let far = |rs: &[f64]| -> Vec<f64> {
                rs.iter()
                    .copied()
                    .filter(|&x| x < 0.7 * edge || x > 1.3 * edge)
                    .collect()
            };
            assert_eq!(far(&pr), far(&br));
            assert!(m.quads.len() > plain.quads.len());
        }
    }

    /// Every edge of `m` is shared by two quads, or lies on the arc or the axis.
    fn assert_conforming(m: &SectionMesh) {
        let mut count = std::collections::HashMap::new();
        for q in &m.quads {
            for k in 0..4 {
                let (a, b) = (q[k], q[(k + 1) % 4]);
                *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        let r = 0.5 * D;
        for (&(a, b), &c) in &count {
            let (p, q) = (m.nodes[a as usize], m.nodes[b as usize]);
            let on_arc = |p: [f64; 2]| (p[0].hypot(p[1]) - r).abs() < 1e-12 * r;
            let outer = (p[0] == 0.0 && q[0] == 0.0) || (on_arc(p) && on_arc(q));
            assert!(c == 2 || (c == 1 && outer), "edge {p:?}-{q:?} in {c} quads");
        }
    }

    #[test]
    fn a_confined_band_needs_an_odd_split_and_a_depth_in_range() {
        let band = EdgeBand::around(2.0 * A, 5);
        assert!(band.depth < 1.0);
        let even = EdgeBand { split: 4, ..band };
        let e = ladder_ball_banded(D, A, 0, &even).unwrap_err().to_string();
        assert!(e.contains("band.split") && e.contains("odd"), "{e}");
        for depth in [0.0, 1.5, f64::NAN] {
            let e = ladder_ball_banded(D, A, 0, &band.to_depth(depth))
                .unwrap_err()
                .to_string();
            assert!(e.contains("band.depth"), "{e}");
        }
        // A sixth of level 0's 18 rays and of level 1's 36.
        assert_eq!((band.first_ray(18), band.first_ray(36)), (15, 30));
    }

    #[test]
    fn a_band_inside_the_refined_core_is_refused() {
        // The core reaches 1.5 contact radii along the surface.
        let band = EdgeBand::around(1.2 * A, 4);
        let e = ladder_ball_banded(D, A, 0, &band).unwrap_err().to_string();
        assert!(e.contains("band.inner") && e.contains("core"), "{e}");
        let bad = EdgeBand { split: 0, ..band };
        let e = ladder_ball_banded(D, A, 0, &bad).unwrap_err().to_string();
        assert!(e.contains("band.split"), "{e}");
    }

    #[test]
    fn bad_arguments_name_the_field() {
        let msg = |r: Result<SectionMesh>| r.unwrap_err().to_string();
        assert!(msg(ladder_ball(-1.0, A, 0)).contains("diameter"));
        assert!(msg(ladder_ball(D, f64::NAN, 0)).contains("contact_radius"));
        assert!(msg(ladder_ball(D, D, 0)).contains("contact_radius"));
        assert!(msg(ladder_ball(D, A, MAX_LEVEL + 1)).contains("level"));
    }
}
