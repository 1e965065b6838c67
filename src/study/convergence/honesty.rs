//! Is the error estimate honest? Over a set of cases, the estimate of each run (mesh levels
//! −1 and 0, [`crate::study::records::error_estimate`]) against its true error, taken as the
//! difference from the same case two refinements finer (level +2): head-on cases
//! ([`honesty_cases`]) and oblique impacts on a wall ([`oblique_cases`]), whose tangential
//! figures are checked too.
//!
//! The study takes a runner closure `run(scene, level)`, so the 3D model and any other model
//! are checked by the same code; [`honesty_table`] and [`oblique_honesty_table`] print the
//! result as a Markdown table.

use crate::error::Result;
use crate::scene::{Override, Scene, DEFAULT_SCENE};
use crate::study::records::error_estimate::{ErrorEstimate, LevelOutcome, TangentialEstimate};
use crate::study::records::estimate::Estimate;
use crate::study::records::tangential::Tangential;
use std::path::Path;

/// The materials of the default check (three presets: soft, medium and stiff-and-light).
pub const HONESTY_MATERIALS: [&str; 3] = ["copper-fe", "steel", "aluminum"];
/// The speeds of the default check: each ball's speed along the line of centres, m/s.
pub const HONESTY_SPEEDS: [f64; 7] = [0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0];

/// One head-on case of the check.
#[derive(Debug, Clone)]
pub struct HonestyCase {
    /// Material preset of both balls.
    pub material: String,
    /// Each ball's speed towards the other, m/s.
    pub speed: f64,
    /// Angle of incidence from the contact normal, degrees (0: head-on).
    pub incidence_deg: f64,
    /// The scene (the default scene's D = 20 mm balls, the preset, ±speed, `extra` sets).
    pub scene: Scene,
}

/// The cases: every material of `materials` at every speed of `speeds` (m/s per ball, > 0),
/// with the `extra` scene overrides (e.g. a mesh) applied to each. Fails on a bad override.
pub fn honesty_cases(
    materials: &[&str],
    speeds: &[f64],
    extra: &dyn Fn(&str, f64) -> Vec<String>,
) -> Result<Vec<HonestyCase>> {
    let mut cases = Vec::new();
    for &m in materials {
        for &v in speeds {
            let mut sets = vec![
                format!("ball1.material=\"{m}\""),
                format!("ball2.material=\"{m}\""),
                format!("ball1.velocity=[{v},0,0]"),
                format!("ball2.velocity=[{},0,0]", -v),
            ];
            sets.extend(extra(m, v));
            let sets = sets
                .iter()
                .map(|s| Override::parse(s))
                .collect::<Result<Vec<_>>>()?;
            let scene = Scene::from_toml(DEFAULT_SCENE, Path::new("."), &sets)?;
            cases.push(HonestyCase {
                material: m.to_string(),
                speed: v,
                incidence_deg: 0.0,
                scene,
            });
        }
    }
    Ok(cases)
}

/// Oblique cases of a ball on a wall: the scene file `base` (ball 1 against a wall whose
/// normal is −x), its ball 1 made of each `(name, material)` of `materials` (a scene value,
/// e.g. `{ preset = "copper-fe", mu = 0.092 }`) and sent at the speed `speed` (m/s, > 0) at
/// each angle of incidence of `angles_deg` (degrees from the normal, in [0, 90)), the
/// `extra` overrides applied last. Fails on an unreadable base or a bad override.
pub fn oblique_cases(
    base: &Path,
    materials: &[(&str, &str)],
    speed: f64,
    angles_deg: &[f64],
    extra: &[String],
) -> Result<Vec<HonestyCase>> {
    let mut cases = Vec::new();
    for &(name, material) in materials {
        for &deg in angles_deg {
            let (vt, vn) = (
                speed * deg.to_radians().sin(),
                speed * deg.to_radians().cos(),
            );
            let sets = [
                format!("ball1.material={material}"),
                format!("ball1.velocity=[{vn},{vt},0]"),
            ]
            .iter()
            .chain(extra)
            .map(|s| Override::parse(s))
            .collect::<Result<Vec<_>>>()?;
            cases.push(HonestyCase {
                material: name.to_string(),
                speed,
                incidence_deg: deg,
                scene: Scene::from_file(base, &sets)?,
            });
        }
    }
    Ok(cases)
}

/// The check of one quantity of one case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Check {
    /// The run's value (level 0), in the quantity's unit.
    pub value: f64,
    /// Its error estimate (GCI), same unit.
    pub estimate: f64,
    /// Its true error |level 0 − level +2|, same unit.
    pub true_error: f64,
}

impl Check {
    /// True when the true error lies within the estimate.
    pub fn honest(&self) -> bool {
        self.true_error <= self.estimate
    }

    fn of(est: &Estimate, reference: f64) -> Check {
        Check {
            value: est.finest,
            estimate: est.error,
            true_error: (est.finest - reference).abs(),
        }
    }
}

/// The result of one case.
#[derive(Debug, Clone)]
pub struct HonestyRow {
    /// Material preset.
    pub material: String,
    /// Speed of each ball, m/s.
    pub speed: f64,
    /// Angle of incidence, degrees (0: head-on).
    pub incidence_deg: f64,
    /// Coefficient of restitution e, -.
    pub e: Check,
    /// Maximum approach δ_max, m.
    pub delta_max: Check,
    /// Contact duration, s.
    pub contact_duration: Check,
    /// The tangential figures of an oblique impact (absent head-on).
    pub tangential: Option<TangentialChecks>,
    /// Wall time of the three runs, s.
    pub wall_time_s: f64,
}

/// The checks of an oblique impact's tangential figures ([`Tangential`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialChecks {
    /// Tangential restitution of the contact point, - (absent without slip at touch).
    pub restitution: Option<Check>,
    /// Rebound angle of ball 1, rad.
    pub rebound_angle: Check,
    /// Ball 1's spin after the impact, rad/s.
    pub spin1_after: Check,
}

impl TangentialChecks {
    /// The checks of the estimate `est` against the level +2 figures `fine`.
    fn of(est: &TangentialEstimate, fine: &Tangential) -> TangentialChecks {
        TangentialChecks {
            restitution: est
                .restitution
                .as_ref()
                .zip(fine.restitution)
                .map(|(e, r)| Check::of(e, r)),
            rebound_angle: Check::of(&est.rebound_angle, fine.rebound_angle),
            spin1_after: Check::of(&est.spin1_after, fine.spin1_after),
        }
    }
}

/// Runs each case on levels −1, 0 and +2 with `run(scene, level)` and checks the estimate;
/// `progress` is told each finished row. Errors of `run` pass through.
pub fn check_honesty(
    cases: &[HonestyCase],
    mut run: impl FnMut(&Scene, i32) -> Result<LevelOutcome>,
    mut progress: impl FnMut(&HonestyRow),
) -> Result<Vec<HonestyRow>> {
    let mut rows = Vec::new();
    for c in cases {
        let coarse = run(&c.scene, -1)?;
        let base = run(&c.scene, 0)?;
        let fine = run(&c.scene, 2)?;
        let est = ErrorEstimate::from_runs(vec![coarse, base], None)?;
        let three_d = crate::study::convergence::bulk_share::runs_in_3d(&c.scene)?;
        let est = crate::study::convergence::bulk_share::with_bulk_share(&c.scene, three_d, est)?;
        let row = HonestyRow {
            material: c.material.clone(),
            speed: c.speed,
            incidence_deg: c.incidence_deg,
            e: Check::of(&est.e, fine.e),
            delta_max: Check::of(&est.delta_max, fine.delta_max),
            contact_duration: Check::of(&est.contact_duration, fine.contact_duration),
            tangential: est
                .tangential
                .as_ref()
                .zip(fine.tangential.as_ref())
                .map(|(t, f)| TangentialChecks::of(t, f)),
            wall_time_s: coarse.wall_time_s + base.wall_time_s + fine.wall_time_s,
        };
        progress(&row);
        rows.push(row);
    }
    Ok(rows)
}

/// The rows as a Markdown table (relative estimate and true error in %, ✓ when honest) with
/// a closing line counting the honest cases per quantity.
pub fn honesty_table(rows: &[HonestyRow]) -> String {
    let mut s = String::from(
        "| material | v per ball (m/s) | e | e: estimate / true error | δ_max: estimate / true error | t_c: estimate / true error | wall (s) |\n|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {:.4} | {} | {} | {} | {:.1} |\n",
            r.material,
            r.speed,
            r.e.value,
            cell(&r.e),
            cell(&r.delta_max),
            cell(&r.contact_duration),
            r.wall_time_s
        ));
    }
    let count = |f: fn(&HonestyRow) -> Check| rows.iter().filter(|r| f(r).honest()).count();
    s.push_str(&format!(
        "\nTrue error within the estimate: e {} of {n}, δ_max {} of {n}, t_c {} of {n}.\n",
        count(|r| r.e),
        count(|r| r.delta_max),
        count(|r| r.contact_duration),
        n = rows.len()
    ));
    s
}

/// A check as a table cell: estimate and true error relative to the value, in %, and ✓ when
/// honest.
fn cell(c: &Check) -> String {
    let pct = |x: f64| 100.0 * x / c.value.abs().max(f64::MIN_POSITIVE);
    format!(
        "{:.3} % / {:.3} % {}",
        pct(c.estimate),
        pct(c.true_error),
        if c.honest() { "✓" } else { "✗" }
    )
}

/// The oblique rows as a Markdown table (each quantity's relative estimate and true error in
/// %, ✓ when honest) with a closing line counting the honest cases per quantity; a row
/// without tangential figures shows dashes there.
pub fn oblique_honesty_table(rows: &[HonestyRow]) -> String {
    let mut s = String::from(
        "| material | incidence (°) | e_t | e_t: estimate / true error | rebound angle | spin after | e | wall (s) |\n|---|---|---|---|---|---|---|---|\n",
    );
    let opt = |c: Option<Check>| c.as_ref().map_or("-".to_string(), cell);
    for r in rows {
        let t = r.tangential.as_ref();
        let restitution = t.and_then(|t| t.restitution);
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {:.1} |\n",
            r.material,
            r.incidence_deg,
            restitution.map_or("-".to_string(), |c| format!("{:.4}", c.value)),
            opt(restitution),
            opt(t.map(|t| t.rebound_angle)),
            opt(t.map(|t| t.spin1_after)),
            cell(&r.e),
            r.wall_time_s
        ));
    }
    let count = |f: &dyn Fn(&HonestyRow) -> Option<Check>| {
        let checks: Vec<Check> = rows.iter().filter_map(f).collect();
        let honest = checks.iter().filter(|c| c.honest()).count();
        format!("{honest} of {}", checks.len())
    };
    s.push_str(&format!(
        "\nTrue error within the estimate: e_t {}, rebound angle {}, spin after {}, e {}.\n",
        count(&|r| r.tangential.and_then(|t| t.restitution)),
        count(&|r| r.tangential.map(|t| t.rebound_angle)),
        count(&|r| r.tangential.map(|t| t.spin1_after)),
        count(&|r| Some(r.e)),
    ));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f(h) = f0 (1 + c h^p), h = 2^−level: honest for p ≥ 1 (the two-level rule's bound).
    fn model(p: f64) -> impl FnMut(&Scene, i32) -> Result<LevelOutcome> {
        move |s: &Scene, level: i32| {
            let h = 2f64.powi(-level);
            let v = s.ball1.velocity[0];
            let f = |f0: f64, c: f64| f0 * (1.0 + c * h.powf(p));
            Ok(LevelOutcome {
                level,
                pole_size: h,
                size: h,
                e: f(0.9 - 0.1 * v, 0.02),
                delta_max: f(1e-5 * v, -0.05),
                contact_duration: f(6e-5, 0.03),
                peak_force: f(1e3, 0.04),
                wall_time_s: 0.0,
                phase: None,
                // An oblique scene (tangential speed) has tangential figures.
                tangential: (s.ball1.velocity[1] != 0.0).then(|| Tangential {
                    restitution: Some(f(0.3, 0.1)),
                    incidence_angle: 0.5,
                    rebound_angle: f(0.4, -0.05),
                    spin1_after: f(-500.0, 0.02),
                    spin1_before: 0.0,
                    spin1_inertia_ratio: None,
                }),
            })
        }
    }

    #[test]
    fn oblique_cases_check_their_tangential_figures() {
        let base = Path::new("verification/dem-benchmarks/test4-alumina.toml");
        let materials = [(
            "alumina",
            "{ E = 3.8e11, nu = 0.23, rho = 4000.0, yield = 1e11, mu = 0.092 }",
        )];
        let cases = oblique_cases(base, &materials, 3.9, &[10.0, 30.0], &[]).unwrap();
        assert_eq!(cases.len(), 2);
        let v = cases[1].scene.ball1.velocity;
        assert!(
            (v[1] / v[0] - 30f64.to_radians().tan()).abs() < 1e-12,
            "{v:?}"
        );
        assert_eq!(cases[1].incidence_deg, 30.0);
        let rows = check_honesty(&cases, model(1.5), |_| ()).unwrap();
        let t = rows[0]
            .tangential
            .expect("oblique rows have tangential checks");
        assert!(t.restitution.unwrap().honest() && t.spin1_after.honest());
        let table = oblique_honesty_table(&rows);
        assert!(
            table.contains("e_t 2 of 2, rebound angle 2 of 2"),
            "{table}"
        );
        // The tangential bars assume order 1 (3 |d₂₁|), which covers any order above 0
        // against level +2; e's assume 2 and miss an order of 0.5. A ladder drifting away on
        // refinement (as past a knee) is missed by both.
        let rows = check_honesty(&cases, model(0.5), |_| ()).unwrap();
        let table = oblique_honesty_table(&rows);
        assert!(
            table.contains("e_t 2 of 2") && table.contains("e 0 of 2"),
            "{table}"
        );
        let rows = check_honesty(&cases, model(-0.5), |_| ()).unwrap();
        assert!(oblique_honesty_table(&rows).contains("e_t 0 of 2"));
        let missing = oblique_cases(Path::new("no/such.toml"), &materials, 3.9, &[10.0], &[]);
        assert!(missing.unwrap_err().to_string().contains("no/such.toml"));
    }

    #[test]
    fn orders_of_one_and_more_are_within_the_estimate_and_below_are_not() {
        let cases =
            honesty_cases(&["copper-fe", "steel"], &[0.1, 1.0], &|_, _| Vec::new()).unwrap();
        assert_eq!(cases.len(), 4);
        assert_eq!(cases[2].scene.ball1.material_name, "steel");
        let mut seen = 0;
        let rows = check_honesty(&cases, model(1.5), |_| seen += 1).unwrap();
        assert_eq!(seen, 4);
        assert!(rows.iter().all(|r| r.e.honest() && r.delta_max.honest()));
        let table = honesty_table(&rows);
        assert!(table.contains("e 4 of 4"), "{table}");
        let rows = check_honesty(&cases, model(0.5), |_| ()).unwrap();
        assert!(rows.iter().all(|r| !r.e.honest()));
        assert!(honesty_table(&rows).contains("e 0 of 4"));
    }
}
