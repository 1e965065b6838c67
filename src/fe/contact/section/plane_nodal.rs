//! Penalty contact of a meridian boundary against a rigid frictionless plane z = z₀ (the
//! symmetry plane of two equal balls in a head-on impact, or a rigid wall), with the 3D
//! penalty rule: k_I = FKN · E · A_I / h_I, A_I the area of the ring the node carries,
//! A_I = Σ_segments 2π l (2 r_I + r_J)/6 (the consistent ring area ∫ N_I 2π r ds of its
//! segments of length l), h_I the thickness of the quads under it (area / segment length,
//! averaged over its segments). Frictionless: a head-on impact has no tangential slip on the
//! symmetry plane and no tangential load anywhere by symmetry about the axis.

use crate::error::{Error, Result};
use crate::fe::contact::penalty::{normal_force, stable_step};
use crate::fe::interaction::{ContactState, Interaction, InteractionEnergy, StepContext};
use crate::mesh::section::SectionMesh;
use std::f64::consts::PI;

/// Which side of the plane the body lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The body lies at z ≤ z₀ (the plane stops motion towards +z).
    Below,
    /// The body lies at z ≥ z₀.
    Above,
}

impl Side {
    /// +1 below the plane, −1 above: the sign that makes the gap sign·(z₀ − z) positive apart.
    pub fn sign(self) -> f64 {
        match self {
            Side::Below => 1.0,
            Side::Above => -1.0,
        }
    }
}

/// A rigid plane z = z₀ and the penalty springs of the boundary nodes that may touch it
/// (one spring per node: the contact area grows ring by ring).
#[derive(Debug, Clone)]
pub struct NodalPlane {
    z0: f64,
    sign: f64,
    nodes: Vec<usize>,
    k: Vec<f64>,
    state: ContactState,
}

/// Length (m) and thickness h (m: area of the quad under it over its length) of the boundary
/// segment `s` of `mesh`.
///
/// Errors: a segment that is no edge of a quad.
pub fn segment_length_and_thickness(mesh: &SectionMesh, s: [u32; 2]) -> Result<(f64, f64)> {
    let q = mesh
        .quads
        .iter()
        .find(|q| q.contains(&s[0]) && q.contains(&s[1]))
        .ok_or_else(|| {
            Error::invalid(
                "mesh.segment",
                format!("{}-{}", s[0], s[1]),
                "a boundary segment that is an edge of a quad",
            )
        })?;
    let (pa, pb) = (mesh.nodes[s[0] as usize], mesh.nodes[s[1] as usize]);
    let l = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
    Ok((
        l,
        crate::fe::elements::ring::shape::area(&q.map(|n| mesh.nodes[n as usize])) / l,
    ))
}

/// Checks a penalty factor FKN: finite and > 0.
///
/// Errors: `contact.fkn` outside that range.
pub fn check_fkn(fkn: f64) -> Result<()> {
    if fkn.is_finite() && fkn > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid("contact.fkn", fkn, "FKN > 0, finite"))
    }
}

/// Consistent ring areas (m²) and mean element thicknesses (m) of the nodes of `segments`.
pub fn ring_areas_and_thickness(
    mesh: &SectionMesh,
    segments: &[[u32; 2]],
) -> Result<Vec<(usize, f64, f64)>> {
    let mut acc: std::collections::BTreeMap<usize, (f64, f64, usize)> = Default::default();
    for s in segments {
        let (a, b) = (s[0] as usize, s[1] as usize);
        let (l, h) = segment_length_and_thickness(mesh, *s)?;
        let (pa, pb) = (mesh.nodes[a], mesh.nodes[b]);
        for (i, ri, rj) in [(a, pa[0], pb[0]), (b, pb[0], pa[0])] {
            let e = acc.entry(i).or_insert((0.0, 0.0, 0));
            e.0 += 2.0 * PI * l * (2.0 * ri + rj) / 6.0;
            e.1 += h;
            e.2 += 1;
        }
    }
    Ok(acc
        .into_iter()
        .map(|(i, (a, h, n))| (i, a, h / n as f64))
        .collect())
}

/// The energy of a penalty contact on the section: what its springs store now (their force
/// is conservative, so the work they did on the nodes is minus that, J; nothing dissipated).
pub fn penalty_energy(state: &ContactState) -> InteractionEnergy {
    InteractionEnergy {
        stored: state.stored,
        dissipated: 0.0,
        work: -state.stored,
    }
}

impl NodalPlane {
    /// The plane z = `z0` (m) with the body on `side`, acting on the nodes of `segments` of
    /// `mesh`, with penalty factor `fkn` (> 0) on Young's modulus `youngs` (Pa).
    pub fn new(
        mesh: &SectionMesh,
        segments: &[[u32; 2]],
        z0: f64,
        side: Side,
        fkn: f64,
        youngs: f64,
    ) -> Result<Self> {
        check_fkn(fkn)?;
        let nh = ring_areas_and_thickness(mesh, segments)?;
        Ok(NodalPlane {
            state: ContactState::default(),
            z0,
            sign: side.sign(),
            nodes: nh.iter().map(|t| t.0).collect(),
            k: nh.iter().map(|t| fkn * youngs * t.1 / t.2).collect(),
        })
    }

    /// The nodes (indices) and their spring stiffnesses, N/m.
    pub fn springs(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.nodes.iter().copied().zip(self.k.iter().copied())
    }
}

impl Interaction<2> for NodalPlane {
    fn name(&self) -> &str {
        "nodal plane contact"
    }

    fn add_forces(&mut self, ctx: &StepContext<'_, 2>, f: &mut [[f64; 2]]) -> Result<()> {
        let x = ctx.x;
        let mut s = ContactState::default();
        for (&i, &k) in self.nodes.iter().zip(&self.k) {
            let gap = self.sign * (self.z0 - x[i][1]);
            let fz = normal_force(k, 0.0, gap, 0.0);
            if fz > 0.0 {
                f[i][1] -= self.sign * fz;
                s.add_node(fz, 0.5 * k * gap * gap, -gap, x[i][0]);
            }
        }
        self.state = s;
        Ok(())
    }

    /// The smallest of [`Interaction::node_limits`], without collecting them: the
    /// single-rate loop asks every step.
    fn stable_time_step(&self, mass: &[f64], omega: &[f64]) -> Option<f64> {
        let steps = self
            .springs()
            .map(|(i, k)| stable_step(k, mass[i], omega[i]));
        Some(steps.fold(f64::INFINITY, f64::min))
    }

    fn energy(&self) -> InteractionEnergy {
        penalty_energy(&self.state)
    }

    fn state(&self) -> ContactState {
        self.state
    }

    fn node_limits(&self, mass: &[f64], omega: &[f64]) -> Vec<(usize, f64)> {
        // Each spring acts on its node alone: every node its own step.
        self.springs()
            .map(|(i, k)| (i, stable_step(k, mass[i], omega[i])))
            .collect()
    }
}
