//! The frame: a single-degree-of-freedom oscillator that carries the box horizontally.

use crate::error::{Error, Result};
use std::f64::consts::PI;

/// M x'' + c x' + k x = F: modal mass M (kg), stiffness k (N/m), viscous damping c (N·s/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Mass M moving with the top beam (box included), kg.
    pub mass: f64,
    /// Stiffness k, N/m.
    pub stiffness: f64,
    /// Viscous (structural) damping c, N·s/m.
    pub damping: f64,
}

impl Frame {
    /// The frame whose empty free decay has damped frequency `frequency` (Hz) and damping
    /// ratio `ratio` (-), as a free-decay test measures them: ω_n = 2πf/√(1 − ζ²),
    /// k = M ω_n², c = 2ζ M ω_n. Errors name the field: M > 0 kg, f > 0 Hz, 0 ≤ ζ < 1.
    pub fn from_free_decay(mass: f64, frequency: f64, ratio: f64) -> Result<Frame> {
        if !(mass.is_finite() && mass > 0.0) {
            return Err(Error::invalid("frame.mass", mass, "mass > 0 kg, finite"));
        }
        if !(frequency.is_finite() && frequency > 0.0) {
            return Err(Error::invalid(
                "frame.frequency",
                frequency,
                "frequency > 0 Hz, finite",
            ));
        }
        if !(ratio.is_finite() && (0.0..1.0).contains(&ratio)) {
            return Err(Error::invalid(
                "frame.damping_ratio",
                ratio,
                "0 <= damping_ratio < 1 (a fraction, not per cent)",
            ));
        }
        let omega = 2.0 * PI * frequency / (1.0 - ratio * ratio).sqrt();
        Ok(Frame {
            mass,
            stiffness: mass * omega * omega,
            damping: 2.0 * ratio * mass * omega,
        })
    }

    /// Undamped natural circular frequency ω_n = √(k/M), rad/s.
    pub fn natural_frequency(&self) -> f64 {
        (self.stiffness / self.mass).sqrt()
    }

    /// Spring force −k x (N) at displacement x (m).
    pub fn spring_force(&self, x: f64) -> f64 {
        -self.stiffness * x
    }

    /// Damper force −c v (N) at velocity v (m/s).
    pub fn damper_force(&self, v: f64) -> f64 {
        -self.damping * v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn damped_frequency_and_ratio_round_trip() {
        let f = Frame::from_free_decay(5.76, 1.69, 0.0045).unwrap();
        let wn = f.natural_frequency();
        let zeta = f.damping / (2.0 * f.mass * wn);
        let fd = wn * (1.0 - zeta * zeta).sqrt() / (2.0 * PI);
        assert!((zeta - 0.0045).abs() < 1e-15);
        assert!((fd - 1.69).abs() < 1e-13);
    }

    #[test]
    fn bad_values_name_the_field() {
        let e = Frame::from_free_decay(-1.0, 1.69, 0.0045).unwrap_err();
        assert!(e.to_string().contains("frame.mass = -1"), "{e}");
        let e = Frame::from_free_decay(1.0, 1.69, 1.2).unwrap_err();
        assert!(e.to_string().contains("frame.damping_ratio"), "{e}");
    }
}
