//! What a contact pair reports each step: force resultants, contact area and patch radius,
//! penetration and energies.

use crate::fe::tensor::{add, dot, norm, scale, sub, tangential};

/// One step's contact state. Forces are those acting on the first body of the pair (the
/// deformable body for a rigid plane), N.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactOutput {
    /// Time t^n of the evaluation, s.
    pub time: f64,
    /// Sum of the normal nodal contact forces on the first body, N.
    pub normal_resultant: [f64; 3],
    /// Sum of the tangential (friction) nodal forces on the first body, N.
    pub tangential_resultant: [f64; 3],
    /// Sum of the normal force magnitudes over all contact nodes, N (≥ 0).
    pub normal_force: f64,
    /// Magnitude of the tangential resultant, N.
    pub tangential_force: f64,
    /// Area of the nodes in contact (tributary areas, pass-weighted), m².
    pub area: f64,
    /// Largest in-plane distance of a contact node from the force centre, m.
    pub patch_radius: f64,
    /// Largest penetration over the contact nodes, m (≥ 0).
    pub max_penetration: f64,
    /// Number of node–segment contacts this step.
    pub active_nodes: usize,
    /// How many of them slid (friction on the cone) this step.
    pub sliding_nodes: usize,
    /// Energy stored in penalty and stick springs now, J.
    pub stored_energy: f64,
    /// Energy dissipated so far by friction and contact damping, J.
    pub dissipated_energy: f64,
    /// The friction part of `dissipated_energy`, J.
    pub friction_energy: f64,
}

/// The contact pressure at one node in contact.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PressureSample {
    /// Node number (global).
    pub node: u32,
    /// Current position of the node, m.
    pub position: [f64; 3],
    /// Outward normal of the opposing surface at the node's projection.
    pub normal: [f64; 3],
    /// Normal pressure: normal nodal force over its weighted tributary area, Pa.
    pub pressure: f64,
    /// Weighted tributary area of the node, m².
    pub area: f64,
}

/// One node in contact, as the output sees it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NodeContact {
    /// Normal force magnitude, N.
    pub normal: f64,
    /// Tangential force on the node, N.
    pub tangential: [f64; 3],
    /// Penetration, m (≥ 0).
    pub penetration: f64,
    /// Whether the node slid this step.
    pub sliding: bool,
}

/// Accumulates a step's output from node contacts.
#[derive(Debug, Clone, Default)]
pub struct OutputBuilder {
    out: ContactOutput,
    samples: Vec<PressureSample>,
    weighted_position: [f64; 3],
}

impl OutputBuilder {
    /// Starts the output of time `t` (s).
    pub fn new(t: f64) -> Self {
        OutputBuilder {
            out: ContactOutput {
                time: t,
                ..Default::default()
            },
            ..Default::default()
        }
    }

    /// Adds one node contact: `sign` = +1 when the node is on the first body, −1 when it is on
    /// the second (its reaction acts on the first body).
    pub fn add(&mut self, sign: f64, s: PressureSample, c: NodeContact) {
        let NodeContact {
            normal,
            tangential: tangential_force,
            penetration,
            sliding,
        } = c;
        self.out.sliding_nodes += usize::from(sliding);
        self.out.normal_resultant = add(self.out.normal_resultant, scale(sign * normal, s.normal));
        self.out.tangential_resultant =
            add(self.out.tangential_resultant, scale(sign, tangential_force));
        self.out.normal_force += normal;
        self.out.area += s.area;
        self.out.max_penetration = self.out.max_penetration.max(penetration);
        self.out.active_nodes += 1;
        self.weighted_position = add(self.weighted_position, scale(normal, s.position));
        self.samples.push(s);
    }

    /// Finishes the step with the pair's energies (J).
    pub fn finish(
        mut self,
        stored: f64,
        dissipated: f64,
        friction: f64,
    ) -> (ContactOutput, Vec<PressureSample>) {
        let o = &mut self.out;
        o.friction_energy = friction;
        o.tangential_force = norm(o.tangential_resultant);
        o.stored_energy = stored;
        o.dissipated_energy = dissipated;
        if o.normal_force > 0.0 {
            let centre = scale(1.0 / o.normal_force, self.weighted_position);
            let nr = norm(o.normal_resultant);
            let axis = if nr > 0.0 {
                scale(1.0 / nr, o.normal_resultant)
            } else {
                [0.0; 3]
            };
            o.patch_radius = self
                .samples
                .iter()
                .map(|s| {
                    let d = sub(s.position, centre);
                    if nr > 0.0 {
                        norm(tangential(d, axis))
                    } else {
                        dot(d, d).sqrt()
                    }
                })
                .fold(0.0, f64::max);
        }
        (self.out, self.samples)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resultants_area_and_radius_of_a_symmetric_patch() {
        let mut b = OutputBuilder::new(1.0);
        let n = [0.0, 0.0, 1.0];
        for (x, y) in [
            (0.0, 0.0),
            (1e-3, 0.0),
            (-1e-3, 0.0),
            (0.0, 1e-3),
            (0.0, -1e-3),
        ] {
            let s = PressureSample {
                node: 0,
                position: [x, y, 0.0],
                normal: n,
                pressure: 1.0,
                area: 1e-6,
            };
            b.add(
                1.0,
                s,
                NodeContact {
                    normal: 2.0,
                    tangential: [0.1, 0.0, 0.0],
                    penetration: 1e-7,
                    sliding: x > 0.0,
                },
            );
        }
        let (o, samples) = b.finish(3.0, 4.0, 1.0);
        assert_eq!(samples.len(), 5);
        assert!((o.normal_resultant[2] - 10.0).abs() < 1e-12);
        assert!((o.tangential_force - 0.5).abs() < 1e-12);
        assert!((o.area - 5e-6).abs() < 1e-18);
        assert!((o.patch_radius - 1e-3).abs() < 1e-15);
        assert_eq!(
            (o.stored_energy, o.dissipated_energy, o.active_nodes),
            (3.0, 4.0, 5)
        );
    }
}

/// What a [`ContactProbe`] holds: the last step's output and, when asked for, its pressures.
#[derive(Debug, Clone, Default)]
pub struct ProbeData {
    /// Output of the last evaluated step.
    pub last: ContactOutput,
    /// Pressure samples of the last step (filled only when the probe records pressures).
    pub pressures: Vec<PressureSample>,
    /// Largest normal force (sum of magnitudes) seen so far, N.
    pub peak_normal_force: f64,
    /// Largest penetration seen so far, m.
    pub peak_penetration: f64,
    /// Time of the first step with contact, s (`None` before contact).
    pub first_contact: Option<f64>,
    /// Time of the last step with contact, s.
    pub last_contact: Option<f64>,
    /// Whether pressure samples are copied each step.
    pub record_pressures: bool,
    /// The normal-force pulse: (time in s, normal force in N) of every step with a force.
    pub pulse: Vec<(f64, f64)>,
}

impl ProbeData {
    /// Contact duration, s: from the force pulse ([`super::duration::pulse_duration`]), or
    /// first to last step with contact when the pulse is too short to fit; 0 without
    /// contact.
    pub fn contact_duration(&self) -> f64 {
        super::duration::pulse_duration(&self.pulse).unwrap_or(
            match (self.first_contact, self.last_contact) {
                (Some(a), Some(b)) => b - a,
                _ => 0.0,
            },
        )
    }
}

/// A shared read handle on a contact pair's output, for callers that hand the pair to the
/// solver as a `Box<dyn Interaction>` and still want its forces, area and pressures.
#[derive(Debug, Clone, Default)]
pub struct ContactProbe(std::sync::Arc<std::sync::Mutex<ProbeData>>);

impl ContactProbe {
    /// Whether any step so far had contact (cheaper than [`ContactProbe::get`]).
    pub fn touched(&self) -> bool {
        self.0
            .lock()
            .map(|d| d.first_contact.is_some())
            .unwrap_or(false)
    }

    /// Times (s) of the first and last steps with contact so far, without copying the
    /// recorded pulse as [`ContactProbe::get`] does (for per-step checks).
    pub fn contact_span(&self) -> (Option<f64>, Option<f64>) {
        self.0
            .lock()
            .map(|d| (d.first_contact, d.last_contact))
            .unwrap_or((None, None))
    }

    /// A copy of the current data.
    pub fn get(&self) -> ProbeData {
        self.0.lock().map(|d| d.clone()).unwrap_or_default()
    }

    /// The last step's output.
    pub fn last(&self) -> ContactOutput {
        self.0.lock().map(|d| d.last).unwrap_or_default()
    }

    /// Asks for the pressure samples to be copied every step (off by default: it allocates).
    pub fn record_pressures(&self, on: bool) {
        if let Ok(mut d) = self.0.lock() {
            d.record_pressures = on;
        }
    }

    /// Records one step (called by the contact pairs).
    pub fn update(&self, out: &ContactOutput, samples: &[PressureSample]) {
        if let Ok(mut d) = self.0.lock() {
            d.last = *out;
            if d.record_pressures {
                d.pressures = samples.to_vec();
            }
            d.peak_normal_force = d.peak_normal_force.max(out.normal_force);
            d.peak_penetration = d.peak_penetration.max(out.max_penetration);
            if out.active_nodes > 0 {
                d.first_contact.get_or_insert(out.time);
                d.last_contact = Some(out.time);
            }
            if out.normal_force > 0.0 {
                d.pulse.push((out.time, out.normal_force));
            }
        }
    }
}
