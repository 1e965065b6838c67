//! Mass scaling of the section's ring quads: their Courant steps and ring masses, given to
//! the one mechanism both models use ([`crate::fe::mass_scaling`], where the method and why
//! it is sound are).

use crate::error::{Error, Result};
use crate::fe::elements::ring::mass::element_masses;
use crate::fe::elements::ring::shape::characteristic_length;
use crate::fe::mass_scaling::for_elements;
pub use crate::fe::mass_scaling::{check_budget, MassScaling, MAX_BUDGET};

/// Courant step (s) and ring mass (kg) of each quad of `nodes` (r, z in m) and `quads`, with
/// `wave_speed` and `rho` (m/s, kg/m³) the quad's material's.
fn steps_and_masses(
    nodes: &[[f64; 2]],
    quads: &[[u32; 4]],
    wave_speed: impl Fn(usize) -> f64,
    rho: impl Fn(usize) -> f64,
) -> Vec<(f64, f64)> {
    quads
        .iter()
        .enumerate()
        .map(|(e, q)| {
            let x = q.map(|i| nodes[i as usize]);
            let m: f64 = element_masses(&x, rho(e)).iter().sum();
            (characteristic_length(&x) / wave_speed(e), m)
        })
        .collect()
}

/// The density factors that raise the smallest quads of the section (`nodes` in m, `quads`
/// counter-clockwise, each quad's material's P-wave speed `wave_speed(e)` in m/s and density
/// `rho(e)` in kg/m³) to the largest common target step whose added mass is at most `budget`
/// times the section's mass. A budget of 0 returns factors of 1.
///
/// Errors: a budget outside [0, [`MAX_BUDGET`]]; an empty mesh or a quad with a non-positive
/// or non-finite step or mass.
pub fn within_budget(
    nodes: &[[f64; 2]],
    quads: &[[u32; 4]],
    wave_speed: impl Fn(usize) -> f64,
    rho: impl Fn(usize) -> f64,
    budget: f64,
) -> Result<MassScaling> {
    check_budget(budget)?;
    if quads.is_empty() {
        return Err(Error::invalid("mesh.quads", 0, "at least one quad"));
    }
    let sm = steps_and_masses(nodes, quads, wave_speed, rho);
    for_elements(&sm, budget, "mesh.quads")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of `n` unit-depth quads along r ∈ [1, 2], of heights h_k = 2^{-k} m.
    fn strip(n: usize) -> (Vec<[f64; 2]>, Vec<[u32; 4]>) {
        let mut nodes = vec![[1.0, 0.0], [2.0, 0.0]];
        let mut quads = Vec::new();
        let mut z = 0.0;
        for k in 0..n {
            z += 0.5f64.powi(k as i32);
            let b = nodes.len() as u32;
            nodes.push([1.0, z]);
            nodes.push([2.0, z]);
            quads.push([b - 2, b - 1, b + 1, b]);
        }
        (nodes, quads)
    }

    #[test]
    fn a_zero_budget_scales_nothing() {
        let (nodes, quads) = strip(4);
        let s = within_budget(&nodes, &quads, |_| 1.0, |_| 1.0, 0.0).unwrap();
        assert!(s.scale.iter().all(|&f| f == 1.0));
        assert_eq!(s.added_fraction, 0.0);
        assert!((s.target_step - s.unscaled_step).abs() <= 1e-12 * s.unscaled_step);
    }

    #[test]
    fn the_added_mass_meets_the_budget_and_no_scaled_step_is_below_the_target() {
        let (nodes, quads) = strip(6);
        let budget = 5e-3;
        let s = within_budget(&nodes, &quads, |_| 3.0, |_| 2.0, budget).unwrap();
        assert!((s.added_fraction - budget).abs() < 1e-9 * budget, "{s:?}");
        let sm = steps_and_masses(&nodes, &quads, |_| 3.0, |_| 2.0);
        for (&(dt, _), &f) in sm.iter().zip(&s.scale) {
            assert!(dt * f.sqrt() >= s.target_step * (1.0 - 1e-12));
            if f > 1.0 {
                assert!((dt * f.sqrt() / s.target_step - 1.0).abs() < 1e-12);
            }
        }
        // The thinnest quad is scaled the most, the thickest not at all.
        assert!(s.scale[5] > s.scale[4] && s.scale[0] == 1.0);
        assert!(s.target_step > s.unscaled_step);
    }

    #[test]
    fn a_budget_too_small_for_the_thin_quad_leaves_the_target_between_the_steps() {
        // Two quads of heights 1 and 1/2: raising the thin one to the thick one's step costs
        // three of its masses, all of the strip's, far above 1 %.
        let (nodes, quads) = strip(2);
        let s = within_budget(&nodes, &quads, |_| 1.0, |_| 1.0, MAX_BUDGET).unwrap();
        let sm = steps_and_masses(&nodes, &quads, |_| 1.0, |_| 1.0);
        assert!(s.target_step > sm[1].0 && s.target_step < sm[0].0, "{s:?}");
        assert!((s.added_fraction / MAX_BUDGET - 1.0).abs() < 1e-9, "{s:?}");
        assert_eq!(s.scale[0], 1.0);
    }

    #[test]
    fn a_budget_that_covers_every_quad_stops_at_the_largest_step() {
        // 200 unit squares and one of height 1/2 on top: raising the thin one costs three
        // of its half masses, 0.75 % of the strip, within a budget of 1 %.
        let mut nodes = Vec::new();
        for k in 0..=200 {
            nodes.push([1.0, k as f64]);
            nodes.push([2.0, k as f64]);
        }
        nodes.push([1.0, 200.5]);
        nodes.push([2.0, 200.5]);
        let quads: Vec<[u32; 4]> = (0..201u32)
            .map(|k| [2 * k, 2 * k + 1, 2 * k + 3, 2 * k + 2])
            .collect();
        let s = within_budget(&nodes, &quads, |_| 1.0, |_| 1.0, MAX_BUDGET).unwrap();
        assert_eq!(s.target_step, 1.0);
        assert!((s.scale[200] - 4.0).abs() < 1e-12 && s.scale[..200].iter().all(|&f| f == 1.0));
        assert!(s.added_fraction < MAX_BUDGET && s.added_fraction > 0.5 * MAX_BUDGET);
    }

    #[test]
    fn a_bad_budget_is_one_line_naming_the_field() {
        let (nodes, quads) = strip(2);
        for b in [-1e-3, 0.5, f64::NAN] {
            let e = within_budget(&nodes, &quads, |_| 1.0, |_| 1.0, b)
                .unwrap_err()
                .to_string();
            assert!(e.contains("mass_scaling") && !e.contains('\n'), "{e}");
        }
    }
}
