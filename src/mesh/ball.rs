//! Conforming all-hex meshes of a ball, graded toward the contact pole (+R, 0, 0).
//!
//! Construction (see docs/design.md, section 3). The sphere inversion
//! `X = Q + 4R^2 (Y - Q) / |Y - Q|^2` about the antipode Q = (-R, 0, 0) fixes the pole
//! P = (R, 0, 0) and maps the half-ball `|Y - P| <= 2R, Y_x >= R` exactly onto the front half
//! `x >= 0` of the ball: the flat face onto the front hemisphere of the surface, the dome onto
//! the equatorial disk x = 0, and spheres centred on P onto spheres that meet the ball surface
//! at right angles. The half-ball is meshed as an O-grid centred on P: a half-cube core of
//! cells of the pole size, wrapped by spherical layers that grow geometrically (ratio about
//! 1 + 1.9/n for n cells along a cube edge), so every layer has the same number of cells.
//! The refinement therefore stays local to the pole in all three directions instead of
//! spreading along grid lines, and the element count grows only with log(R / h_pole). The
//! inversion is conformal, so cube-like cells stay cube-like. The back half is the mirror image
//! of the same construction without pole refinement; both halves put identical nodes on the
//! disk x = 0, so the mesh is conforming with no hanging nodes.

use super::{topology::boundary_faces, Mesh};
use crate::error::{Error, Result};
use std::collections::BTreeMap;
use std::f64::consts::PI;

/// Polar half-angle (degrees, measured from +x at the ball centre) of the contact-candidate
/// patch. A 2 m/s copper impact of 20 mm balls has a contact radius under 1 mm (about 6
/// degrees); 30 degrees leaves ample room for larger, softer or faster impacts.
pub const CONTACT_HALF_ANGLE_DEG: f64 = 30.0;

/// Largest element count the mesher will build (a guard against typing 1e-6 for the size).
pub const MAX_ELEMENTS: usize = 4_000_000;

pub use super::cut::Cut;

/// What to mesh. Lengths in metres.
#[derive(Debug, Clone, PartialEq)]
pub struct BallSpec {
    /// Ball diameter D, m.
    pub diameter: f64,
    /// Far-field element size h, m: an upper bound on element edges away from the pole (they
    /// lie between about 0.2 h and 0.6 h, so that flat facets keep the volume within 0.5 % at
    /// h = R / 5).
    pub size: f64,
    /// Element size at the contact pole, m; `None` meshes the ball uniformly (pole size = h).
    /// A pole size above about a fifth of `size` (and below the surface facet) gets the finest
    /// pole core that fits ([`CORE_REACH`]), about `size` / 4.7.
    pub pole_size: Option<f64>,
    /// Full ball or a symmetric part.
    pub cut: Cut,
}

/// The checked sizes of a ball mesh: radius R (m), cells n along a core edge (even) and the
/// surface facet size π R / (2n) (m) of the unrefined parts. Shared by the 3D and the
/// meridian mesher, so both refuse the same inputs with the same messages.
///
/// Errors: non-finite or non-positive `diameter` or `size`, `size` above the radius or below
/// radius / 600, `pole_size` above `size` or below `size / 10^4`.
pub(super) fn core_cells(
    diameter: f64,
    size: f64,
    pole_size: Option<f64>,
) -> Result<(f64, usize, f64)> {
    let d = diameter;
    if !(d.is_finite() && d > 0.0) {
        return Err(Error::invalid("diameter", d, "a finite length > 0 m"));
    }
    let r = 0.5 * d;
    let h = size;
    if !(h.is_finite() && h > 0.0 && h <= r) {
        return Err(Error::invalid(
            "size",
            h,
            format!("0 < size <= radius = {r} m"),
        ));
    }
    let h0 = pole_size.unwrap_or(h);
    if !(h0.is_finite() && h0 <= h && h0 >= h * 1e-4) {
        return Err(Error::invalid(
            "pole_size",
            h0,
            format!("size/1e4 <= pole_size <= size = {h} m"),
        ));
    }
    // Cells along a core edge: the disk x = 0 gets 4n cells of about pi R / (2n) <= h/2
    // around its rim, and no element edge away from the pole exceeds about 0.6 h. Even, so
    // that grid planes lie on y = 0 and z = 0.
    let n_raw = (PI * r / h * (1.0 - 1e-9)).ceil().max(4.0);
    if n_raw > 2000.0 {
        return Err(Error::invalid(
            "size",
            h,
            format!("size >= radius / 600 = {:.4e} m", r / 600.0),
        ));
    }
    let n = (n_raw as usize).div_ceil(2) * 2;
    // Surface facet size at the rim of the disk x = 0; the unrefined parts use it everywhere.
    let facet = PI * r / (2.0 * n as f64);
    Ok((r, n, facet))
}

/// Meshes a ball of diameter `spec.diameter` centred at the origin with 8-node hexahedra,
/// refined toward the pole (+R, 0, 0).
///
/// Face sets (outward quads): `surface` (the spherical boundary only), `contact` (surface
/// quads with at least one node within [`CONTACT_HALF_ANGLE_DEG`] of +x, seen from the
/// centre), `sym_y` / `sym_z` (quads on the cut planes y = 0 / z = 0, empty when that plane is
/// not a cut). Each node set is the node set of the face set of the same name, so `contact`
/// holds every surface node within the contact angle plus the ring just outside it, and a
/// mesh written to `.msh` and read back keeps its sets. `Mesh::boundary` holds every boundary
/// quad, cut planes included. Output is deterministic.
///
/// Errors: non-finite or non-positive sizes, `size` above the radius, `pole_size` above
/// `size` or below `size / 10^4`, or more than [`MAX_ELEMENTS`] elements.
pub fn ball(spec: &BallSpec) -> Result<Mesh> {
    let (r, n, facet) = core_cells(spec.diameter, spec.size, spec.pole_size)?;
    let front = match spec.pole_size {
        Some(p) if p < facet => Plan::refined(r, n, p),
        _ => Plan::uniform(r, n, facet),
    };
    let back = Plan::uniform(r, n, facet);
    let estimate = front.elements() + back.elements();
    if estimate > MAX_ELEMENTS {
        return Err(Error::invalid(
            "size",
            spec.size,
            format!("a size giving at most {MAX_ELEMENTS} elements (this one gives {estimate})"),
        ));
    }
    let mut mesh = Mesh::default();
    let dome = front.build(&mut mesh, false, None);
    back.build(&mut mesh, true, Some(&dome));
    let mesh = cut(mesh, spec.cut, r);
    Ok(with_sets(mesh, spec.cut, r))
}

/// Spacing function of the core grid on [-1, 1]: a blend of uniform (gnomonic) and tangent
/// (equiangular) spacing. Pure tangent spacing makes the outer core cells twice as deep as the
/// first spherical layer; the blend keeps that jump near the 1.3 target while keeping the
/// angular cell size on the sphere within a factor of about 1.5.
fn spacing(s: f64) -> f64 {
    (1.0 - SPACING_BLEND) * s + SPACING_BLEND * (0.25 * PI * s).tan()
}

/// Weight of tangent spacing in [`spacing`].
const SPACING_BLEND: f64 = 0.25;

/// Slope of [`spacing`] at 0: the angular cell size at a core face centre is `spacing'(0) 2/n`.
fn spacing_slope0() -> f64 {
    1.0 - SPACING_BLEND + SPACING_BLEND * 0.25 * PI
}

/// How far the core surface of an unrefined half-ball is rounded toward a sphere (0 = flat
/// cube faces, 1 = sphere); the rest of the rounding happens in the spherical layers. The
/// refined core is not rounded: rounding shrinks its corner cells below the pole cells, and
/// its many layers make the cube-to-sphere transition gentle anyway.
const CORE_ROUNDING: f64 = 0.5;

/// Geometry of one O-grid half-ball in local coordinates (u inward from the pole, v, w).
pub(super) struct Plan {
    /// Ball radius, m.
    pub(super) r: f64,
    /// Cells along a core edge (even); the core has n/2 cells in depth.
    pub(super) n: usize,
    /// Core half-width, m.
    pub(super) a: f64,
    /// Number of spherical layers.
    pub(super) layers: usize,
    /// Length scale of the core's depth correction (see [`core_point`]).
    pub(super) deepen: f64,
}

impl Plan {
    /// Unrefined half-ball: core cells at the face centres of size `cell` (m).
    pub(super) fn uniform(r: f64, n: usize, cell: f64) -> Plan {
        Plan::with_core(r, n, cell * n as f64 / (2.0 * spacing_slope0()))
    }

    /// Half-ball refined at the pole: the shortest core edge is `h_pole` (m), or shorter
    /// when a core that large would reach the dome ([`CORE_REACH`]; a pole size within a
    /// factor of about 4 of the bulk size): then the largest core that fits.
    pub(super) fn refined(r: f64, n: usize, h_pole: f64) -> Plan {
        // Edges scale with a while the core is small against R: a few fixed-point steps on
        // the shortest edge of the mapped core give a = the requested pole size. For a large
        // core the steps diverge (the inversion shrinks its deep cells).
        let mut a = h_pole * n as f64 / (2.0 * spacing_slope0());
        for _ in 0..4 {
            a *= h_pole / shortest_core_edge(r, n, a, 2.0 * r);
        }
        if !(a.is_finite() && core_reach(a, r, n) <= CORE_REACH * 2.0 * r) {
            a = largest_core(r, n);
        }
        let mut plan = Plan::with_core(r, n, a);
        plan.deepen = 2.0 * r;
        plan
    }

    pub(super) fn with_core(r: f64, n: usize, a: f64) -> Plan {
        // Never bigger than fits comfortably inside the dome radius 2R.
        let a = a.min(1.25 * r);
        // Layers grow like the angular cell size so that cells stay cube-like; the ratio
        // never exceeds 1.3.
        let q_ideal = 1.0 + spacing_slope0() * 2.0 / n as f64;
        let span = (2.0 * r / a).ln();
        let layers = ((span / q_ideal.ln()).round() as usize)
            .max((span / 1.3f64.ln()).ceil() as usize)
            .max(1);
        Plan {
            r,
            n,
            a,
            layers,
            deepen: f64::INFINITY,
        }
    }

    fn elements(&self) -> usize {
        let n = self.n;
        let m = n / 2;
        m * n * n + self.layers * (n * n + 4 * n * m)
    }

    /// Appends this half-ball's nodes and hexes to `mesh`. The front half (`mirror` false)
    /// is refined at P; the back half is its reflection in x = 0. `dome` (the front's dome
    /// node ids, by pattern index) makes the back reuse the front's nodes on x = 0. Returns
    /// this half's dome node ids.
    fn build(&self, mesh: &mut Mesh, mirror: bool, dome: Option<&[u32]>) -> Vec<u32> {
        let (n, m, a, r) = (self.n, self.n / 2, self.a, self.r);
        let id = |i: usize, j: usize, k: usize| i + (m + 1) * (j + (n + 1) * k);
        let mut local = vec![[0.0; 3]; (m + 1) * (n + 1) * (n + 1)];
        for k in 0..=n {
            for j in 0..=n {
                for i in 0..=m {
                    local[id(i, j, k)] = core_point(i, j, k, n, a, self.deepen);
                }
            }
        }
        let core = super::structured_hexes([m, n, n], |i, j, k| id(i, j, k) as u32);
        // Outer core faces (all but the flat face u = 0 on the ball surface), outward.
        let on_flat = |c: u32| (c as usize).is_multiple_of(m + 1);
        let outer: Vec<[u32; 4]> = boundary_faces(&core)
            .into_iter()
            .filter(|q| !q.iter().all(|&c| on_flat(c)))
            .collect();
        // Pattern nodes: the core surface nodes the layers grow from, in first-seen order.
        let mut pattern_of = vec![usize::MAX; local.len()];
        let mut pattern = Vec::new();
        for q in &outer {
            for &c in q {
                if pattern_of[c as usize] == usize::MAX {
                    pattern_of[c as usize] = pattern.len();
                    pattern.push(c as usize);
                }
            }
        }
        // Layer l node on the ray of pattern node p: radius r0^(1 - l/L) (2R)^(l/L), from the
        // core surface distance r0 (a rounded cube) to the sphere of radius 2R at the dome,
        // geometric along every ray.
        let big_l = self.layers;
        let n_core = local.len();
        let mut shell = Vec::with_capacity(pattern.len() * big_l);
        for l in 1..=big_l {
            let frac = l as f64 / big_l as f64;
            for &c in &pattern {
                // Along the ray through core surface node c, from its distance r0 to 2R.
                let t = local[c];
                let len = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
                let rad = if l == big_l {
                    2.0 * r
                } else {
                    len.powf(1.0 - frac) * (2.0 * r).powf(frac)
                };
                shell.push(t.map(|x| x / len * rad));
            }
        }
        // Map to the ball. Node ids: core, then layers; dome nodes may be shared.
        let base = mesh.nodes.len() as u32;
        let np = pattern.len();
        let dome_start = n_core + (big_l - 1) * np;
        let mut global = Vec::with_capacity(n_core + shell.len());
        let mut next = base;
        for (loc_id, y) in local.iter().chain(shell.iter()).enumerate() {
            if loc_id >= dome_start {
                if let Some(shared) = dome {
                    global.push(shared[loc_id - dome_start]);
                    continue;
                }
            }
            let mut x = invert(*y, r);
            if loc_id < n_core && on_flat(loc_id as u32) {
                // Exactly on the sphere (the flat face maps onto it).
                let len = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
                x = x.map(|c| c * r / len);
            }
            if loc_id >= dome_start {
                x[0] = 0.0; // the dome maps onto the plane x = 0
            }
            if mirror {
                x[0] = -x[0];
            }
            mesh.nodes.push(x);
            global.push(next);
            next += 1;
        }
        let layer_node = |l: usize, c: u32| -> u32 {
            if l == 0 {
                global[c as usize]
            } else {
                global[n_core + (l - 1) * np + pattern_of[c as usize]]
            }
        };
        let start = mesh.hexes.len();
        for h in &core {
            mesh.hexes.push(h.map(|c| global[c as usize]));
        }
        for q in &outer {
            for l in 1..=big_l {
                let b = q.map(|c| layer_node(l - 1, c));
                let t = q.map(|c| layer_node(l, c));
                mesh.hexes
                    .push([b[0], b[1], b[2], b[3], t[0], t[1], t[2], t[3]]);
            }
        }
        // The inversion reverses orientation (and the mirror reverses it back): restore
        // positive Jacobians by reversing the node order where needed.
        let p0 = super::quality::hex_points(mesh, &mesh.hexes[start]);
        if super::quality::hex_volume(&p0) < 0.0 {
            for h in &mut mesh.hexes[start..] {
                *h = [h[0], h[3], h[2], h[1], h[4], h[7], h[6], h[5]];
            }
        }
        (0..np).map(|p| global[dome_start + p]).collect()
    }
}

/// Grid point (i, j, k) of the unit half-cube [0, 1] x [-1, 1]^2 with n/2 x n x n cells,
/// spaced by [`spacing`].
fn cube_point(i: usize, j: usize, k: usize, n: usize) -> [f64; 3] {
    [
        spacing(2.0 * i as f64 / n as f64),
        spacing(-1.0 + 2.0 * j as f64 / n as f64),
        spacing(-1.0 + 2.0 * k as f64 / n as f64),
    ]
}

/// Core node (local coordinates, m) of a half-cube of half-width `a`.
///
/// Unrefined core (`deepen` infinite): rounded toward a sphere, each grid point pulled in along
/// its ray by (|t| / max|t_i|)^(-rounding max|t_i|), which leaves the centre alone and turns
/// the cube surface into r = a |t|^(1 - rounding). Refined core (`deepen` = 2R): not rounded,
/// but pushed out along its ray by (1 + u / 2R)^2, which offsets the inversion's shrinking of
/// deeper cells (its scale is (2R / (2R + u))^2 along the axis) so that the cells at the pole
/// are as small as any.
pub(super) fn core_point(i: usize, j: usize, k: usize, n: usize, a: f64, deepen: f64) -> [f64; 3] {
    let rounding = if deepen.is_finite() {
        0.0
    } else {
        CORE_ROUNDING
    };
    let t = cube_point(i, j, k, n);
    let mx = t.iter().fold(0.0f64, |s, x| s.max(x.abs()));
    let f = if mx > 0.0 {
        let c = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt() / mx;
        a * c.powf(-rounding * mx)
    } else {
        a
    };
    let g = (1.0 + t[0] * f / deepen).powi(2);
    t.map(|x| x * f * g)
}

/// Largest distance of a refined core's nodes from the pole before the inversion, as a
/// share of the dome radius 2R, that leaves room for the spherical layers: beyond about 0.6
/// the layers on the core's corner rays grow thinner than half the pole cells (a smaller
/// stable step), and a core reaching the dome folds them over it (inverted hexes). Pole
/// sizes down to about a fifth of the bulk size need no more than 0.6.
pub const CORE_REACH: f64 = 0.6;

/// Distance (m) from the pole, before the inversion, of the farthest node of a refined core
/// of half-width `a` (m) with `n` cells along an edge on a ball of radius `r` (m): a deep
/// corner ([`core_point`] at i = n/2, j = k = 0).
fn core_reach(a: f64, r: f64, n: usize) -> f64 {
    let p = core_point(n / 2, 0, 0, n, a, 2.0 * r);
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

/// The half-width (m) of the refined core whose reach is [`CORE_REACH`] of the dome radius,
/// with `n` cells along an edge on a ball of radius `r` (m) (bisection; the reach grows with
/// the half-width).
fn largest_core(r: f64, n: usize) -> f64 {
    let target = CORE_REACH * 2.0 * r;
    let (mut lo, mut hi) = (0.0, 2.0 * r);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if core_reach(mid, r, n) <= target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// Shortest edge (m) of the core of half-width `a` after mapping onto the ball.
fn shortest_core_edge(r: f64, n: usize, a: f64, deepen: f64) -> f64 {
    let m = n / 2;
    let x = |i, j, k| invert(core_point(i, j, k, n, a, deepen), r);
    let mut shortest = f64::INFINITY;
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=m {
                let p = x(i, j, k);
                for (di, dj, dk) in [(1, 0, 0), (0, 1, 0), (0, 0, 1)] {
                    if i + di <= m && j + dj <= n && k + dk <= n {
                        let q = x(i + di, j + dj, k + dk);
                        let e = [0, 1, 2].map(|c| q[c] - p[c]);
                        shortest = shortest.min((e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt());
                    }
                }
            }
        }
    }
    shortest
}

/// Sphere inversion about the antipode Q = (-R, 0, 0) with radius 2R, applied to the local
/// point (u, v, w) = Y - P: maps the half-ball around P onto the front half of the ball.
pub(super) fn invert(y: [f64; 3], r: f64) -> [f64; 3] {
    let d = [2.0 * r + y[0], y[1], y[2]];
    let f = 4.0 * r * r / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    [-r + f * d[0], f * d[1], f * d[2]]
}

/// Keeps the elements on the kept side of the cut planes and renumbers the nodes in their
/// original order. Nodes within 1e-12 R of a cut plane are put exactly on it.
fn cut(mesh: Mesh, cut: Cut, r: f64) -> Mesh {
    let (keep_y, keep_z) = match cut {
        Cut::Full => return finish(mesh),
        Cut::Half => (false, true),
        Cut::Quarter => (true, true),
    };
    let centroid =
        |h: &[u32; 8], a: usize| h.iter().map(|&i| mesh.nodes[i as usize][a]).sum::<f64>();
    let hexes: Vec<[u32; 8]> = mesh
        .hexes
        .iter()
        .filter(|h| (!keep_y || centroid(h, 1) > 0.0) && (!keep_z || centroid(h, 2) > 0.0))
        .copied()
        .collect();
    let mut used = vec![u32::MAX; mesh.nodes.len()];
    let mut nodes = Vec::new();
    let tol = 1e-12 * r;
    let mut hexes_out = Vec::with_capacity(hexes.len());
    for h in &hexes {
        hexes_out.push(h.map(|i| {
            if used[i as usize] == u32::MAX {
                used[i as usize] = nodes.len() as u32;
                let mut p = mesh.nodes[i as usize];
                for c in p.iter_mut().skip(1) {
                    if c.abs() <= tol {
                        *c = 0.0;
                    }
                }
                nodes.push(p);
            }
            used[i as usize]
        }));
    }
    finish(Mesh {
        nodes,
        hexes: hexes_out,
        ..Default::default()
    })
}

fn finish(mut mesh: Mesh) -> Mesh {
    mesh.boundary = boundary_faces(&mesh.hexes);
    mesh
}

/// Adds the node and face sets (see [`ball`]).
fn with_sets(mut mesh: Mesh, cut: Cut, r: f64) -> Mesh {
    let on_plane = |q: &[u32; 4], a: usize| q.iter().all(|&i| mesh.nodes[i as usize][a] == 0.0);
    let (cut_y, cut_z) = match cut {
        Cut::Full => (false, false),
        Cut::Half => (false, true),
        Cut::Quarter => (true, true),
    };
    let mut faces: BTreeMap<String, Vec<[u32; 4]>> = BTreeMap::new();
    for name in ["surface", "contact", "sym_y", "sym_z"] {
        faces.insert(name.into(), Vec::new());
    }
    let cos_c = CONTACT_HALF_ANGLE_DEG.to_radians().cos();
    let in_contact = |i: u32| {
        let p = mesh.nodes[i as usize];
        p[0] >= cos_c * r * (1.0 - 1e-12)
    };
    for q in &mesh.boundary {
        if cut_y && on_plane(q, 1) {
            faces.get_mut("sym_y").unwrap().push(*q);
        } else if cut_z && on_plane(q, 2) {
            faces.get_mut("sym_z").unwrap().push(*q);
        } else {
            faces.get_mut("surface").unwrap().push(*q);
            if q.iter().any(|&i| in_contact(i)) {
                faces.get_mut("contact").unwrap().push(*q);
            }
        }
    }
    let nodes_of = |qs: &[[u32; 4]]| {
        let mut v: Vec<u32> = qs.iter().flatten().copied().collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let mut sets = BTreeMap::new();
    let surface = nodes_of(&faces["surface"]);
    sets.insert("contact".to_string(), nodes_of(&faces["contact"]));
    sets.insert("surface".to_string(), surface);
    sets.insert("sym_y".to_string(), nodes_of(&faces["sym_y"]));
    sets.insert("sym_z".to_string(), nodes_of(&faces["sym_z"]));
    mesh.node_sets = sets;
    mesh.face_sets = faces;
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inversion_maps_the_half_ball_onto_the_front_half() {
        let r = 0.01;
        // Pole fixed, flat face onto the sphere, dome onto x = 0.
        assert_eq!(invert([0.0, 0.0, 0.0], r), [r, 0.0, 0.0]);
        for (v, w) in [(0.003, 0.0), (0.01, -0.007), (0.0, 0.02)] {
            let x = invert([0.0, v, w], r);
            let len = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
            assert!((len - r).abs() < 1e-15, "{x:?}");
        }
        let d = [0.3f64, -0.5, 0.2];
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let x = invert(d.map(|c| c / l * 2.0 * r), r);
        assert!(x[0].abs() < 1e-15, "{x:?}");
    }

    #[test]
    fn a_pole_size_near_the_bulk_size_gives_a_valid_mesh() {
        // Pole sizes from 1/2.1 to 1/6 of the bulk size: the fixed point of the core size
        // diverges above about 1/4 and a core reaching the dome folds the layers (scaled
        // Jacobian -1); one nearly reaching it leaves sliver layers on its corner rays.
        for d_over_size in [5.0, 6.0, 10.0, 28.0] {
            for ratio in [2.1, 2.5, 3.0, 3.5, 3.8, 4.0, 4.5, 6.0] {
                let size = 0.005 / d_over_size;
                let spec = BallSpec {
                    diameter: 0.005,
                    size,
                    pole_size: Some(size / ratio),
                    cut: Cut::Half,
                };
                let q = crate::mesh::quality::summary(&ball(&spec).unwrap());
                let at = format!("D/{d_over_size}, size/pole {ratio}");
                assert!(q.min_scaled_jacobian > 0.3, "{at}: {q:?}");
                assert!(q.min_edge <= 1.01 * size / ratio, "{at}: {q:?}");
                assert!(q.min_edge >= size / 12.0, "{at}: a sliver layer, {q:?}");
            }
        }
    }

    #[test]
    fn refined_core_has_the_requested_shortest_edge() {
        let plan = Plan::refined(0.01, 16, 1e-4);
        let e = shortest_core_edge(0.01, 16, plan.a, plan.deepen);
        assert!((e - 1e-4).abs() < 1e-7, "{e}");
        assert!(plan.layers > 10, "{}", plan.layers);
    }
}
