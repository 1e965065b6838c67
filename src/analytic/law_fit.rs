//! Calibration of a normal contact law: least squares on the relative errors of e and δ_max
//! over a set of head-on impacts (Levenberg-Marquardt in the logarithms of the free
//! parameters, uncertainties from the covariance s²(JᵀJ)⁻¹), and the export of the fitted
//! parameters in the input syntax of DEM codes that ship the law.

use super::body::Body;
use super::impact::integrate;
use super::laws::coulomb::Coulomb;
use super::laws::{ContactPair, NormalSpec, Params};
use crate::error::{Error, Result};

/// One measured (or FE) head-on impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation {
    /// Relative normal approach speed v_r, m/s.
    pub speed: f64,
    /// Coefficient of restitution.
    pub e: f64,
    /// Maximum approach, m.
    pub delta_max: f64,
}

/// Column of `header` named exactly `name`.
fn column(header: &[&str], name: &str) -> Option<usize> {
    header.iter().position(|h| h.trim() == name)
}

/// Reads observations from CSV text. Two layouts are accepted: the general one with columns
/// `v_r [m/s]`, `e [-]`, `delta_max [m]` (any others ignored), and a `twoball sweep` CSV
/// (head-on rows with status `done`, columns `v1n [m/s]`, `v2n [m/s]`, `v1t [m/s]`,
/// `v2t [m/s]`, `e_fe [-]`, `delta_max_fe [m]`), filtered to `diameter` (m, if given) and
/// `mesh` (if given). `source` names the input in errors.
pub fn read_observations(
    text: &str,
    source: &str,
    diameter: Option<f64>,
    mesh: Option<&str>,
) -> Result<Vec<Observation>> {
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header: Vec<&str> = lines
        .next()
        .ok_or_else(|| Error::Parse(format!("{source}: empty file")))?
        .split(',')
        .collect();
    let num = |row: &[&str], i: usize, line: usize| -> Result<f64> {
        let cell = row.get(i).copied().unwrap_or("").trim();
        cell.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                Error::Parse(format!(
                    "{source} line {line}: column {} = '{cell}' is not a finite number",
                    header[i].trim()
                ))
            })
    };
    let mut out = vec![];
    if let (Some(iv), Some(ie), Some(id)) = (
        column(&header, "v_r [m/s]"),
        column(&header, "e [-]"),
        column(&header, "delta_max [m]"),
    ) {
        for (k, l) in lines.enumerate() {
            let row: Vec<&str> = l.split(',').collect();
            out.push(Observation {
                speed: num(&row, iv, k + 2)?,
                e: num(&row, ie, k + 2)?,
                delta_max: num(&row, id, k + 2)?,
            });
        }
    } else {
        let need = [
            "status",
            "diameter [m]",
            "v1n [m/s]",
            "v2n [m/s]",
            "v1t [m/s]",
            "v2t [m/s]",
            "e_fe [-]",
            "delta_max_fe [m]",
        ];
        let mut idx = vec![];
        for n in need {
            idx.push(column(&header, n).ok_or_else(|| {
                Error::Parse(format!(
                    "{source}: no column '{n}' (expected either v_r [m/s], e [-], delta_max [m] \
                     or a twoball sweep CSV)"
                ))
            })?);
        }
        let im = column(&header, "mesh");
        for (k, l) in lines.enumerate() {
            let row: Vec<&str> = l.split(',').collect();
            if row.get(idx[0]).map(|s| s.trim()) != Some("done") {
                continue;
            }
            if let (Some(m), Some(i)) = (mesh, im) {
                if row.get(i).map(|s| s.trim()) != Some(m) {
                    continue;
                }
            }
            let line = k + 2;
            let d = num(&row, idx[1], line)?;
            if diameter.is_some_and(|want| (d - want).abs() > 1e-9 * want) {
                continue;
            }
            if num(&row, idx[4], line)? != 0.0 || num(&row, idx[5], line)? != 0.0 {
                continue;
            }
            out.push(Observation {
                speed: num(&row, idx[2], line)? - num(&row, idx[3], line)?,
                e: num(&row, idx[6], line)?,
                delta_max: num(&row, idx[7], line)?,
            });
        }
    }
    for o in &out {
        if !(o.speed > 0.0 && o.e > 0.0 && o.delta_max > 0.0) {
            return Err(Error::invalid(
                format!("{source} observation"),
                format!(
                    "v_r = {}, e = {}, delta_max = {}",
                    o.speed, o.e, o.delta_max
                ),
                "v_r > 0, e > 0, delta_max > 0",
            ));
        }
    }
    Ok(out)
}

/// A fitted law.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// The optimum: all parameters, the free ones' uncertainties, and the root-mean-square
    /// relative residual over e and δ_max.
    pub optimum: LeastSquares,
    /// Per observation: (observation, fitted e, fitted δ_max).
    pub rows: Vec<(Observation, f64, f64)>,
}

/// e and δ_max of law `spec` with `params` for the pair of `b1`, `b2` at approach speed v.
pub fn predict(
    spec: &NormalSpec,
    pair: &ContactPair,
    params: &Params,
    b1: &Body,
    b2: &Body,
    speed: f64,
) -> Result<(f64, f64, f64)> {
    let law = (spec.build)(pair, params);
    let (v1, v2) = if b2.is_wall() {
        ([speed, 0.0], [0.0, 0.0])
    } else {
        ([0.5 * speed, 0.0], [-0.5 * speed, 0.0])
    };
    let r = integrate(b1, b2, v1, v2, law.as_ref(), &Coulomb { mu: 0.0 }, 1e-9)?
        .ok_or_else(|| Error::invalid("speed", speed, "> 0 m/s"))?;
    Ok((r.e, r.delta_max, r.contact_duration))
}

/// Solves the small dense system A x = b (Gaussian elimination, partial pivoting); `None` if
/// singular.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c].abs() < 1e-300 {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        let (top, rest) = a.split_at_mut(c + 1);
        let pivot = &top[c];
        for (i, row) in rest.iter_mut().enumerate() {
            let f = row[c] / pivot[c];
            for (x, p) in row.iter_mut().zip(pivot.iter()).skip(c) {
                *x -= f * p;
            }
            b[c + 1 + i] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    Some(x)
}

/// Weights of the relative residuals of e and δ_max in a fit (0 leaves a quantity out).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weights {
    /// Weight of the relative error in e.
    pub e: f64,
    /// Weight of the relative error in δ_max.
    pub delta_max: f64,
}

impl Weights {
    /// e and δ_max alike (what `twoball laws fit` uses).
    pub const BOTH: Weights = Weights {
        e: 1.0,
        delta_max: 1.0,
    };
    /// e alone.
    pub const E_ONLY: Weights = Weights {
        e: 1.0,
        delta_max: 0.0,
    };
}

/// Fits the `free` parameters of `spec` (others at `fixed` overrides or defaults) to `obs`,
/// with the relative residuals of e and δ_max weighted by `w` (each weight finite and ≥ 0,
/// not both 0; `twoball laws fit` uses [`Weights::BOTH`]); the rms residual and the
/// uncertainties count only the residuals with a positive weight.
/// Errors: no observations, an unknown or duplicate free key, a law that fails to integrate,
/// weights out of range.
#[allow(clippy::too_many_arguments)]
pub fn fit_weighted(
    spec: &NormalSpec,
    pair: &ContactPair,
    b1: &Body,
    b2: &Body,
    obs: &[Observation],
    free: &[String],
    fixed: &[(String, f64)],
    w: Weights,
) -> Result<Fit> {
    let valid = |x: f64| x.is_finite() && x >= 0.0;
    if !(valid(w.e) && valid(w.delta_max) && w.e + w.delta_max > 0.0) {
        return Err(Error::invalid(
            "fit weights",
            format!("e {}, delta_max {}", w.e, w.delta_max),
            "finite, >= 0, not both 0",
        ));
    }
    if obs.is_empty() {
        return Err(Error::invalid(
            "observations",
            0,
            "at least one head-on impact",
        ));
    }
    let residuals = |p: &Params| -> Result<Vec<f64>> {
        let mut r = Vec::with_capacity(2 * obs.len());
        for o in obs {
            let (e, d, _) = predict(spec, pair, p, b1, b2, o.speed)?;
            if w.e > 0.0 {
                r.push(w.e * (e - o.e) / o.e);
            }
            if w.delta_max > 0.0 {
                r.push(w.delta_max * (d - o.delta_max) / o.delta_max);
            }
        }
        Ok(r)
    };
    let optimum = least_squares(spec, pair, free, fixed, residuals)?;
    let mut rows = vec![];
    for o in obs {
        let (e, d, _) = predict(spec, pair, &optimum.params, b1, b2, o.speed)?;
        rows.push((*o, e, d));
    }
    Ok(Fit { optimum, rows })
}

/// The optimum of a least-squares fit of a law's parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct LeastSquares {
    /// All parameters, the free ones at their optimum.
    pub params: Params,
    /// Free parameter names.
    pub free: Vec<&'static str>,
    /// One-standard-deviation uncertainty of each free parameter (same units; NaN if there
    /// are no more residuals than free parameters).
    pub sigma: Vec<f64>,
    /// Root-mean-square residual at the optimum (the residuals' unit).
    pub rms: f64,
}

/// Fits the `free` parameters of `spec` (the others at the `fixed` overrides or their defaults
/// for `pair`) so that the residuals `residuals(params)` have the least sum of squares:
/// Levenberg-Marquardt in the logarithms of the free parameters (each stays positive and
/// within its declared range), uncertainties from the covariance s²(JᵀJ)⁻¹.
///
/// Errors: an unknown, duplicate or non-positive free key; a failing `residuals`.
pub fn least_squares(
    spec: &NormalSpec,
    pair: &ContactPair,
    free: &[String],
    fixed: &[(String, f64)],
    residuals: impl Fn(&Params) -> Result<Vec<f64>>,
) -> Result<LeastSquares> {
    let base = Params::resolve(spec.name, spec.params, fixed, pair)?;
    let mut names: Vec<&'static str> = vec![];
    for f in free {
        let s = spec.params.iter().find(|p| p.key == f).ok_or_else(|| {
            let keys: Vec<&str> = spec.params.iter().map(|p| p.key).collect();
            Error::invalid("--free", f, format!("one of {}", keys.join(", ")))
        })?;
        if names.contains(&s.key)
            || s.min < 0.0
            || base.get(s.key).is_nan()
            || base.get(s.key) <= 0.0
        {
            return Err(Error::invalid(
                "--free",
                f,
                "distinct keys of positive parameters",
            ));
        }
        names.push(s.key);
    }
    let make = |theta: &[f64]| -> Result<Params> {
        let mut over: Vec<(String, f64)> = base.iter().map(|(k, v)| (k.to_string(), v)).collect();
        for (k, t) in names.iter().zip(theta) {
            let s = spec.params.iter().find(|p| p.key == *k).expect("declared");
            let v = t.exp().clamp(s.min.max(1e-300), s.max);
            over.push((k.to_string(), v));
        }
        Params::resolve(spec.name, spec.params, &over, pair)
    };
    let residuals = |theta: &[f64]| -> Result<Vec<f64>> { residuals(&make(theta)?) };
    let ssr = |r: &[f64]| r.iter().map(|x| x * x).sum::<f64>();
    let mut theta: Vec<f64> = names.iter().map(|k| base.get(k).ln()).collect();
    let mut r = residuals(&theta)?;
    let mut lambda = 1e-3;
    let np = names.len();
    let jacobian = |theta: &[f64], r: &[f64]| -> Result<Vec<Vec<f64>>> {
        let mut cols = vec![];
        for j in 0..np {
            let mut t = theta.to_vec();
            let h = 1e-6;
            t[j] += h;
            let rj = residuals(&t)?;
            cols.push(
                rj.iter()
                    .zip(r)
                    .map(|(a, b)| (a - b) / h)
                    .collect::<Vec<_>>(),
            );
        }
        Ok(cols)
    };
    let normal = |cols: &[Vec<f64>]| -> Vec<Vec<f64>> {
        (0..np)
            .map(|i| {
                (0..np)
                    .map(|j| cols[i].iter().zip(&cols[j]).map(|(a, b)| a * b).sum())
                    .collect()
            })
            .collect()
    };
    for _ in 0..if np == 0 { 0 } else { 60 } {
        let cols = jacobian(&theta, &r)?;
        let jtj = normal(&cols);
        let g: Vec<f64> = cols
            .iter()
            .map(|c| -c.iter().zip(&r).map(|(a, b)| a * b).sum::<f64>())
            .collect();
        let mut improved = false;
        for _ in 0..20 {
            let mut a = jtj.clone();
            for (i, row) in a.iter_mut().enumerate() {
                row[i] += lambda * jtj[i][i].max(1e-12);
            }
            let Some(step) = solve(a, g.clone()) else {
                lambda *= 10.0;
                continue;
            };
            let trial: Vec<f64> = theta.iter().zip(&step).map(|(t, s)| t + s).collect();
            let rt = residuals(&trial)?;
            if ssr(&rt) < ssr(&r) {
                let gain = (ssr(&r) - ssr(&rt)) / ssr(&r).max(1e-300);
                theta = trial;
                r = rt;
                lambda = (lambda / 3.0).max(1e-12);
                improved = gain > 1e-12;
                break;
            }
            lambda *= 4.0;
        }
        if !improved {
            break;
        }
    }
    let params = make(&theta)?;
    let dof = r.len() as f64 - np as f64;
    let sigma = if np == 0 {
        vec![]
    } else if dof > 0.0 {
        let cols = jacobian(&theta, &r)?;
        let jtj = normal(&cols);
        let s2 = ssr(&r) / dof;
        (0..np)
            .map(|j| {
                let mut unit = vec![0.0; np];
                unit[j] = 1.0;
                solve(jtj.clone(), unit).map_or(f64::NAN, |col| {
                    (s2 * col[j]).max(0.0).sqrt() * params.get(names[j])
                })
            })
            .collect()
    } else {
        vec![f64::NAN; np]
    };
    Ok(LeastSquares {
        params,
        free: names,
        sigma,
        rms: (ssr(&r) / r.len() as f64).sqrt(),
    })
}
