//! The section model's converged head-on answer (`study::convergence::phase_ensemble::converged_head_on`)
//! for two identical balls: the ensembles of family levels LEVEL − 1 and LEVEL, member by
//! member, and the answer with its error bars (verification/contact-penalty.md, "The section's
//! converged answer").
//!
//! `cargo run --release --example phase_ensemble -- LEVEL MESHES V_REL [MATERIAL] [one-point|b-bar|full] [D]`
//! (LEVEL −2..7, MESHES even, V_REL the relative speed in m/s, MATERIAL a preset, default
//! copper-fe, D the diameter in m, default 0.02). `PHASE_CONTACT=nodal` enforces the symmetry
//! plane by the penalty springs instead of the kinematic constraint. `PHASE_ONLY=1` runs the
//! ensemble of LEVEL alone (no coarse ensemble, no bar): the deep levels of a ladder. With
//! `PHASE_RING_AT=R` (µm) as well, the ring ratio q is read at the contact radius R instead
//! of from a pilot run, and all members run at once (`ensemble_at_radius`). `PHASE_BAND=SPLIT`
//! runs the banded family instead (`study::convergence::phase_band`: the surface rings at the contact edge
//! of a level-0 run split SPLIT-fold; LEVEL ≥ 1). `PHASE_MASS_SCALING=BUDGET` mass-scales
//! every run within BUDGET (added mass over the section's; `fe::section::mass_scaling`).
//! `PHASE_SUBCYCLE_MAX_LEVEL=K` caps the subcycling at level K instead of the section's
//! default 2 (`twoball run --tolerance` runs its family with K = 3).

use twoball::fe::elements::ring::QuadFormulation;
use twoball::fe::subcycle::Integration;
use twoball::material::Material;
use twoball::study::convergence::phase_ensemble::{
    converged_head_on, ensemble_at, ensemble_at_radius, HeadOnCase, HeadOnTarget, PhaseEnsemble,
    PhasePlan,
};
use twoball::study::run::section_impact::PlaneContact;

/// Argument `i` parsed, or `default` when absent.
fn arg<T: std::str::FromStr>(
    args: &[String],
    i: usize,
    what: &str,
    default: Option<T>,
) -> Result<T, String> {
    match (args.get(i), default) {
        (Some(s), _) => s
            .parse()
            .map_err(|_| format!("argument {i} ({what}): {s:?} is not valid")),
        (None, Some(d)) => Ok(d),
        (None, None) => Err(format!(
            "argument {i} ({what}) is missing: LEVEL MESHES V_REL [MATERIAL] [one-point|b-bar|full] [D]"
        )),
    }
}

/// Prints the members of `en` and its means, headed by `label`.
fn print_ensemble(label: &str, en: &PhaseEnsemble) {
    println!("{label} ensemble: ring ratio q {:.4}", en.ring_ratio);
    for r in &en.runs {
        println!(
            "  s {:.4}: e {:.5}, δ_max {:.4} µm, t_c {:.3} µs, F_peak {:.1} N, contact radius {:.1} µm, energy error {:.1e}, {:.2} s",
            r.scale, r.e, r.delta_max * 1e6, r.contact_duration * 1e6, r.peak_force,
            r.contact_radius * 1e6, r.energy_error, r.wall_time_s
        );
    }
    println!(
        "  mean: e {:.5} (sampling error {:.1e}, members {:.5}-{:.5}), δ_max {:.4} µm, t_c {:.3} µs",
        en.e.mean, en.e.sampling_error, en.e.min, en.e.max,
        en.delta_max.mean * 1e6, en.contact_duration.mean * 1e6
    );
}

fn run(args: &[String]) -> Result<(), String> {
    let level: i32 = arg(args, 1, "LEVEL", None)?;
    let meshes: usize = arg(args, 2, "MESHES", None)?;
    let v: f64 = arg(args, 3, "V_REL", None)?;
    let name: String = arg(args, 4, "MATERIAL", Some("copper-fe".to_string()))?;
    let formulation = match args.get(5) {
        None => QuadFormulation::default(),
        Some(o) => QuadFormulation::from_name(o).ok_or_else(|| {
            format!(
                "argument 5: {o:?} is not one of {}",
                QuadFormulation::NAMES.join(", ")
            )
        })?,
    };
    let diameter: f64 = arg(args, 6, "D", Some(0.02))?;
    let material = Material::preset(&name).map_err(|e| e.to_string())?;
    let case = HeadOnCase {
        diameter,
        material,
        relative_speed: v,
        target: HeadOnTarget::IdenticalBall,
        formulation,
        plane: match std::env::var("PHASE_CONTACT").as_deref() {
            Ok("nodal") => PlaneContact::Nodal,
            _ => PlaneContact::Kinematic,
        },
        mass_scaling: match std::env::var("PHASE_MASS_SCALING") {
            Ok(b) => b
                .parse()
                .map_err(|_| format!("PHASE_MASS_SCALING: {b:?} is not a budget"))?,
            Err(_) => 0.0,
        },
        integration: match std::env::var("PHASE_SUBCYCLE_MAX_LEVEL") {
            Ok(k) => Integration::Subcycled {
                max_level: k
                    .parse()
                    .map_err(|_| format!("PHASE_SUBCYCLE_MAX_LEVEL: {k:?} is not a level"))?,
            },
            Err(_) => Integration::subcycled(),
        },
    };
    if std::env::var("PHASE_ONLY").as_deref() == Ok("1") {
        let en = match std::env::var("PHASE_RING_AT") {
            Ok(r) => {
                let r: f64 = r
                    .parse()
                    .map_err(|_| format!("PHASE_RING_AT: {r:?} is not a radius in µm"))?;
                ensemble_at_radius(&case, level, meshes, r * 1e-6)
            }
            Err(_) => ensemble_at(&case, level, meshes).map(|(en, _)| en),
        }
        .map_err(|e| e.to_string())?;
        print_ensemble(&format!("level {level}"), &en);
        let cpu: f64 = en.runs.iter().map(|r| r.wall_time_s).sum();
        println!("{cpu:.1} s CPU");
        return Ok(());
    }
    let band = match std::env::var("PHASE_BAND") {
        Ok(b) => Some(
            b.parse::<usize>()
                .map_err(|_| format!("PHASE_BAND: {b:?} is not a split (1-16)"))?,
        ),
        Err(_) => None,
    };
    let plan = PhasePlan {
        level,
        meshes,
        band,
        ..PhasePlan::default()
    };
    let ans = converged_head_on(&case, &plan).map_err(|e| e.to_string())?;
    if let Some(edge) = ans.band_edge {
        println!(
            "edge band: split {}, around the contact edge {:.1} µm",
            band.unwrap_or(1),
            edge * 1e6
        );
    }
    for (label, en) in [("coarse", &ans.coarse), ("fine", &ans.fine)] {
        print_ensemble(label, en);
    }
    let pct = |b: &twoball::study::records::estimate::Estimate| {
        100.0 * b.relative_error.unwrap_or(f64::NAN)
    };
    println!(
        "e {:.5} ± {:.5} ({:.2} %); δ_max {:.4} µm ± {:.2} %; t_c {:.3} µs ± {:.2} %; F_peak {:.1} N ± {:.2} %; {:.1} s CPU",
        ans.e.finest, ans.e.error, pct(&ans.e), ans.delta_max.finest * 1e6, pct(&ans.delta_max),
        ans.contact_duration.finest * 1e6, pct(&ans.contact_duration), ans.peak_force.finest,
        pct(&ans.peak_force), ans.cpu_time_s
    );
    Ok(())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Err(e) = run(&args) {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}
