//! Reading the trace a deck writes (`trace.txt`: t [s], x1 [m], x2 [m], vx1 [m/s], vx2 [m/s],
//! fx1 [N] per line; `#` lines ignored) into the collision's e, δ_max and contact duration.

use crate::error::{Error, Result};

/// What a DEM code made of the collision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DemOutcome {
    /// Coefficient of restitution (vx2 − vx1)/v_r at the last line.
    pub e: f64,
    /// Largest overlap D − (x2 − x1), m.
    pub delta_max: f64,
    /// Contact duration, s: from the first overlap (interpolated to zero overlap) to the end
    /// of contact (see [`read`]).
    pub contact_duration: f64,
}

/// The outcome of `text` for balls of diameter `d` (m) approaching at `speed` (m/s).
/// `tensile`: the contact ends where the overlap returns to 0 (a law whose force may pull);
/// otherwise where the contact force −fx1 first reaches 0 after the largest overlap, linearly
/// extrapolated from the two lines before when the code clipped it to 0 at a line.
///
/// Errors: a line that is not six numbers, fewer than three lines, no overlap, or a contact
/// that has not ended by the last line: the balls still overlap and (a law that may pull)
/// or the force has not stayed at zero since the end (`source` names the file).
pub fn read(text: &str, source: &str, d: f64, speed: f64, tensile: bool) -> Result<DemOutcome> {
    let mut rows: Vec<[f64; 6]> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let l = line.trim();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        let v: Vec<f64> = l
            .split_whitespace()
            .map(|x| x.parse::<f64>())
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| Error::Parse(format!("{source}:{}: not six numbers: {l}", i + 1)))?;
        let row: [f64; 6] = v
            .try_into()
            .map_err(|_| Error::Parse(format!("{source}:{}: not six numbers: {l}", i + 1)))?;
        rows.push(row);
    }
    if rows.len() < 3 {
        return Err(Error::Parse(format!(
            "{source}: fewer than three trace lines"
        )));
    }
    let overlap = |r: &[f64; 6]| d - (r[2] - r[1]);
    let force = |r: &[f64; 6]| -r[5];
    let (imax, dmax) = rows
        .iter()
        .enumerate()
        .map(|(i, r)| (i, overlap(r)))
        .fold((0, f64::MIN), |a, b| if b.1 > a.1 { b } else { a });
    if dmax <= 0.0 {
        return Err(Error::Parse(format!("{source}: the balls never overlap")));
    }
    // Start: the last line before the largest overlap without overlap, interpolated.
    let start = match (0..imax).rev().find(|&i| overlap(&rows[i]) <= 0.0) {
        Some(i) => cross(&rows[i], &rows[i + 1], overlap),
        None => {
            // The balls touch at the first line's time minus its overlap over the speed.
            rows[0][0] - overlap(&rows[0]) / speed
        }
    };
    let end = if tensile {
        let j = (imax..rows.len())
            .find(|&i| overlap(&rows[i]) <= 0.0)
            .ok_or_else(|| unfinished(source))?;
        cross(&rows[j - 1], &rows[j], overlap)
    } else {
        let j = (imax..rows.len())
            .find(|&i| force(&rows[i]) <= 0.0)
            .ok_or_else(|| unfinished(source))?;
        if overlap(&rows[j]) <= 0.0 && overlap(&rows[j - 1]) > 0.0 {
            // The force ends with the overlap (an elastic law): the overlap crosses exactly.
            cross(&rows[j - 1], &rows[j], overlap)
        } else if force(&rows[j]) == 0.0 && j >= 2 && force(&rows[j - 2]) > force(&rows[j - 1]) {
            // Clipped at 0: extend the last two unclipped forces to zero.
            let (a, b) = (&rows[j - 2], &rows[j - 1]);
            let t = b[0] + force(b) * (b[0] - a[0]) / (force(a) - force(b));
            t.min(rows[j][0])
        } else {
            cross(&rows[j - 1], &rows[j], force)
        }
    };
    let last = rows[rows.len() - 1];
    // The velocities are final once the balls are apart, or (a law whose force is clipped)
    // once the force has stayed at zero since the contact ended.
    let after = rows.iter().filter(|r| r[0] > end);
    let quiet = !tensile && after.clone().count() > 0 && after.clone().all(|r| force(r) <= 0.0);
    if overlap(&last) > 0.0 && !quiet {
        return Err(unfinished(source));
    }
    Ok(DemOutcome {
        e: (last[4] - last[3]) / speed,
        delta_max: dmax,
        contact_duration: end - start,
    })
}

/// Time where `f` crosses zero between lines `a` and `b`, linearly interpolated.
fn cross(a: &[f64; 6], b: &[f64; 6], f: impl Fn(&[f64; 6]) -> f64) -> f64 {
    let (fa, fb) = (f(a), f(b));
    if fa == fb {
        return b[0];
    }
    a[0] + (b[0] - a[0]) * fa / (fa - fb)
}

fn unfinished(source: &str) -> Error {
    Error::Parse(format!(
        "{source}: the contact has not ended by the last line (run longer or faster)"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_collision_reads_back() {
        // Overlap δ = sin(t) for t in [0, π], then apart; force = δ (tensile law).
        let mut s = String::from("# header\n");
        let d = 1.0;
        for i in 0..=400 {
            let t = i as f64 * 0.01;
            let delta = if t < std::f64::consts::PI {
                t.sin()
            } else {
                -(t - std::f64::consts::PI)
            };
            let x = (d - delta) / 2.0;
            let v = if t < std::f64::consts::PI {
                0.5 * t.cos()
            } else {
                -0.5
            };
            s += &format!("{t} {} {x} {v} {} {}\n", -x, -v, -delta.max(0.0));
        }
        let o = read(&s, "test", d, 1.0, true).unwrap();
        assert!((o.e - 1.0).abs() < 1e-12);
        assert!((o.delta_max - 1.0).abs() < 1e-4);
        assert!((o.contact_duration - std::f64::consts::PI).abs() < 1e-3);
        assert!(read("1 2 3\n", "t", 1.0, 1.0, true).is_err());
    }
}
