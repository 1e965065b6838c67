//! Calibration against the benchmark's FE points (acceptance 4 of the contact-law issue):
//! per metal, the existing least-squares fit (`analytic::law_fit`) of a few laws with free
//! parameters that make physical sense, on the FE points of 0.1-10 m/s; and the FE's own
//! power-law slope of e(v) against Johnson's v^(-1/4).

use crate::analytic::law_fit::{fit_weighted, Observation, Weights};
use crate::analytic::laws::{ContactPair, Registry};
use crate::analytic::Body;
use crate::error::Result;
use crate::material::Material;

/// The fitted laws and their free parameters in a fit to e and δ_max.
pub const FIT_LAWS: [(&str, &[&str]); 6] = [
    ("thornton", &["p_y"]),
    ("li-yang-shi", &["p_y"]),
    ("jackson-green", &["S_y"]),
    ("tabor-hardening", &["c", "E_t"]),
    ("walton-braun", &["k", "e"]),
    ("hertz-damped", &["E_star", "e"]),
];

/// The free parameters of a law of [`FIT_LAWS`] in a fit to e alone: a stiffness that does
/// not change e (the constant-restitution laws' `k` and `E_star`) stays at its default.
pub fn e_only_free(law: &str) -> &'static [&'static str] {
    match law {
        "walton-braun" | "hertz-damped" => &["e"],
        _ => FIT_LAWS
            .iter()
            .find(|(l, _)| *l == law)
            .map_or(&[], |(_, f)| f),
    }
}

/// Relative speeds (m/s) of the FE points a fit uses.
pub const FIT_RANGE: (f64, f64) = (0.1, 10.0);

/// The acceptance bound on the best fitted law's largest relative error in e.
pub const TARGET_E_ERROR: f64 = 0.03;

/// One law fitted to one metal's FE points.
#[derive(Debug, Clone, PartialEq)]
pub struct LawFit {
    /// Normal law name.
    pub law: String,
    /// Free parameters: (key, fitted value, one-sigma uncertainty), SI units.
    pub params: Vec<(String, f64, f64)>,
    /// Root-mean-square relative residual over e and δ_max.
    pub rms: f64,
    /// Signed relative error in e of largest magnitude over the points.
    pub worst_e: f64,
    /// Signed relative error in δ_max of largest magnitude over the points.
    pub worst_delta: f64,
}

/// A power law e = C v^n fitted (least squares in logarithms) to the FE e.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLaw {
    /// Exponent n.
    pub exponent: f64,
    /// Prefactor C (e at 1 m/s), -.
    pub prefactor: f64,
    /// Signed relative error in e of largest magnitude over the points.
    pub worst_e: f64,
}

/// ln e = a + b ln v + c (ln v)² fitted (least squares) to the FE e: a restitution whose
/// log-log slope b + 2c ln v changes linearly in ln v.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogQuadratic {
    /// Coefficients a, b, c (v in m/s).
    pub coefficients: [f64; 3],
    /// Signed relative error in e of largest magnitude over the points.
    pub worst_e: f64,
}

impl LogQuadratic {
    /// The log-log slope d ln e / d ln v at speed `v` (m/s).
    pub fn slope(&self, v: f64) -> f64 {
        self.coefficients[1] + 2.0 * self.coefficients[2] * v.ln()
    }
}

/// Determinant of a 3 × 3 matrix.
fn det3(m: [[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// [`LogQuadratic`] through `obs` (None with fewer than four points: it would interpolate).
pub fn log_quadratic(obs: &[Observation]) -> Option<LogQuadratic> {
    if obs.len() < 4 {
        return None;
    }
    let mut a = [[0.0; 3]; 3];
    let mut rhs = [0.0; 3];
    for o in obs {
        let x = o.speed.ln();
        let basis = [1.0, x, x * x];
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] += basis[i] * basis[j];
            }
            rhs[i] += basis[i] * o.e.ln();
        }
    }
    let d = det3(a);
    if d.abs() < 1e-300 {
        return None;
    }
    let coefficients = [0, 1, 2].map(|k| {
        let mut m = a;
        for (row, r) in m.iter_mut().zip(rhs) {
            row[k] = r;
        }
        det3(m) / d
    });
    let [c0, c1, c2] = coefficients;
    Some(LogQuadratic {
        coefficients,
        worst_e: worst(obs.iter().map(|o| {
            let x = o.speed.ln();
            (c0 + c1 * x + c2 * x * x).exp() / o.e - 1.0
        })),
    })
}

/// The fits of one metal.
#[derive(Debug, Clone, PartialEq)]
pub struct MetalFit {
    /// Metal preset.
    pub metal: String,
    /// Ball diameter of the FE points, m.
    pub diameter: f64,
    /// The FE points used.
    pub observations: Vec<Observation>,
    /// Each law fitted to e and δ_max (as `twoball laws fit`), or why it failed.
    pub fits: Vec<(String, std::result::Result<LawFit, String>)>,
    /// Each law fitted to e alone, or why it failed.
    pub e_fits: Vec<(String, std::result::Result<LawFit, String>)>,
    /// The FE's power law over the points (None with fewer than two).
    pub power_law: Option<PowerLaw>,
    /// The FE's local slope d ln e / d ln v between its two fastest points.
    pub top_slope: Option<f64>,
    /// The FE's local slope d ln e / d ln v between its two slowest points.
    pub bottom_slope: Option<f64>,
    /// The FE's log-quadratic e(v) over the points (None with fewer than four).
    pub log_quadratic: Option<LogQuadratic>,
}

impl MetalFit {
    /// The law fitted to e alone with the smallest largest |error in e|.
    pub fn best(&self) -> Option<&LawFit> {
        self.e_fits
            .iter()
            .filter_map(|(_, f)| f.as_ref().ok())
            .min_by(|a, b| a.worst_e.abs().total_cmp(&b.worst_e.abs()))
    }
}

/// The signed value of largest magnitude (0 for none).
fn worst(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(0.0, |w, x| if x.abs() > w.abs() { x } else { w })
}

/// e = C v^n through `obs` by least squares on ln e.
pub fn power_law(obs: &[Observation]) -> Option<PowerLaw> {
    if obs.len() < 2 {
        return None;
    }
    let n = obs.len() as f64;
    let (x, y): (Vec<f64>, Vec<f64>) = obs.iter().map(|o| (o.speed.ln(), o.e.ln())).unzip();
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    let exponent = sxy / sxx;
    let prefactor = (my - exponent * mx).exp();
    Some(PowerLaw {
        exponent,
        prefactor,
        worst_e: worst(
            obs.iter()
                .map(|o| prefactor * o.speed.powf(exponent) / o.e - 1.0),
        ),
    })
}

/// Fits every law of [`FIT_LAWS`] in `registry` to `obs` (FE points of two balls of
/// `material`, diameter `diameter` m, within [`FIT_RANGE`]), once to e and δ_max and once to
/// e alone; a law that fails to fit keeps its message.
///
/// Errors: a ball the material or diameter rejects.
pub fn fit_metal(
    registry: &Registry,
    metal: &str,
    material: Material,
    diameter: f64,
    obs: Vec<Observation>,
) -> Result<MetalFit> {
    let b = Body::ball(material, diameter, "ball")?;
    let pair = ContactPair::between(&b, &b, material.mu);
    let fit_all = |w: Weights| -> Vec<(String, std::result::Result<LawFit, String>)> {
        FIT_LAWS
            .iter()
            .filter_map(|(law, free)| {
                let spec = registry.normal(law).ok()?;
                let free = if w.delta_max == 0.0 {
                    e_only_free(law)
                } else {
                    free
                };
                let free: Vec<String> = free.iter().map(|s| s.to_string()).collect();
                let r = fit_weighted(spec, &pair, &b, &b, &obs, &free, &[], w)
                    .map(|f| LawFit {
                        law: law.to_string(),
                        params: f
                            .optimum
                            .free
                            .iter()
                            .zip(&f.optimum.sigma)
                            .map(|(k, s)| (k.to_string(), f.optimum.params.get(k), *s))
                            .collect(),
                        rms: f.optimum.rms,
                        worst_e: worst(f.rows.iter().map(|(o, e, _)| e / o.e - 1.0)),
                        worst_delta: worst(f.rows.iter().map(|(o, _, d)| d / o.delta_max - 1.0)),
                    })
                    .map_err(|e| e.to_string());
                Some((law.to_string(), r))
            })
            .collect()
    };
    let (fits, e_fits) = if obs.is_empty() {
        (vec![], vec![])
    } else {
        (fit_all(Weights::BOTH), fit_all(Weights::E_ONLY))
    };
    let top_slope = match obs.len() {
        n if n >= 2 => {
            let (a, b) = (obs[n - 2], obs[n - 1]);
            Some((b.e / a.e).ln() / (b.speed / a.speed).ln())
        }
        _ => None,
    };
    let bottom_slope =
        (obs.len() >= 2).then(|| (obs[1].e / obs[0].e).ln() / (obs[1].speed / obs[0].speed).ln());
    Ok(MetalFit {
        metal: metal.to_string(),
        diameter,
        power_law: power_law(&obs),
        log_quadratic: log_quadratic(&obs),
        top_slope,
        bottom_slope,
        observations: obs,
        fits,
        e_fits,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_law_through_exact_points() {
        let obs: Vec<Observation> = [0.1, 1.0, 10.0]
            .iter()
            .map(|&v: &f64| Observation {
                speed: v,
                e: 0.4 * v.powf(-0.25),
                delta_max: 1e-5,
            })
            .collect();
        let p = power_law(&obs).unwrap();
        assert!((p.exponent + 0.25).abs() < 1e-12 && (p.prefactor - 0.4).abs() < 1e-12);
        assert!(p.worst_e.abs() < 1e-12);
    }

    #[test]
    fn log_quadratic_through_exact_points() {
        let obs: Vec<Observation> = [0.1, 0.3, 1.0, 3.0, 10.0]
            .iter()
            .map(|&v: &f64| Observation {
                speed: v,
                e: (-1.0 - 0.2 * v.ln() - 0.01 * v.ln().powi(2)).exp(),
                delta_max: 1e-5,
            })
            .collect();
        let q = log_quadratic(&obs).unwrap();
        for (c, want) in q.coefficients.iter().zip([-1.0, -0.2, -0.01]) {
            assert!((c - want).abs() < 1e-9, "{c} vs {want}");
        }
        assert!((q.slope(1.0) + 0.2).abs() < 1e-9 && q.worst_e.abs() < 1e-9);
    }
}
