//! Run time against error (`twoball bench study`): one scene on a ladder of meshes, element
//! formulations and time-step factors, each run's error in e and δ_max taken against a
//! Richardson-extrapolated reference, so a researcher can pick the cheapest setting that
//! reaches a given accuracy.
//!
//! The mesh ladder refines the scene's graded mesh uniformly: level m has bulk size D/(10 m)
//! and pole size D/(100 m) (the default mesh is m = 1), so the grading ratio stays 10 and
//! h ∝ 1/m. The three finest ladder levels in constant ratio r give each quantity's observed
//! order and extrapolated value by the project's one estimate
//! ([`crate::study::records::estimate`], Roache 1998, ch. 5). When the differences change
//! sign (not yet in the asymptotic range) or the order falls outside
//! [`ORDER_RANGE`](crate::study::records::estimate::ORDER_RANGE), no extrapolation is made:
//! the finest value is the reference, marked as such.
//!
//! Because the contact patch is resolved only by the pole elements, the error in e is
//! governed mostly by the pole size; extra "pole refinement" runs (pole size D/(100 m k) at
//! the middle density) show what a finer pole alone buys, judged against the same reference.

pub mod dem;
pub mod kernel;
pub mod machine;
pub mod profile;
pub mod robustness;

use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use crate::scene::{Formulation, Override, Scene};
use crate::study::common::plots::{Chart, Series, Style};
use crate::study::records::case_cache::{CaseCache, Layout};
use crate::study::records::estimate::{estimate, Estimate};
use crate::study::run::scene::run_scene;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::Path;

/// One configuration of the ladder.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Setting {
    /// Mesh density multiplier m (bulk size D/(10 m), pole size D/(100 m)).
    pub density: f64,
    /// Element formulation.
    pub element: Formulation,
    /// Time-step safety factor.
    pub time_step_factor: f64,
    /// Extra pole refinement k (pole size D/(100 m k)); 1 on the mesh ladder.
    #[serde(default = "one")]
    pub pole_refinement: f64,
}

fn one() -> f64 {
    1.0
}

impl Setting {
    /// A short label, e.g. `one-point m=1.41 s=0.9`.
    pub fn label(&self) -> String {
        let pole = self.pole_tag(|k| format!(" pole/{k}"));
        format!(
            "{} m={:.3}{pole} s={}",
            element_name(self.element),
            self.density,
            self.time_step_factor
        )
    }

    fn file_stem(&self) -> String {
        let pole = self.pole_tag(|k| format!("_k{k:.3}"));
        format!(
            "{}_m{:.4}{pole}_s{:.3}",
            element_name(self.element),
            self.density,
            self.time_step_factor
        )
    }

    /// Bulk element size over diameter, D/(10 m) / D.
    pub fn bulk_size_per_d(&self) -> f64 {
        0.1 / self.density
    }

    /// Pole element size over diameter, D/(100 m k) / D.
    pub fn pole_size_per_d(&self) -> f64 {
        0.01 / (self.density * self.pole_refinement)
    }

    /// Whether this setting is a level of the mesh ladder (no extra pole refinement).
    fn on_ladder(&self) -> bool {
        self.pole_refinement == 1.0
    }

    /// Nothing on the mesh ladder, else `tag` of the extra pole refinement k.
    fn pole_tag(&self, tag: impl FnOnce(f64) -> String) -> String {
        if self.on_ladder() {
            String::new()
        } else {
            tag(self.pole_refinement)
        }
    }
}

fn element_name(f: Formulation) -> &'static str {
    f.name()
}

/// What one run of the ladder measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Measured {
    /// The configuration.
    pub setting: Setting,
    /// Elements simulated (after symmetry reduction).
    pub elements: usize,
    /// Element updates.
    pub element_cycles: u64,
    /// Wall time of the FE run, s.
    pub wall_time_s: f64,
    /// Coefficient of restitution.
    pub e: f64,
    /// Largest approach, m.
    pub delta_max: f64,
    /// Contact duration, s.
    pub contact_duration: f64,
    /// Energy error (relative).
    pub energy_error: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Ladder {
    /// Mesh densities m, ascending, in constant ratio (at least 3).
    pub densities: Vec<f64>,
    /// Element formulations run on every density.
    pub elements: Vec<Formulation>,
    /// Extra time-step factors run on the middle density of the ladder (m = 1 for the
    /// default ladder) with the first formulation.
    pub time_step_factors: Vec<f64>,
    /// Time-step factor of the mesh ladder.
    pub base_factor: f64,
    /// Extra pole refinements k (pole size D/(100 m k)) run on the middle density with the
    /// first formulation and the base factor.
    pub pole_refinements: Vec<f64>,
}

impl Ladder {
    /// The `twoball bench study` command that runs this ladder (its folder `DIR`).
    pub fn command(&self) -> String {
        let list = |v: &[f64]| {
            v.iter()
                .map(|x| format!("{x}"))
                .collect::<Vec<_>>()
                .join(",")
        };
        let elements: Vec<&str> = self.elements.iter().map(|&f| element_name(f)).collect();
        format!(
            "twoball bench study --out DIR --densities {} --elements {} --time-step-factor {} \
             --time-step-factors {} --pole-refinements {}",
            list(&self.densities),
            elements.join(","),
            self.base_factor,
            list(&self.time_step_factors),
            list(&self.pole_refinements)
        )
    }

    /// Checks the ladder, naming the bad field.
    pub fn validated(self) -> Result<Self> {
        if self.densities.len() < 3 {
            return Err(Error::invalid(
                "--densities",
                format!("{:?}", self.densities),
                "at least 3 densities (Richardson needs three meshes)",
            ));
        }
        if !self
            .densities
            .iter()
            .all(|m| m.is_finite() && (0.2..=4.0).contains(m))
            || !self.densities.windows(2).all(|w| w[1] > w[0])
        {
            return Err(Error::invalid(
                "--densities",
                format!("{:?}", self.densities),
                "ascending values in 0.2..=4",
            ));
        }
        let n = self.densities.len();
        let r1 = self.densities[n - 1] / self.densities[n - 2];
        let r2 = self.densities[n - 2] / self.densities[n - 3];
        if (r1 / r2 - 1.0).abs() > 0.02 {
            return Err(Error::invalid(
                "--densities",
                format!("{:?}", self.densities),
                "the three finest in a constant ratio (within 2 %)",
            ));
        }
        if self.elements.is_empty() {
            return Err(Error::invalid(
                "--elements",
                "none",
                "one-point and/or b-bar",
            ));
        }
        for &s in self.time_step_factors.iter().chain([&self.base_factor]) {
            if !(s > 0.0 && s <= 1.0) {
                return Err(Error::invalid("--time-step-factors", s, "0 < factor <= 1"));
            }
        }
        for &k in &self.pole_refinements {
            if !(k.is_finite() && (1.0..=8.0).contains(&k)) {
                return Err(Error::invalid("--pole-refinements", k, "1 <= k <= 8"));
            }
        }
        Ok(self)
    }

    /// Every setting to run, in order.
    pub fn settings(&self) -> Vec<Setting> {
        let mut out = Vec::new();
        for &element in &self.elements {
            for &density in &self.densities {
                out.push(Setting {
                    density,
                    element,
                    time_step_factor: self.base_factor,
                    pole_refinement: 1.0,
                });
            }
        }
        for &s in &self.time_step_factors {
            if s != self.base_factor {
                out.push(Setting {
                    density: self.densities[self.densities.len() / 2],
                    element: self.elements[0],
                    time_step_factor: s,
                    pole_refinement: 1.0,
                });
            }
        }
        for &k in &self.pole_refinements {
            if k != 1.0 {
                out.push(Setting {
                    density: self.densities[self.densities.len() / 2],
                    element: self.elements[0],
                    time_step_factor: self.base_factor,
                    pole_refinement: k,
                });
            }
        }
        out
    }
}

/// The scene with one ladder setting applied to both balls, on the 3D model (the hex
/// meshes of the ladder; `reduction.symmetry = "auto"` runs as `"auto-3d"`).
pub fn scene_for(base: &Scene, toml: &str, dir: &Path, s: &Setting) -> Result<Scene> {
    let mut sets = Vec::new();
    for (k, b) in [(1, &base.ball1), (2, &base.ball2)] {
        let size = b.diameter * s.bulk_size_per_d();
        let pole = b.diameter * s.pole_size_per_d();
        sets.push(Override::parse(&format!(
            "ball{k}.mesh={{size={size:e},pole_size={pole:e}}}"
        ))?);
    }
    sets.push(Override::parse(&format!(
        "solver.element=\"{}\"",
        element_name(s.element)
    ))?);
    sets.push(Override::parse(&format!(
        "solver.time_step_factor={}",
        s.time_step_factor
    ))?);
    let mut scene = Scene::from_toml(toml, dir, &sets)?;
    scene.reduction.symmetry = scene.reduction.symmetry.three_d();
    Ok(scene)
}

/// Runs (or reads back from `dir/cases/`) every setting of `ladder` on the scene `toml`
/// (read relative to `scene_dir`), calling `progress` after each. Each finished case is
/// stored atomically, so an interrupted bench resumes where it stopped.
///
/// Errors: scene errors, FE failures (naming the setting), I/O errors.
pub fn run_settings(
    toml: &str,
    scene_dir: &Path,
    ladder: &Ladder,
    dir: &Path,
    mut progress: impl FnMut(&Measured, bool),
) -> Result<Vec<Measured>> {
    let base = Scene::from_toml(toml, scene_dir, &[])?;
    let cases = CaseCache::new(dir.join("cases"));
    ensure_dir(cases.dir())?;
    let mut out = Vec::new();
    for s in ladder.settings() {
        let key = s.file_stem();
        if let Some(m) = cases.read(&key, |m: &Measured| m.setting == s) {
            progress(&m, true);
            out.push(m);
            continue;
        }
        let scene = scene_for(&base, toml, scene_dir, &s)?;
        let opts = crate::study::run::simulate::RunOptions {
            history_rows: 400,
            ..Default::default()
        };
        let report = run_scene(&scene, &opts)
            .map_err(|e| Error::Numerical(format!("bench study, {}: {e}", s.label())))?;
        let fe = report
            .fe
            .as_ref()
            .ok_or_else(|| Error::invalid("scene", "no impact", "a scene whose balls collide"))?;
        let m = Measured {
            setting: s,
            elements: fe.elements,
            element_cycles: fe.element_cycles,
            wall_time_s: fe.wall_time_s,
            e: fe.outcome.e,
            delta_max: fe.outcome.delta_max,
            contact_duration: fe.outcome.contact_duration,
            energy_error: fe.energy_error,
        };
        cases.write(&key, &m, Layout::Pretty)?;
        progress(&m, false);
        out.push(m);
    }
    Ok(out)
}

/// References of e, δ_max and contact duration from the three finest meshes of the first
/// formulation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct References {
    /// Formulation whose ladder gave the references.
    pub element: Formulation,
    /// Refinement ratio r of the three finest meshes.
    pub ratio: f64,
    /// Coefficient of restitution (its `extrapolated` value is the reference).
    pub e: Estimate,
    /// Largest approach, m.
    pub delta_max: Estimate,
    /// Contact duration, s.
    pub contact_duration: Estimate,
}

/// Whether a reference is extrapolated (a monotone ladder within the trusted orders, or one
/// already settled); otherwise it is the finest mesh's value.
fn reference_is_extrapolated(x: &Estimate) -> bool {
    x.behaviour.is_asymptotic()
}

/// Richardson references from the ladder runs of formulation `element` at base factor.
///
/// Errors: fewer than three such runs, or a quantity of theirs that is not finite.
pub fn references(runs: &[Measured], ladder: &Ladder, element: Formulation) -> Result<References> {
    let mut l: Vec<&Measured> = runs
        .iter()
        .filter(|m| {
            m.setting.element == element
                && m.setting.time_step_factor == ladder.base_factor
                && m.setting.on_ladder()
        })
        .collect();
    l.sort_by(|a, b| a.setting.density.total_cmp(&b.setting.density));
    if l.len() < 3 {
        return Err(Error::invalid(
            "bench study",
            format!("{} runs of {}", l.len(), element_name(element)),
            "three mesh levels",
        ));
    }
    let t = &l[l.len() - 3..];
    let ratio = t[2].setting.density / t[1].setting.density;
    let q = |f: fn(&Measured) -> f64, what: &str| {
        estimate(&[f(t[0]), f(t[1]), f(t[2])], ratio).ok_or_else(|| {
            Error::Numerical(format!(
                "bench study: {what} of the three finest meshes is not finite"
            ))
        })
    };
    Ok(References {
        element,
        ratio,
        e: q(|m| m.e, "e")?,
        delta_max: q(|m| m.delta_max, "delta_max")?,
        contact_duration: q(|m| m.contact_duration, "contact duration")?,
    })
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The table (CSV, SI units in the header) of every run with its errors against `r`.
pub fn csv(runs: &[Measured], r: &References) -> String {
    let mut s = String::from(
        "element,density_m,bulk_size_per_d,pole_size_per_d,time_step_factor,elements,element_cycles,wall_time_s,e,delta_max_m,contact_duration_s,energy_error,err_e_rel,err_delta_max_rel,err_duration_rel\n",
    );
    for m in runs {
        let st = &m.setting;
        let _ = writeln!(
            s,
            "{},{},{:.6e},{:.6e},{},{},{},{:.4},{:.7e},{:.7e},{:.7e},{:.3e},{:.4e},{:.4e},{:.4e}",
            element_name(st.element),
            st.density,
            st.bulk_size_per_d(),
            st.pole_size_per_d(),
            st.time_step_factor,
            m.elements,
            m.element_cycles,
            m.wall_time_s,
            m.e,
            m.delta_max,
            m.contact_duration,
            m.energy_error,
            rel(m.e, r.e.extrapolated),
            rel(m.delta_max, r.delta_max.extrapolated),
            rel(m.contact_duration, r.contact_duration.extrapolated),
        );
    }
    s
}

/// The fastest run whose error in e is at most `tol` (relative), if any.
pub fn fastest_within<'a>(runs: &'a [Measured], r: &References, tol: f64) -> Option<&'a Measured> {
    runs.iter()
        .filter(|m| rel(m.e, r.e.extrapolated) <= tol)
        .min_by(|a, b| a.wall_time_s.total_cmp(&b.wall_time_s))
}

/// A Markdown summary: references, the table, the fastest setting within 1 % in e.
pub fn markdown(runs: &[Measured], refs: &[References]) -> String {
    let r = &refs[0];
    let mut s = String::new();
    let ext = |name: &str, x: &Estimate, unit: &str| {
        format!(
            "| {name} | {:.6e} {unit} | {:.2} | {} |\n",
            x.extrapolated,
            x.observed_order.unwrap_or(f64::NAN),
            if reference_is_extrapolated(x) {
                "yes"
            } else {
                "no: reference = finest mesh"
            }
        )
    };
    for rr in refs {
        let _ = writeln!(
            s,
            "Richardson references from the three finest {} meshes (ratio r = {:.3}):\n",
            element_name(rr.element),
            rr.ratio
        );
        s.push_str(
            "| quantity | extrapolated | observed order p | asymptotic |\n|---|---|---|---|\n",
        );
        s.push_str(&ext("e", &rr.e, ""));
        s.push_str(&ext("delta_max", &rr.delta_max, "m"));
        s.push_str(&ext("contact duration", &rr.contact_duration, "s"));
        s.push('\n');
    }
    let _ = writeln!(
        s,
        "Errors below are against the {} references.\n",
        element_name(r.element)
    );
    s.push_str("| element | m | bulk size / D | pole size / D | time-step factor | elements | element-cycles | wall (s) | e | err e | err delta_max | err duration | energy err |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for m in runs {
        let st = &m.setting;
        let _ = writeln!(
            s,
            "| {} | {:.3} | 1/{:.0} | 1/{:.0} | {} | {} | {:.3e} | {:.2} | {:.5} | {:.2} % | {:.2} % | {:.2} % | {:.1e} |",
            element_name(st.element),
            st.density,
            1.0 / st.bulk_size_per_d(),
            1.0 / st.pole_size_per_d(),
            st.time_step_factor,
            m.elements,
            m.element_cycles as f64,
            m.wall_time_s,
            m.e,
            100.0 * rel(m.e, r.e.extrapolated),
            100.0 * rel(m.delta_max, r.delta_max.extrapolated),
            100.0 * rel(m.contact_duration, r.contact_duration.extrapolated),
            m.energy_error
        );
    }
    match fastest_within(runs, r, 0.01) {
        Some(m) => {
            let _ = writeln!(
                s,
                "\nFastest setting within 1 % in e: {} ({} elements), {:.2} s wall, error in e {:.2} %.",
                m.setting.label(),
                m.elements,
                m.wall_time_s,
                100.0 * rel(m.e, r.e.extrapolated)
            );
        }
        None => s.push_str("\nNo setting of this ladder reaches 1 % in e.\n"),
    }
    s
}

/// Wall time against error in e and δ_max, log10-log10 (SVG).
///
/// Errors: plotting failures.
pub fn chart(runs: &[Measured], r: &References) -> Result<String> {
    let mut series = Vec::new();
    let mut groups: Vec<(Formulation, f64, bool)> = Vec::new();
    for m in runs {
        let g = (
            m.setting.element,
            m.setting.time_step_factor,
            m.setting.on_ladder(),
        );
        if !groups.contains(&g) {
            groups.push(g);
        }
    }
    for (q, name) in [(0, "e"), (1, "delta_max")] {
        for &(el, f, ladder) in &groups {
            let points = runs
                .iter()
                .filter(|m| {
                    m.setting.element == el
                        && m.setting.time_step_factor == f
                        && m.setting.on_ladder() == ladder
                })
                .map(|m| {
                    let err = if q == 0 {
                        rel(m.e, r.e.extrapolated)
                    } else {
                        rel(m.delta_max, r.delta_max.extrapolated)
                    };
                    (m.wall_time_s.max(1e-3).log10(), err.max(1e-6).log10())
                })
                .collect();
            series.push(Series {
                label: format!(
                    "{name}: {} s={f}{}",
                    element_name(el),
                    if ladder { "" } else { " finer pole" }
                ),
                points,
                style: Style::Points,
            });
        }
    }
    Chart {
        title: "run time against error (Richardson reference)".into(),
        x_label: "log10 wall time (s)".into(),
        y_label: "log10 relative error".into(),
        series,
    }
    .svg()
}

/// Writes `bench-study.csv`, `bench-study.md` and `bench-study.svg` into `dir`, atomically.
///
/// Errors: I/O and plotting failures; fewer than three mesh levels of the first formulation.
pub fn write_outputs(runs: &[Measured], ladder: &Ladder, dir: &Path) -> Result<String> {
    let mut refs = Vec::new();
    for &el in &ladder.elements {
        refs.push(references(runs, ladder, el)?);
    }
    write_atomic(dir.join("bench-study.csv"), csv(runs, &refs[0]).as_bytes())?;
    let md = format!(
        "Written by `{}`.\n\n{}",
        ladder.command(),
        markdown(runs, &refs)
    );
    write_atomic(dir.join("bench-study.md"), md.as_bytes())?;
    write_atomic(
        dir.join("bench-study.svg"),
        chart(runs, &refs[0])?.as_bytes(),
    )?;
    Ok(md)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_order_ladder_gives_an_extrapolated_reference() {
        // q(h) = 2 + 3 h² on h = 1, 1/2, 1/4.
        let x = estimate(&[5.0, 2.75, 2.1875], 2.0).unwrap();
        assert!((x.observed_order.unwrap() - 2.0).abs() < 1e-12);
        assert!((x.extrapolated - 2.0).abs() < 1e-12);
        assert!(reference_is_extrapolated(&x));
    }

    #[test]
    fn an_oscillating_ladder_gives_the_finest_value() {
        let x = estimate(&[1.0, 1.2, 1.1], 2.0).unwrap();
        assert!(!reference_is_extrapolated(&x));
        assert!(x.observed_order.is_none());
        assert_eq!(x.extrapolated, 1.1);
    }

    #[test]
    fn ladder_needs_three_levels_in_constant_ratio() {
        let l = Ladder {
            densities: vec![0.5, 1.0, 1.5],
            elements: vec![Formulation::OnePoint],
            time_step_factors: vec![],
            base_factor: 0.9,
            pole_refinements: vec![],
        };
        assert!(l.validated().is_err());
    }
}
