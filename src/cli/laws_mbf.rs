//! `twoball laws mbf`: Maw, Barber & Fawcett's elastic oblique impact curve (normalised
//! rebound against incidence angle) by the method of dimensionality reduction.

use super::analytic::{bodies, BodyArgs};
use crate::analytic::collision::pair_friction;
use crate::analytic::maw_barber_fawcett::{curve, CurvePoint, Resolution, DEFAULT_RESOLUTION};
use crate::error::{Error, Result};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `twoball laws mbf`.
#[derive(Debug, Args)]
pub struct MbfArgs {
    /// The two bodies (ball 2 at rest; `--wall rigid` for Maw, Barber & Fawcett's half-space).
    #[command(flatten)]
    pub bodies: BodyArgs,
    /// Normal approach speed, m/s.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub speed: f64,
    /// Friction coefficient of the pair (default: mean of the two materials' mu).
    #[arg(long, allow_negative_numbers = true)]
    pub mu: Option<f64>,
    /// Largest normalised incidence angle psi_1 = kappa v_t/(mu v_n).
    #[arg(long, default_value_t = 10.0, allow_negative_numbers = true)]
    pub psi_max: f64,
    /// Points of the curve, evenly spaced in psi_1 from psi_max/points to psi_max.
    #[arg(long, default_value_t = 20)]
    pub points: usize,
    /// Springs on the half-line of the method of dimensionality reduction.
    #[arg(long, default_value_t = DEFAULT_RESOLUTION.springs)]
    pub springs: usize,
    /// Time steps per Hertz contact duration.
    #[arg(long, default_value_t = DEFAULT_RESOLUTION.steps)]
    pub steps: usize,
    /// Also write the curve to this CSV file.
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
}

/// The CSV header: one column a quantity, units in brackets.
const HEADER: &str = "psi_in [-],psi_out [-],slip_before [m/s],slip_after [m/s],\
tangential_restitution [-],e [-],impulse_ratio_over_mu [-],gross_slip_fraction [-],\
v1n_after [m/s],v1t_after [m/s],spin1_after [rad/s],contact_duration [s]";

/// One CSV row of `p` (friction coefficient `mu`).
fn row(p: &CurvePoint, mu: f64) -> String {
    let i = &p.impact;
    let cols = [
        p.psi_in,
        p.psi_out,
        i.slip_before,
        i.slip_after,
        i.tangential_restitution().unwrap_or(0.0),
        i.e,
        i.impulse_ratio(mu),
        i.gross_slip_fraction,
        i.v1_after[0],
        i.v1_after[1],
        i.spin_after[0],
        i.contact_duration,
    ];
    cols.map(|c| format!("{c:.9e}")).join(",")
}

/// `twoball laws mbf`.
pub fn run(a: MbfArgs) -> Result<()> {
    let (b1, b2) = bodies(&a.bodies)?;
    let mu = a.mu.unwrap_or_else(|| pair_friction(&b1, &b2));
    if !(a.psi_max > 0.0 && a.psi_max.is_finite()) {
        return Err(Error::invalid("--psi-max", a.psi_max, "a finite angle > 0"));
    }
    if !(1..=1000).contains(&a.points) {
        return Err(Error::invalid("--points", a.points, "1 to 1000"));
    }
    let psi: Vec<f64> = (1..=a.points)
        .map(|k| a.psi_max * k as f64 / a.points as f64)
        .collect();
    let res = Resolution {
        springs: a.springs,
        steps: a.steps,
    };
    let points = curve(&b1, &b2, a.speed, mu, &psi, res)?;
    println!(
        "Maw, Barber & Fawcett elastic oblique impact (method of dimensionality reduction, \
         {} springs, {} steps per contact time), mu = {mu}, normal speed {} m/s",
        res.springs, res.steps, a.speed
    );
    println!(
        "{:>9} {:>10} {:>10} {:>12} {:>10}",
        "psi_in", "psi_out", "e_t", "J_t/(mu J_n)", "gross slip"
    );
    for p in &points {
        println!(
            "{:>9.4} {:>10.5} {:>10.5} {:>12.6} {:>10.3}",
            p.psi_in,
            p.psi_out,
            p.impact.tangential_restitution().unwrap_or(0.0),
            p.impact.impulse_ratio(mu),
            p.impact.gross_slip_fraction
        );
    }
    if let Some(path) = &a.out {
        let mut text = String::from(HEADER);
        text.push('\n');
        for p in &points {
            text += &row(p, mu);
            text.push('\n');
        }
        crate::atomic::write_atomic(path, text.as_bytes())?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
