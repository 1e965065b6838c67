//! The report's oblique part: every tangential law against the FE's tangential restitution
//! and rebound spin, with the FE's error bars, over Maw, Barber & Fawcett's normalised angle
//! of incidence, for each metal and its elastic twin; the laws ranked per group.

use super::bars::bar;
use super::fe::ObliqueFe;
use super::matrix::ObliquePoint;
use super::{BenchResults, ObliqueResult};
use std::fmt::Write as _;

/// The points of one metal and response (plastic or the elastic twin), in matrix order.
pub fn group<'a>(r: &'a BenchResults, metal: &str, elastic: bool) -> Vec<&'a ObliqueResult> {
    r.oblique
        .iter()
        .filter(|o| o.point.metal == metal && o.point.elastic == elastic)
        .collect()
}

/// The (metal, elastic) groups present, in matrix order.
pub fn groups(r: &BenchResults) -> Vec<(String, bool)> {
    let mut out: Vec<(String, bool)> = vec![];
    for o in &r.oblique {
        let g = (o.point.metal.clone(), o.point.elastic);
        if !out.contains(&g) {
            out.push(g);
        }
    }
    out
}

/// The response's name: "elastic twin", or "elastic-plastic" for the metal itself.
pub fn response(elastic: bool) -> &'static str {
    if elastic {
        "elastic twin"
    } else {
        "elastic-plastic"
    }
}

/// One tangential law's errors over a group's points.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentialErrors {
    /// Tangential law name.
    pub law: String,
    /// RMS of e_t(law) − e_t(FE), -.
    pub rms_restitution: f64,
    /// RMS of the relative spin error ω(law)/ω(FE) − 1, -.
    pub rms_spin: f64,
    /// Points whose e_t(law) lies within the FE bar.
    pub within_bar: usize,
    /// Points compared (those with an FE answer).
    pub points: usize,
}

/// The tangential laws' errors over `pts`, best (smallest RMS e_t error) first.
pub fn rank_tangential(pts: &[&ObliqueResult], laws: &[String]) -> Vec<TangentialErrors> {
    let mut out: Vec<TangentialErrors> = laws
        .iter()
        .enumerate()
        .map(|(k, law)| {
            let (mut se, mut ss, mut within, mut n) = (0.0, 0.0, 0, 0);
            for o in pts {
                let (Some(f), Some(l)) = (o.fe.as_ref().and_then(|f| f.done()), o.laws.get(k))
                else {
                    continue;
                };
                let de = l.tangential_restitution - f.tangential_restitution.finest;
                se += de * de;
                ss += (l.spin / f.spin.finest - 1.0).powi(2);
                within += usize::from(de.abs() <= f.tangential_restitution.error);
                n += 1;
            }
            let rms = |s: f64| {
                if n > 0 {
                    (s / n as f64).sqrt()
                } else {
                    f64::NAN
                }
            };
            TangentialErrors {
                law: law.clone(),
                rms_restitution: rms(se),
                rms_spin: rms(ss),
                within_bar: within,
                points: n,
            }
        })
        .collect();
    out.sort_by(|a, b| a.rms_restitution.total_cmp(&b.rms_restitution));
    out
}

/// The FE's tangential over μ times its normal impulse on ball 1, in the frame of touch:
/// J_t/(μJ_n) = Δv_t/(μ(1 + e)v_n/2), from ball 1's tangential velocity before (v_t/2) and after
/// and the restitution e (1 in gross sliding by the rigid-body exchange; less while the contact
/// sticks in part).
pub fn impulse_ratio(p: &ObliquePoint, f: &ObliqueFe) -> f64 {
    let dvt = 0.5 * p.ratio * p.normal_speed - f.v1t_after;
    dvt / (p.material.mu * (1.0 + f.e.finest) * 0.5 * p.normal_speed)
}

/// Appends the oblique section to `s`.
pub fn oblique_section(s: &mut String, r: &BenchResults) {
    if r.oblique.is_empty() {
        return;
    }
    let _ = writeln!(s, "## Oblique impacts: tangential laws\n");
    let _ = writeln!(
        s,
        "Two identical balls, relative normal speed v_n and tangential speed v_t, no spin \
         before. ψ₁ = κ v_t/(μ v_n) is Maw, Barber & Fawcett's normalised angle of incidence \
         (κ = 4G*/E*, μ the metal's friction coefficient). FE: the 3D half model on the default \
         graded meshes (level 0), each figure with its two-level error bar from meshes twice as \
         coarse (level −1); the tangential figures' bars assume order 1 (three times the \
         step) and the spin's carries at least the impulse's share of e_t's (docs/design.md, \
         \"Error estimates\"). Against the next level finer on four copper points the \
         tangential bars held in 8 of 8 checks and e's in 2 of 4 (docs/contact-laws.md, \"The \
         oblique bars\"). e_t = −u⁺/u⁻ is the tangential restitution of the contact points, ω the \
         spin of ball 1 after (rad/s, about n × t). The elastic twin is the metal with a yield \
         strength of 100 GPa. Each tangential law is paired with Hertz on the elastic twin and \
         with the metal's best-ranked normal law otherwise (named). Theory: Maw, Barber & \
         Fawcett's elastic impact (`twoball laws mbf`) on the elastic twin. FE J_t/(μJ_n): ball \
         1's tangential over μ times its normal impulse in the frame of touch (1 in gross \
         sliding by the rigid-body exchange).\n"
    );
    let _ = writeln!(
        s,
        "Ranking per metal and response, over the points with an FE answer: RMS of e_t(law) − \
         e_t(FE), RMS of the relative spin error, and the points where the law's e_t lies within \
         the FE bar.\n"
    );
    let _ = writeln!(
        s,
        "| metal | response | rank | tangential law | RMS e_t error | RMS ω error (%) | e_t within the FE bar |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for (metal, elastic) in groups(r) {
        let pts = group(r, &metal, elastic);
        if !pts
            .iter()
            .any(|o| o.fe.as_ref().is_some_and(|f| f.done().is_some()))
        {
            let _ = writeln!(
                s,
                "| {metal} | {} | | no FE answer | | | |",
                response(elastic)
            );
            continue;
        }
        for (i, t) in rank_tangential(&pts, &r.tangential_laws).iter().enumerate() {
            let _ = writeln!(
                s,
                "| {metal} | {} | {} | {} | {:.3} | {:.1} | {} of {} |",
                response(elastic),
                i + 1,
                t.law,
                t.rms_restitution,
                100.0 * t.rms_spin,
                t.within_bar,
                t.points
            );
        }
    }
    let _ = writeln!(s);
    let laws = r.tangential_laws.join(" | ");
    let dashes = "---|".repeat(r.tangential_laws.len());
    for (title, spin) in [
        ("Tangential restitution e_t", false),
        ("Spin ω of ball 1 after (rad/s)", true),
    ] {
        let _ = writeln!(s, "{title}, FE with its bar and each law:\n");
        let _ = writeln!(
            s,
            "| metal | response | ψ₁ | v_t/v_n | normal law | FE e | FE J_t/(μJ_n) | FE | theory | {laws} |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|{dashes}");
        for o in &r.oblique {
            let p = &o.point;
            let normal = o.laws.first().map_or("", |l| l.normal_law.as_str());
            let lead = format!(
                "| {} | {} | {:.2} | {:.4} | {normal} |",
                p.metal,
                response(p.elastic),
                p.angle,
                p.ratio
            );
            let Some(f) = o.fe.as_ref().and_then(|f| f.done()) else {
                let why = match &o.fe {
                    Some(super::cache::Stored::Failed(m)) => {
                        format!("failed: {}", m.replace('|', "/"))
                    }
                    _ => "not run".into(),
                };
                let _ = writeln!(s, "{lead} | {why} | | |{}", " |".repeat(o.laws.len()));
                continue;
            };
            let (fe, theory, cells): (String, String, Vec<String>) = if spin {
                (
                    bar(f.spin.finest, f.spin.error, 1.0, 2),
                    o.theory.map_or(String::new(), |t| format!("{:.2}", t.spin)),
                    o.laws.iter().map(|l| format!("{:.2}", l.spin)).collect(),
                )
            } else {
                let t = &f.tangential_restitution;
                (
                    bar(t.finest, t.error, 1.0, 4),
                    o.theory.map_or(String::new(), |t| {
                        format!("{:.4}", t.tangential_restitution)
                    }),
                    o.laws
                        .iter()
                        .map(|l| format!("{:.4}", l.tangential_restitution))
                        .collect(),
                )
            };
            let _ = writeln!(
                s,
                "{lead} {:.4} | {:.4} | {fe} | {theory} | {} |",
                f.e.finest,
                impulse_ratio(p, f),
                cells.join(" | ")
            );
        }
        let _ = writeln!(s);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;
    use crate::study::laws_bench::cache::Stored;
    use crate::study::laws_bench::fe::ObliqueFe;
    use crate::study::laws_bench::law_side::ObliqueLaw;
    use crate::study::laws_bench::matrix::ObliquePoint;
    use crate::study::records::estimate::Estimate;

    /// A point whose FE says e_t = `et` ± `bar` and spin −10 rad/s, and two laws: one off
    /// by `off` in e_t with the FE spin, one off by 0.5 with twice the spin.
    fn point(et: f64, bar: f64, off: f64) -> ObliqueResult {
        let est = |v: f64, e: f64| Estimate::recorded(v, e);
        let law = |name: &str, d: f64, spin: f64| ObliqueLaw {
            law: name.into(),
            normal_law: "hertz".into(),
            e: 1.0,
            tangential_restitution: et + d,
            spin,
            v1t_after: 0.0,
        };
        ObliqueResult {
            point: ObliquePoint {
                metal: "steel".into(),
                material: Material::preset("steel").unwrap(),
                diameter: 0.02,
                normal_speed: 1.0,
                ratio: 0.1,
                angle: 1.0,
                elastic: false,
            },
            fe: Some(Stored::Done(ObliqueFe {
                e: est(0.4, 0.01),
                tangential_restitution: est(et, bar),
                spin: est(-10.0, 0.1),
                v1t_after: 0.0,
                delta_max: est(1e-5, 1e-7),
                contact_duration: est(1e-4, 1e-6),
                energy_error: 1e-4,
                wall_seconds: 1.0,
            })),
            laws: vec![law("far", 0.5, -20.0), law("near", off, -10.0)],
            theory: None,
        }
    }

    /// Ball 1 losing μ(1 + e)v_n/2 of its tangential speed took the full Coulomb impulse.
    #[test]
    fn the_impulse_ratio_is_one_at_the_coulomb_limit() {
        let o = point(0.2, 0.01, 0.0);
        let Some(Stored::Done(mut f)) = o.fe.clone() else {
            unreachable!()
        };
        let (p, mu) = (&o.point, o.point.material.mu);
        f.v1t_after = 0.5 * p.ratio * p.normal_speed - mu * (1.0 + 0.4) * 0.5 * p.normal_speed;
        assert!((impulse_ratio(p, &f) - 1.0).abs() < 1e-12);
        f.v1t_after = 0.5 * p.ratio * p.normal_speed;
        assert_eq!(impulse_ratio(p, &f), 0.0);
    }

    /// The RMS errors are those of the points, the bar count counts the points inside the
    /// FE bar, the law nearer in e_t ranks first, and a point without an FE answer is left
    /// out.
    #[test]
    fn tangential_laws_rank_by_their_rms_error_in_e_t() {
        let mut none = point(0.2, 0.01, 0.0);
        none.fe = Some(Stored::Failed("stopped".into()));
        let pts = [point(0.2, 0.05, 0.03), point(0.3, 0.01, -0.04), none];
        let refs: Vec<&ObliqueResult> = pts.iter().collect();
        let ranked = rank_tangential(&refs, &["far".into(), "near".into()]);
        assert_eq!(ranked[0].law, "near");
        assert_eq!(ranked[0].points, 2);
        assert!(
            (ranked[0].rms_restitution - (0.5f64 * (0.03 * 0.03 + 0.04 * 0.04)).sqrt()).abs()
                < 1e-15
        );
        assert_eq!(ranked[0].rms_spin, 0.0);
        assert_eq!(ranked[0].within_bar, 1);
        assert!((ranked[1].rms_restitution - 0.5).abs() < 1e-12);
        assert!((ranked[1].rms_spin - 1.0).abs() < 1e-12);
        assert_eq!(ranked[1].within_bar, 0);
    }
}
