//! Contact-history curves of the analytical model and of the contact-law integrator as CSV
//! files (SI units in the header).

use crate::analytic::history::history;
use crate::analytic::impact::LawImpact;
use crate::analytic::Collision;
use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use std::path::Path;

/// Writes the analytical contact history of `c` at `samples` instants from first touch to
/// separation to `path` as CSV (`t_s,delta_m,delta_dot_m_per_s,force_N`; header only
/// without impact), atomically.
///
/// Errors: `samples` < 2 ([`Error::Invalid`] naming `--samples`); a non-finite value
/// ([`Error::Numerical`]); a failed write.
pub fn write_analytic_curve(c: &Collision, path: &Path, samples: usize) -> Result<()> {
    if samples < 2 {
        return Err(Error::invalid("--samples", samples, ">= 2"));
    }
    let mut s = String::from("t_s,delta_m,delta_dot_m_per_s,force_N\n");
    if let Some(n) = &c.normal {
        for p in history(n, samples) {
            for v in [p.t, p.delta, p.delta_dot, p.force] {
                if !v.is_finite() {
                    return Err(Error::Numerical(format!(
                        "contact history: {v} at t = {}",
                        p.t
                    )));
                }
            }
            s.push_str(&format!(
                "{:.9e},{:.9e},{:.9e},{:.9e}\n",
                p.t, p.delta, p.delta_dot, p.force
            ));
        }
    }
    write_atomic(path, s.as_bytes())
}

/// Writes the contact history of a law's impact `i` to `path` as CSV (`t_s,delta_m,
/// delta_dot_m_per_s,force_N,tangential_force_N,slip_speed_m_per_s`), atomically.
///
/// Errors: a non-finite value ([`Error::Numerical`]); a failed write.
pub fn write_law_curve(i: &LawImpact, path: &Path) -> Result<()> {
    let mut s = String::from(
        "t_s,delta_m,delta_dot_m_per_s,force_N,tangential_force_N,slip_speed_m_per_s\n",
    );
    for p in &i.history {
        let row = [p.t, p.delta, p.rate, p.force, p.tangential_force, p.slip];
        if let Some(v) = row.iter().find(|v| !v.is_finite()) {
            return Err(Error::Numerical(format!(
                "contact history: {v} at t = {}",
                p.t
            )));
        }
        let cells: Vec<String> = row.iter().map(|v| format!("{v:.9e}")).collect();
        s.push_str(&cells.join(","));
        s.push('\n');
    }
    write_atomic(path, s.as_bytes())
}
