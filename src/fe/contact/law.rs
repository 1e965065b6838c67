//! The contact law of one node: penalty spring and dashpot in the normal direction, Coulomb
//! stick spring and return mapping in the tangent plane.

use super::friction::{return_map, stick_energy, CoulombFriction, StickState};
use super::params::ContactParams;
use super::penalty::{damping_constant, normal_force};
use crate::fe::tensor::{add, norm, scale, tangential};

/// Constants of one contact node, fixed after the first step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NodeLaw {
    /// Normal penalty stiffness (already times the pass weight), N/m.
    pub k: f64,
    /// Tangential stick stiffness, N/m.
    pub kt: f64,
    /// Normal dashpot, N s/m.
    pub c: f64,
    /// Highest element frequency at the node, 2 c / L (wave speed c, Courant length L), rad/s.
    pub omega_elem: f64,
}

impl NodeLaw {
    /// Raises the normal stiffness to at least `k_min` (N/m: the time-step rule's, already
    /// times the pass weight) and sets the tangential stiffness and the dashpot from it as
    /// `params` say, for the node's effective mass `m` (kg).
    pub fn stiffen(&mut self, params: &ContactParams, k_min: f64, m: f64) {
        self.k = self.k.max(k_min);
        self.kt = params.tangential_ratio * self.k;
        self.c = damping_constant(params.damping, self.k, m);
    }
}

/// What one node did this step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NodeResponse {
    /// Normal force magnitude, N (≥ 0).
    pub normal: f64,
    /// Tangential force on the node, N.
    pub tangential: [f64; 3],
    /// Energy dissipated this step by friction and the dashpot, J.
    pub dissipated: f64,
    /// The friction part of `dissipated`, J.
    pub friction: f64,
}

impl NodeResponse {
    /// Total force on the node for outward normal `n` of the opposing surface, N.
    pub fn force(&self, n: [f64; 3]) -> [f64; 3] {
        add(scale(self.normal, n), self.tangential)
    }
}

/// Where a node is relative to the opposing surface this step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NodeKinematics {
    /// Signed gap, m (< 0 in contact).
    pub gap: f64,
    /// Opening rate of the gap, m/s.
    pub gap_rate: f64,
    /// Relative displacement over the last step, m (its tangential part is the slip).
    pub slip: [f64; 3],
    /// Outward unit normal of the opposing surface.
    pub normal: [f64; 3],
    /// The step the rates act over, s.
    pub dt: f64,
}

/// Evaluates the law at kinematics `k`; `friction` `None` for frictionless.
///
/// The stick force is rotated into the current tangent plane (keeping its length) before the
/// return mapping, so rigid rotations of the contact plane do not create slip.
pub fn respond(
    law: &NodeLaw,
    stick: &mut StickState,
    k: &NodeKinematics,
    friction: Option<CoulombFriction>,
) -> NodeResponse {
    let (gap, gap_rate, slip, n, dt) = (k.gap, k.gap_rate, k.slip, k.normal, k.dt);
    let fe = normal_force(law.k, 0.0, gap, 0.0);
    let fnormal = normal_force(law.k, law.c, gap, gap_rate);
    // Dashpot power −F_d ġ (F_d = fnormal − fe acts against the gap rate).
    let mut dissipated = ((fnormal - fe) * -gap_rate * dt).max(0.0);
    let mut ft = [0.0; 3];
    let mut fric = 0.0;
    if let Some(c) = friction {
        let old = norm(stick.force);
        let mut rot = tangential(stick.force, n);
        let l = norm(rot);
        rot = if l > 0.0 {
            scale(old / l, rot)
        } else {
            [0.0; 3]
        };
        stick.force = rot;
        fric = return_map(stick, tangential(slip, n), law.kt, fnormal, c);
        dissipated += fric;
        ft = stick.force;
    }
    NodeResponse {
        normal: fnormal,
        tangential: ft,
        dissipated,
        friction: fric,
    }
}

/// Stored energy of a node in contact at gap `gap` (m): penalty spring plus stick spring, J.
pub fn stored_energy(law: &NodeLaw, stick: &StickState, gap: f64) -> f64 {
    let g = gap.min(0.0);
    0.5 * law.k * g * g
        + if law.kt > 0.0 {
            stick_energy(stick, law.kt)
        } else {
            0.0
        }
}
