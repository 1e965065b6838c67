//! Node-to-segment penalty contact between two meridian boundaries (the contact of two
//! unequal balls head-on): symmetric two-pass like the 3D code, the nodes of each boundary
//! against the segments of the other, each pass with half the stiffness
//! k_I = FKN · E · A_I / h_I (A_I the consistent ring area of the node, h_I the thickness of
//! the quads under it, E the smaller Young's modulus of the two bodies), so that matching
//! meshes carry the one-pass force. Frictionless (head-on: no tangential load by symmetry).

use super::plane_nodal::{penalty_energy, ring_areas_and_thickness};
use crate::error::{Error, Result};
use crate::fe::contact::penalty::{effective_mass, normal_force, stable_step};
use crate::fe::interaction::{ContactState, Interaction, InteractionEnergy, StepContext};

/// One boundary of the pair: its contact segments (body on their left) and the springs of
/// their nodes.
#[derive(Debug, Clone)]
struct Side {
    segments: Vec<[usize; 2]>,
    springs: Vec<(usize, f64)>,
    /// Initial radius r of each spring's node, m.
    radius: Vec<f64>,
}

/// Two-pass node-to-segment contact of two boundaries given in global node numbering.
#[derive(Debug, Clone)]
pub struct SegmentPair {
    sides: [Side; 2],
    state: ContactState,
}

/// A boundary of one body: its mesh, the contact segments (mesh numbering) and the offset
/// of the mesh's nodes in the solver's numbering.
pub struct Boundary<'a> {
    /// The body's meridian mesh.
    pub mesh: &'a crate::mesh::section::SectionMesh,
    /// Its contact segments, counter-clockwise (body on the left).
    pub segments: &'a [[u32; 2]],
    /// Index of the mesh's node 0 in the solver.
    pub offset: usize,
}

impl SegmentPair {
    /// The pair of boundaries `a` and `b` with penalty factor `fkn` (> 0) on the smaller
    /// Young's modulus `youngs` (Pa) of the two bodies.
    pub fn new(a: Boundary<'_>, b: Boundary<'_>, fkn: f64, youngs: f64) -> Result<Self> {
        if !(fkn.is_finite() && fkn > 0.0) {
            return Err(Error::invalid("contact.fkn", fkn, "FKN > 0, finite"));
        }
        let side = |s: &Boundary<'_>| -> Result<Side> {
            let nh = ring_areas_and_thickness(s.mesh, s.segments)?;
            Ok(Side {
                segments: s
                    .segments
                    .iter()
                    .map(|g| [g[0] as usize + s.offset, g[1] as usize + s.offset])
                    .collect(),
                springs: nh
                    .iter()
                    .map(|&(i, area, h)| (i + s.offset, 0.5 * fkn * youngs * area / h))
                    .collect(),
                radius: nh.iter().map(|&(i, _, _)| s.mesh.nodes[i][0]).collect(),
            })
        };
        Ok(SegmentPair {
            sides: [side(&a)?, side(&b)?],
            state: ContactState::default(),
        })
    }
}

/// The smallest mass (kg) of the master nodes a slave node at radius `r` (m) meets: those
/// of the master segments whose radial span, widened by its own length on each side, holds
/// `r` (head-on, the two contact surfaces face each other at equal r near the axis; the
/// widening covers the sliding of the surfaces over each other), or else the master node
/// nearest in r.
fn facing_mass(master: &Side, r: f64, mass: &[f64]) -> f64 {
    let r_of = |node: usize| {
        master
            .springs
            .iter()
            .position(|&(j, _)| j == node)
            .map(|p| master.radius[p])
    };
    let mut m = f64::INFINITY;
    for s in &master.segments {
        let (Some(ra), Some(rb)) = (r_of(s[0]), r_of(s[1])) else {
            continue;
        };
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        let l = hi - lo;
        if r >= lo - l && r <= hi + l {
            m = m.min(mass[s[0]]).min(mass[s[1]]);
        }
    }
    if m.is_finite() {
        return m;
    }
    master
        .springs
        .iter()
        .zip(&master.radius)
        .min_by(|a, b| (a.1 - r).abs().total_cmp(&(b.1 - r).abs()))
        .map_or(f64::INFINITY, |(&(j, _), _)| mass[j])
}

/// Where a node projects onto a segment.
#[derive(Debug, Clone, Copy)]
struct Hit {
    /// Signed gap along the segment's outward normal, m (negative inside).
    gap: f64,
    /// Position along the segment, 0 at its first node, 1 at its second.
    xi: f64,
    /// Outward unit normal of the segment.
    normal: [f64; 2],
    /// The segment's nodes.
    nodes: [usize; 2],
}

/// The closest segment of `segs` under the point `p` (m): among the segments whose
/// projection holds p and whose penetration is less than their length.
fn closest(p: [f64; 2], segs: &[[usize; 2]], x: &[[f64; 2]]) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for s in segs {
        let (a, b) = (x[s[0]], x[s[1]]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let l2 = d[0] * d[0] + d[1] * d[1];
        let l = l2.sqrt();
        let xi = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2;
        if !(0.0..=1.0).contains(&xi) {
            continue;
        }
        let n = [d[1] / l, -d[0] / l];
        let g = (p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1];
        if g < -l || g > l {
            continue;
        }
        if best.is_none_or(|b| g.abs() < b.gap.abs()) {
            best = Some(Hit {
                gap: g,
                xi,
                normal: n,
                nodes: *s,
            });
        }
    }
    best
}

impl Interaction<2> for SegmentPair {
    fn name(&self) -> &str {
        "section pair contact"
    }

    fn add_forces(&mut self, ctx: &StepContext<'_, 2>, f: &mut [[f64; 2]]) -> Result<()> {
        let x = ctx.x;
        let mut st = ContactState::default();
        for pass in 0..2 {
            let (slave, master) = (&self.sides[pass], &self.sides[1 - pass]);
            for &(i, k) in &slave.springs {
                let Some(Hit {
                    gap: g,
                    xi,
                    normal: n,
                    nodes: s,
                }) = closest(x[i], &master.segments, x)
                else {
                    continue;
                };
                let fnr = normal_force(k, 0.0, g, 0.0);
                if fnr <= 0.0 {
                    continue;
                }
                for c in 0..2 {
                    f[i][c] += fnr * n[c];
                    f[s[0]][c] -= (1.0 - xi) * fnr * n[c];
                    f[s[1]][c] -= xi * fnr * n[c];
                }
                // Axial resultant: each pass carries half the pair's force.
                st.add_node(fnr * n[1].abs(), 0.5 * k * g * g, -g, x[i][0]);
            }
        }
        self.state = st;
        Ok(())
    }

    fn stable_time_step(&self, mass: &[f64], omega: &[f64]) -> Option<f64> {
        Some(self.pair_step(mass, omega))
    }

    fn energy(&self) -> InteractionEnergy {
        penalty_energy(&self.state)
    }

    fn state(&self) -> ContactState {
        self.state
    }

    fn node_limits(&self, mass: &[f64], omega: &[f64]) -> Vec<(usize, f64)> {
        // A node's force goes to the segment it meets: the nodes of both boundaries share
        // the pair's step.
        let dt = self.pair_step(mass, omega);
        let mut nodes: Vec<usize> = self
            .sides
            .iter()
            .flat_map(|s| s.springs.iter().map(|&(i, _)| i))
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes.into_iter().map(|i| (i, dt)).collect()
    }
}

impl SegmentPair {
    /// The pair's stable step (s) on masses `mass` (kg) and element frequencies `omega`
    /// (rad/s): both passes may act on a node at once.
    fn pair_step(&self, mass: &[f64], omega: &[f64]) -> f64 {
        let mut dt = f64::INFINITY;
        for pass in 0..2 {
            let (slave, master) = (&self.sides[pass], &self.sides[1 - pass]);
            for (&(i, k), &r) in slave.springs.iter().zip(&slave.radius) {
                // Both passes can act on a node at once: the full stiffness 2k, on the node
                // and the master nodes it meets.
                let m = effective_mass(mass[i], facing_mass(master, r, mass));
                dt = dt.min(stable_step(2.0 * k, m, omega[i]));
            }
        }
        dt
    }
}
