//! The damped laws ranked calibrated. A damped law's restitution is a parameter, not a
//! property of the metal, so its default (e = 0.8, or A = 1e-7 s) says nothing about its
//! form. Per metal, each law's one damping parameter is set (bisection over its interval; e
//! is monotone in it) so that its e equals the FE's at one reference point, the metal's
//! median speed at the largest diameter; the law is then judged at the metal's other points
//! and ranked as the material laws are ([`super::ranking`]).

use super::law_side::head_on_law_with;
use super::matrix::HeadOnPoint;
use super::ranking::{against_fe, metals_of, LawErrors};
use super::HeadOnResult;
use crate::analytic::laws::Registry;
use crate::error::Result;
use rayon::prelude::*;

/// A damped law's one damping parameter and the interval a calibration searches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Damping {
    /// Normal law name.
    pub law: &'static str,
    /// The parameter a calibration sets (the others stay at their defaults).
    pub param: &'static str,
    /// Lower end of the searched interval (the parameter's unit).
    pub low: f64,
    /// Upper end of the searched interval.
    pub high: f64,
    /// Whether the interval is halved in ln of the parameter (a scale, not a fraction).
    pub log_scale: bool,
}

/// A restitution parameter searched over the range its laws accept.
const fn by_e(law: &'static str) -> Damping {
    Damping {
        law,
        param: "e",
        low: 0.01,
        high: 1.0,
        log_scale: false,
    }
}

/// The damped laws.
pub const DAMPED: [Damping; 6] = [
    by_e("linear-dashpot"),
    by_e("hertz-damped"),
    by_e("hunt-crossley"),
    by_e("lankarani-nikravesh"),
    Damping {
        law: "kuwabara-kono",
        param: "A",
        low: 1e-12,
        high: 1e-4,
        log_scale: true,
    },
    by_e("walton-braun"),
];

/// Relative mismatch in e at the reference below which a calibration has converged.
pub const MATCH: f64 = 1e-9;

/// True for a law of [`DAMPED`].
pub fn is_damped(law: &str) -> bool {
    DAMPED.iter().any(|d| d.law == law)
}

/// One damped law calibrated on one metal.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibrated {
    /// The law's errors over the metal's other points (the reference left out).
    pub errors: LawErrors,
    /// The fitted parameter: name and value (its unit: `twoball laws`).
    pub parameter: (&'static str, f64),
}

/// The damped laws of one metal, best first, and where they were calibrated.
#[derive(Debug, Clone, PartialEq)]
pub struct MetalCalibration {
    /// Metal preset.
    pub metal: String,
    /// Relative speed of the reference point, m/s.
    pub speed: f64,
    /// Ball diameter of the reference point, m.
    pub diameter: f64,
    /// The laws, sorted by [`LawErrors::combined`].
    pub laws: Vec<Calibrated>,
    /// The laws whose fit failed (they cannot reach the FE's e at the reference).
    pub failed: Vec<String>,
}

/// The reference point of `metal`: the median-speed point (the faster of the two middle
/// ones) among its points with an FE answer at their largest diameter.
pub fn reference<'a>(head_on: &'a [HeadOnResult], metal: &str) -> Option<&'a HeadOnResult> {
    let done = || {
        head_on
            .iter()
            .filter(move |h| h.point.metal == metal && h.fe_done().is_some())
    };
    let d = done().map(|h| h.point.diameter).fold(f64::NAN, f64::max);
    let mut at_d: Vec<&HeadOnResult> = done().filter(|h| h.point.diameter == d).collect();
    at_d.sort_by(|a, b| a.point.speed.total_cmp(&b.point.speed));
    at_d.get(at_d.len() / 2).copied()
}

/// Relative errors (law − FE)/FE of `law` with `overrides` at point `h`, in the order of
/// [`super::ranking::QUANTITIES`]; None without an FE answer.
fn errors_with(
    registry: &Registry,
    law: &str,
    overrides: &[(String, f64)],
    h: &HeadOnResult,
) -> Result<Option<[f64; 4]>> {
    let Some(f) = h.fe_done() else {
        return Ok(None);
    };
    let l = head_on_law_with(registry, law, overrides, &h.point, h.point.speed)?;
    Ok(Some(against_fe(
        [l.e, l.delta_max, l.contact_duration, l.peak_force],
        f,
    )))
}

/// The value of `d.param` in [low, high] (halved in ln with `log_scale`) at which the law's e
/// equals `target` at point `p`, within [`MATCH`]; None when e(low) − target and
/// e(high) − target have the same sign (no value in the interval reaches it; e is monotone in
/// a damping parameter) or the law fails to integrate at a value tried (the balls do not
/// separate).
fn solve_parameter(registry: &Registry, d: Damping, p: &HeadOnPoint, target: f64) -> Option<f64> {
    let gap = |x: f64| -> Option<f64> {
        let l = head_on_law_with(registry, d.law, &[(d.param.to_string(), x)], p, p.speed).ok()?;
        Some(l.e / target - 1.0)
    };
    let to = |x: f64| if d.log_scale { x.ln() } else { x };
    let from = |y: f64| if d.log_scale { y.exp() } else { y };
    let (ga, gb) = (gap(d.low)?, gap(d.high)?);
    if ga.abs() < MATCH {
        return Some(d.low);
    }
    if ga * gb > 0.0 {
        return None;
    }
    let (mut a, mut b) = (to(d.low), to(d.high));
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        let gm = gap(from(m))?;
        if gm.abs() < MATCH || (b - a).abs() <= 1e-14 * m.abs().max(1.0) {
            return Some(from(m));
        }
        if (gm > 0.0) == (ga > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    Some(from(0.5 * (a + b)))
}

/// Sets the damping parameter of `d.law` so that its e equals the FE's at `reference` and
/// judges the law at the other points of `points`; None when no value reaches it.
///
/// Errors: the law fails to integrate at a point with the value found.
fn calibrate(
    registry: &Registry,
    d: Damping,
    reference: &HeadOnResult,
    points: &[&HeadOnResult],
) -> Result<Option<Calibrated>> {
    let Some(fe) = reference.fe_done() else {
        return Ok(None);
    };
    let Some(value) = solve_parameter(registry, d, &reference.point, fe.e.finest) else {
        return Ok(None);
    };
    let overrides = [(d.param.to_string(), value)];
    let mut rows = vec![];
    for h in points.iter().filter(|h| !std::ptr::eq(**h, reference)) {
        if let Some(r) = errors_with(registry, d.law, &overrides, h)? {
            rows.push(r);
        }
    }
    Ok(Some(Calibrated {
        errors: LawErrors::from_rows(d.law, &rows),
        parameter: (d.param, value),
    }))
}

/// Every damped law of `registry` calibrated on every metal of `head_on` (in the order
/// metals first appear) that has an FE answer.
///
/// Errors: a law that fails to integrate at a point.
pub fn calibrate_all(
    registry: &Registry,
    head_on: &[HeadOnResult],
) -> Result<Vec<MetalCalibration>> {
    let mut out = vec![];
    for metal in metals_of(head_on) {
        let Some(reference) = reference(head_on, metal) else {
            continue;
        };
        let points: Vec<&HeadOnResult> =
            head_on.iter().filter(|h| h.point.metal == metal).collect();
        let present: Vec<Damping> = DAMPED
            .into_iter()
            .filter(|d| registry.normal(d.law).is_ok())
            .collect();
        let fitted: Vec<Option<Calibrated>> = present
            .par_iter()
            .map(|d| calibrate(registry, *d, reference, &points))
            .collect::<Result<_>>()?;
        let failed = present
            .iter()
            .zip(&fitted)
            .filter(|(_, f)| f.is_none())
            .map(|(d, _)| d.law.to_string())
            .collect();
        let mut laws: Vec<Calibrated> = fitted.into_iter().flatten().collect();
        laws.sort_by(|a, b| a.errors.combined.total_cmp(&b.errors.combined));
        out.push(MetalCalibration {
            metal: metal.to_string(),
            speed: reference.point.speed,
            diameter: reference.point.diameter,
            laws,
            failed,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::laws::{ContactPair, Params};
    use crate::analytic::Body;
    use crate::material::Material;

    /// Every damped law is a law of the registry, and both ends of its interval are values of
    /// its parameter that the law accepts (a misspelt or out-of-range entry would otherwise
    /// read as "cannot reach the FE's e").
    #[test]
    fn every_damping_entry_names_a_parameter_its_law_accepts() {
        let registry = Registry::builtin();
        let b = Body::ball(Material::preset("copper-fe").unwrap(), 0.02, "ball").unwrap();
        let pair = ContactPair::between(&b, &b, 0.2);
        for d in DAMPED {
            let spec = registry.normal(d.law).unwrap();
            for x in [d.low, d.high] {
                Params::resolve(spec.name, spec.params, &[(d.param.to_string(), x)], &pair)
                    .unwrap_or_else(|e| panic!("{}: {e}", d.law));
            }
        }
    }
}
