//! The explicit time step written once: Box 6.1 of Belytschko, Liu & Moran (2014), steps
//! 4-12, as a sequence of phases that every explicit model (the 3D hexahedra, the section's
//! ring quads) implements. The model decides how each phase runs (single rate or subcycled,
//! its own nodal storage); the order of the phases, and so the central-difference scheme, is
//! this file's.

use crate::error::Result;

/// The phases of one central-difference step of an explicit model. `Carry` is what one
/// phase hands to the next within the step (powers, work sums, the next stable step).
pub(crate) trait CentralDifference {
    /// What the phases of one step hand on to each other.
    type Carry;

    /// Step 4, time update: the step Δt^{n+1/2} (s) this step takes.
    fn time_update(&mut self) -> f64;

    /// Steps 5-7: first partial velocity update v^{n+1/2} = v^n + (t^{n+1/2} − t^n) a^n,
    /// velocity boundary conditions, displacement update x^{n+1} = x^n + Δt v^{n+1/2}, time
    /// t^{n+1}.
    fn first_partial_update(&mut self, dt: f64) -> Self::Carry;

    /// Step 8, getforce: internal and contact forces at x^{n+1}, the next stable step.
    fn get_forces(&mut self, dt: f64, carry: Self::Carry) -> Result<Self::Carry>;

    /// Steps 9-10: accelerations a^{n+1} = M⁻¹(f_ext − f_int), second partial velocity
    /// update v^{n+1} = v^{n+1/2} + (t^{n+1} − t^{n+1/2}) a^{n+1}, velocity boundary
    /// conditions.
    fn second_partial_update(&mut self, dt: f64, carry: Self::Carry) -> Result<Self::Carry>;

    /// Steps 11-12: the work of the step, the energy balance, the step count.
    fn energy_balance(&mut self, dt: f64, carry: Self::Carry) -> Result<()>;
}

/// One time step n → n+1 of `model` (Box 6.1 steps 4-12). Fails as the model's phases fail
/// (an inverted element, a non-finite force, energy created, no stable step).
#[inline]
pub(crate) fn step<M: CentralDifference>(model: &mut M) -> Result<()> {
    let dt = model.time_update();
    let carry = model.first_partial_update(dt);
    let carry = model.get_forces(dt, carry)?;
    let carry = model.second_partial_update(dt, carry)?;
    model.energy_balance(dt, carry)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mass on a spring, m ẍ = −k x, with the phases of a model.
    struct Oscillator {
        x: f64,
        v: f64,
        a: f64,
        omega2: f64,
        dt: f64,
        energy: Vec<f64>,
    }

    impl CentralDifference for Oscillator {
        type Carry = ();
        fn time_update(&mut self) -> f64 {
            self.dt
        }
        fn first_partial_update(&mut self, dt: f64) {
            self.v += 0.5 * dt * self.a;
            self.x += dt * self.v;
        }
        fn get_forces(&mut self, _dt: f64, _: ()) -> Result<()> {
            self.a = -self.omega2 * self.x;
            Ok(())
        }
        fn second_partial_update(&mut self, dt: f64, _: ()) -> Result<()> {
            self.v += 0.5 * dt * self.a;
            Ok(())
        }
        fn energy_balance(&mut self, _dt: f64, _: ()) -> Result<()> {
            self.energy
                .push(0.5 * self.v * self.v + 0.5 * self.omega2 * self.x * self.x);
            Ok(())
        }
    }

    #[test]
    fn the_step_is_the_central_difference_of_an_oscillator() {
        // x_n = cos(n θ) with cos θ = 1 − (ω Δt)²/2: the exact discrete solution of the
        // central difference x_{n+1} − 2 x_n + x_{n−1} = −(ω Δt)² x_n from x_0 = 1, v_0 = 0.
        let (omega, dt) = (2.0, 0.3);
        let mut m = Oscillator {
            x: 1.0,
            v: 0.0,
            a: -omega * omega,
            omega2: omega * omega,
            dt,
            energy: Vec::new(),
        };
        let theta = (1.0 - 0.5 * (omega * dt).powi(2)).acos();
        for n in 1..=50 {
            step(&mut m).unwrap();
            let exact = (f64::from(n) * theta).cos();
            assert!(
                (m.x - exact).abs() < 1e-12,
                "step {n}: {} against {exact}",
                m.x
            );
        }
        // The energy of full-step velocities oscillates about its start by O((ω Δt)²) and
        // does not drift.
        let (lo, hi) = m
            .energy
            .iter()
            .fold((f64::MAX, 0.0_f64), |(l, h), &e| (l.min(e), h.max(e)));
        assert!(lo > 0.9 * 2.0 && hi < 1.1 * 2.0, "{lo} {hi}");
    }
}
