//! The rigid frictionless plane of the static solver, z = `z` with the body on one side,
//! enforced exactly: a node on the plane (in the active set) has its axial position
//! prescribed there, and its reaction is the contact force; the active set is settled by
//! adding nodes that cross the plane and releasing nodes the plane pulls.

/// A rigid frictionless plane normal to the axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactPlane {
    /// Axial position of the plane, m.
    pub z: f64,
    /// +1 when the body lies above the plane (z > `z`), −1 below.
    pub side: f64,
}

impl ExactPlane {
    /// The gap of a node at axial position `z_node` (m): positive apart, negative across.
    pub fn gap(&self, z_node: f64) -> f64 {
        self.side * (z_node - self.z)
    }

    /// The normal contact force (N, ≥ 0 when pressing) of an axial nodal force `f_z` (N)
    /// exerted by the plane on the body.
    pub fn pressure_of(&self, f_z: f64) -> f64 {
        self.side * f_z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gap_and_pressure_follow_the_side() {
        let below = ExactPlane { z: 1.0, side: 1.0 };
        assert_eq!(below.gap(1.5), 0.5);
        assert_eq!(below.pressure_of(2.0), 2.0);
        let above = ExactPlane { z: 1.0, side: -1.0 };
        assert_eq!(above.gap(1.5), -0.5);
        assert_eq!(above.pressure_of(2.0), -2.0);
    }
}
