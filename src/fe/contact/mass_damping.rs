//! Dynamic relaxation: mass-proportional viscous damping f_i = −α m_i v_i, as an interaction,
//! so the explicit loop settles to the static solution of a slowly applied load (the static
//! Hertz check). The loop then needs no stiffness matrix, and contact, friction and the
//! element kernels are exactly the ones of the impact runs.

use crate::error::{Error, Result};
use crate::fe::interaction::{Interaction, InteractionEnergy, StepContext};

/// Mass-proportional damping of a range of nodes.
#[derive(Debug, Clone)]
pub struct MassDamping {
    /// Damping rate α, 1/s (critical for a mode of angular frequency ω at α = 2ω).
    alpha: f64,
    nodes: std::ops::Range<usize>,
    prev: Vec<[f64; 3]>,
    dt_prev: f64,
    energy: InteractionEnergy,
}

impl MassDamping {
    /// Damping at rate `alpha` (1/s, ≥ 0, finite) on the nodes `nodes`.
    pub fn new(alpha: f64, nodes: std::ops::Range<usize>) -> Result<Self> {
        if !(alpha.is_finite() && alpha >= 0.0) {
            return Err(Error::invalid(
                "relaxation.alpha",
                alpha,
                "alpha >= 0 1/s, finite",
            ));
        }
        let n = nodes.len();
        Ok(MassDamping {
            alpha,
            nodes,
            prev: vec![[0.0; 3]; n],
            dt_prev: 0.0,
            energy: InteractionEnergy::default(),
        })
    }
}

impl Interaction for MassDamping {
    fn name(&self) -> &str {
        "mass damping"
    }

    fn add_forces(&mut self, ctx: &StepContext<'_>, f: &mut [[f64; 3]]) -> Result<()> {
        for (k, n) in self.nodes.clone().enumerate() {
            let v = ctx.v[n];
            let c = -self.alpha * ctx.mass[n];
            let fnew = [c * v[0], c * v[1], c * v[2]];
            let fp = self.prev[k];
            let w = 0.5
                * ((fp[0] + fnew[0]) * v[0] + (fp[1] + fnew[1]) * v[1] + (fp[2] + fnew[2]) * v[2])
                * self.dt_prev;
            self.energy.work += w;
            self.energy.dissipated -= w;
            for a in 0..3 {
                f[n][a] += fnew[a];
            }
            self.prev[k] = fnew;
        }
        self.dt_prev = ctx.dt;
        Ok(())
    }

    /// A dashpot on a lumped mass is stable for α Δt < 2; the limit is 1/α.
    fn stable_time_step(&self, _mass: &[f64], _omega: &[f64]) -> Option<f64> {
        (self.alpha > 0.0).then(|| 1.0 / self.alpha)
    }

    fn energy(&self) -> InteractionEnergy {
        self.energy
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn damped_free_particle_decays_exponentially() {
        // m v' = −α m v: v(t) = v0 e^{−α t}; dissipation = ½ m (v0² − v²).
        let mut d = MassDamping::new(100.0, 0..1).unwrap();
        let (m, dt) = ([2.0], 1e-4);
        let (mut x, mut v) = ([[0.0; 3]], [[1.0, 0.0, 0.0]]);
        for _ in 0..1000 {
            let mut f = [[0.0; 3]];
            d.add_forces(
                &StepContext {
                    t: 0.0,
                    dt,
                    x: &x,
                    v: &v,
                    mass: &m,
                },
                &mut f,
            )
            .unwrap();
            v[0][0] += dt * f[0][0] / m[0];
            x[0][0] += dt * v[0][0];
        }
        let exact = (-100.0f64 * 0.1).exp();
        assert!(
            (v[0][0] - exact).abs() < 0.01 * exact.max(1e-3) + 1e-4,
            "{} vs {exact}",
            v[0][0]
        );
        let lost = 0.5 * m[0] * (1.0 - v[0][0] * v[0][0]);
        assert!((d.energy().dissipated - lost).abs() < 0.02 * lost);
        assert!(MassDamping::new(-1.0, 0..1).is_err());
    }
}
