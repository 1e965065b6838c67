//! Kinematic (constraint) contact of a meridian boundary against a rigid frictionless plane
//! z = z₀: the plane is a unilateral support, enforced exactly at every kick instead of by a
//! penalty spring.
//!
//! Central differences move node i over its next step Δt⁺ with the half-step velocity
//! v^{n+1/2} = v^{n−1/2} + ½(Δt⁻ + Δt⁺) a^n, Δt⁻ the step just closed. When the position this
//! predicts, z^{n+1} = z^n + Δt⁺ v_z^{n+1/2}, lies beyond the plane, the plane adds the
//! normal acceleration that puts it on the plane exactly:
//!
//!   a_z^n = 2 ((z₀ − z^n)/Δt⁺ − v_z^{n−1/2}) / (Δt⁻ + Δt⁺),
//!
//! i.e. the contact force f = m (a_z − a_z,free) of the whole ring. The force only pushes:
//! a node the solid pulls off the plane predicts a position off it and gets none. This is the
//! forward-increment Lagrange multiplier of Carpenter, Taylor & Katona (1991) for a rigid
//! surface, where each constraint involves one node and needs no system solve (the rigid wall
//! of DYNA3D-type codes). Compared with the penalty plane ([`super::plane_nodal`]) it has no
//! compliance (the penalty's FKN → ∞ limit), no stable-step limit of its own (the step is the
//! elements'), and no stored energy; a node that lands loses its normal velocity relative to
//! the plane, and that work is the contact's (counted as external work, ≤ 0 on landing).
//!
//! With subcycling every node drifts with its constant half-step velocity between its kicks,
//! so a node put on the plane at its next kick lies off the plane at every fine step before.

use super::plane_nodal::{ring_areas_and_thickness, Side};
use crate::error::Result;
use crate::fe::interaction::{ContactState, Interaction, InteractionEnergy, Kick, StepContext};
use crate::mesh::section::SectionMesh;

/// A rigid plane z = z₀ enforced as a unilateral kinematic constraint on boundary nodes.
#[derive(Debug, Clone)]
pub struct KinematicPlane {
    z0: f64,
    sign: f64,
    nodes: Vec<usize>,
    /// Contact force of the whole ring on each of `nodes` at its last kick, N (≥ 0, along
    /// −sign·z).
    force: Vec<f64>,
    /// Index into `nodes` of every mesh node (usize::MAX for nodes the plane does not hold).
    slot: Vec<usize>,
    /// The state of the last force evaluation.
    state: ContactState,
    /// Work of the plane's forces on the nodes so far, J.
    work: f64,
}

/// The normal acceleration (m/s²) that puts a node at `z` (m) with half-step velocity `vz`
/// (m/s) and free acceleration `az` (m/s²) on the plane `z0` (m) after a kick closing a step
/// of `close` s and opening one of `open` s, or `None` when the free motion stays on the
/// body's side (`sign` +1: the body lies at z ≤ z₀) or `open` is not positive.
#[inline]
pub fn landing_acceleration(
    z: f64,
    vz: f64,
    az: f64,
    z0: f64,
    sign: f64,
    close: f64,
    open: f64,
) -> Option<f64> {
    if open <= 0.0 {
        return None;
    }
    let span = 0.5 * (close + open);
    let predicted = z + open * (vz + span * az);
    (sign * (predicted - z0) > 0.0).then(|| ((z0 - z) / open - vz) / span)
}

impl KinematicPlane {
    /// The plane z = `z0` (m) with the body on `side`, holding the nodes of `segments` of
    /// `mesh` (the nodes of the whole section are `mesh`'s, indices unchanged).
    ///
    /// Errors: a segment that is no edge of a quad.
    pub fn new(mesh: &SectionMesh, segments: &[[u32; 2]], z0: f64, side: Side) -> Result<Self> {
        let nodes: Vec<usize> = ring_areas_and_thickness(mesh, segments)?
            .iter()
            .map(|t| t.0)
            .collect();
        let mut slot = vec![usize::MAX; mesh.nodes.len()];
        for (k, &i) in nodes.iter().enumerate() {
            slot[i] = k;
        }
        Ok(KinematicPlane {
            z0,
            sign: side.sign(),
            force: vec![0.0; nodes.len()],
            nodes,
            slot,
            state: ContactState::default(),
            work: 0.0,
        })
    }

    /// The index into the plane's nodes of mesh node `i`, or `None` if the plane does not
    /// hold it.
    fn slot_of(&self, i: usize) -> Option<usize> {
        self.slot.get(i).copied().filter(|&k| k != usize::MAX)
    }
}

impl Interaction<2> for KinematicPlane {
    fn name(&self) -> &str {
        "kinematic plane contact"
    }

    fn add_forces(&mut self, ctx: &StepContext<'_, 2>, _f: &mut [[f64; 2]]) -> Result<()> {
        let x = ctx.x;
        let mut s = ContactState::default();
        for (&i, &f) in self.nodes.iter().zip(&self.force) {
            if f > 0.0 {
                s.normal_force += f;
                s.active_nodes += 1;
                s.contact_radius = s.contact_radius.max(x[i][0]);
            }
            s.max_penetration = s.max_penetration.max(self.sign * (x[i][1] - self.z0));
        }
        self.state = s;
        Ok(())
    }

    fn stable_time_step(&self, _mass: &[f64], _omega: &[f64]) -> Option<f64> {
        None
    }

    fn energy(&self) -> InteractionEnergy {
        InteractionEnergy {
            work: self.work,
            ..Default::default()
        }
    }

    fn state(&self) -> ContactState {
        self.state
    }

    fn holds(&self, i: usize) -> bool {
        self.slot_of(i).is_some()
    }

    fn constrain(&mut self, i: usize, node: Kick<2>, a: &mut [f64; 2]) -> f64 {
        let Some(k) = self.slot_of(i) else {
            return 0.0;
        };
        let (z, vz) = (node.x[1], node.v_half[1]);
        let land = landing_acceleration(z, vz, a[1], self.z0, self.sign, node.close, node.open);
        let Some(az) = land else {
            self.force[k] = 0.0;
            return 0.0;
        };
        let f = node.mass * (az - a[1]);
        a[1] = az;
        self.force[k] = -self.sign * f;
        // Work of the force at t^n over half of each step around it.
        let v_next = vz + 0.5 * (node.close + node.open) * az;
        let work = f * 0.5 * (node.close * vz + node.open * v_next);
        self.work += work;
        work
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_free_node_short_of_the_plane_gets_no_force() {
        // 1 m/s towards z0 = 1 mm from 0.9 mm, steps of 1 µs: it stays short.
        assert!(landing_acceleration(0.9e-3, 1.0, 0.0, 1e-3, 1.0, 1e-6, 1e-6).is_none());
        // Moving away from the plane while on it: no force.
        assert!(landing_acceleration(1e-3, -1.0, 0.0, 1e-3, 1.0, 1e-6, 1e-6).is_none());
    }

    #[test]
    fn a_node_that_would_cross_lands_exactly_on_the_plane() {
        let (z0, close, open) = (1e-3, 2e-9, 4e-9);
        for (z, vz, az) in [
            (0.999_999e-3, 800.0, 0.0),
            (1e-3, 0.7, 3e8),
            (1e-3, 0.0, 1e6),
        ] {
            let a = landing_acceleration(z, vz, az, z0, 1.0, close, open).unwrap();
            let v = vz + 0.5 * (close + open) * a;
            let next = z + open * v;
            assert!((next - z0).abs() < 1e-15, "{next} against {z0}");
            // It only pushes: the plane's acceleration is below the free one.
            assert!(a < az);
        }
        // Mirrored: the body above the plane.
        let a = landing_acceleration(-1e-3, -2.0, 0.0, -1e-3, -1.0, 1e-9, 1e-9).unwrap();
        let next = -1e-3 + 1e-9 * (-2.0 + 1e-9 * a);
        assert!((next + 1e-3).abs() < 1e-18 && a > 0.0);
    }

    /// The plane's state after a force evaluation at positions `x` (m).
    fn forces_state(plane: &mut KinematicPlane, x: &[[f64; 2]]) -> ContactState {
        let v = vec![[0.0; 2]; x.len()];
        let mass = vec![1.0; x.len()];
        let ctx = StepContext {
            t: 0.0,
            dt: 1e-8,
            x,
            v: &v,
            mass: &mass,
        };
        plane
            .add_forces(&ctx, &mut vec![[0.0; 2]; x.len()])
            .unwrap();
        plane.state()
    }

    #[test]
    fn the_plane_holds_only_its_boundary_nodes_and_reports_its_force() {
        use crate::mesh::section::{ball, SectionSpec};
        let mesh = ball(&SectionSpec {
            diameter: 0.02,
            size: 0.004,
            pole_size: Some(0.001),
        })
        .unwrap();
        let pole = mesh
            .nodes
            .iter()
            .position(|p| p[0] == 0.0 && p[1] > 0.0099)
            .unwrap();
        let centre = mesh
            .nodes
            .iter()
            .position(|p| p[0].hypot(p[1]) < 1e-9)
            .unwrap();
        let mut plane = KinematicPlane::new(&mesh, &mesh.boundary, 0.01, Side::Below).unwrap();
        assert!(plane.holds(pole) && !plane.holds(centre));
        let mut a = [0.0, 0.0];
        let kick = Kick {
            x: [0.0, 0.01],
            v_half: [0.0, 1.0],
            mass: 2e-6,
            close: 1e-8,
            open: 1e-8,
        };
        let work = plane.constrain(pole, kick, &mut a);
        // Stopping 1 m/s over one step: a = −v/Δt, force m v/Δt = 200 N.
        assert!((a[1] + 1e8).abs() < 1e-3);
        let s = forces_state(&mut plane, &mesh.nodes);
        assert!((s.normal_force - 200.0).abs() < 1e-9 && s.active_nodes == 1);
        // It took work: half of the step before at 1 m/s against 200 N.
        assert!((work + 200.0 * 0.5e-8).abs() < 1e-18);
        // Released when the free motion leaves the plane.
        let away = Kick {
            v_half: [0.0, -1.0],
            ..kick
        };
        assert_eq!(plane.constrain(pole, away, &mut [0.0, 0.0]), 0.0);
        let s = forces_state(&mut plane, &mesh.nodes);
        assert_eq!(s.normal_force, 0.0);
    }
}
