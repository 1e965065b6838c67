//! `twoball static [SCENE] [--support held|free] [--to approach|force|work --value X]
//! [--level L] [--levels 2|3] [--increments N] [--laws] [--out DIR]`: the quasi-static loading and
//! unloading loop of the scene's ball on a rigid plane, with error bars from a mesh ladder.

use crate::analytic::laws::Registry;
use crate::error::{Error, Result};
use crate::mesh::section::band::MAX_SPLIT;
use crate::study::convergence::static_ladder::{
    banded_case, case_of_scene, impact_of_scene, run_loop_ladder, BandPilot, LoopEstimate,
    DEFAULT_BAND_SPLIT, DEFAULT_INCREMENTS, DEFAULT_LEVEL,
};
use crate::study::laws_bench::loops::{csv, laws_on_loop, table, LoopPair};
use crate::study::records::estimate::Estimate;
use crate::study::run::quasi_static::{LoadTo, StaticCase, StaticLoop, Support};
use clap::Args;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Arguments of `twoball static`.
#[derive(Debug, Args)]
pub struct StaticArgs {
    /// Scene file (TOML) of a head-on impact; the built-in default scene when absent.
    pub scene: Option<PathBuf>,
    /// Override a scene value by its dotted path, e.g. --set ball1.material.yield=1e11.
    #[arg(long = "set", value_name = "PATH=VALUE", allow_hyphen_values = true)]
    pub sets: Vec<String>,
    /// How the ball is held: `held` (the hemisphere, its equator on a roller driven towards
    /// the plane; δ its travel) or `free` (the whole ball under the body force that balances
    /// the contact; δ the approach of its centre of mass).
    #[arg(long, default_value = "held")]
    pub support: String,
    /// Where loading stops: `approach` (m), `force` (N) or `work` (J); with --value. Default:
    /// the work of the kinetic energy one ball brings to the plane.
    #[arg(long, requires = "value")]
    pub to: Option<String>,
    /// The value --to stops at (SI: m, N or J).
    #[arg(long, requires = "to")]
    pub value: Option<f64>,
    /// Finest ladder level (0 = six pole cells per Hertz contact radius; each level halves
    /// every length).
    #[arg(long, default_value_t = DEFAULT_LEVEL)]
    pub level: u32,
    /// Levels of the ladder behind the error bars (2 or 3, the finest --level).
    #[arg(long, default_value_t = 2)]
    pub levels: u32,
    /// Increments of loading at level 0 (unloading takes half as many); each level doubles
    /// them.
    #[arg(long, default_value_t = DEFAULT_INCREMENTS)]
    pub increments: usize,
    /// Split the surface rings at the contact edge SPLIT-fold on every level (the edge read
    /// from a plain level-0 loop; an odd split keeps the shells near the surface), or `none`
    /// for the plain ladder.
    #[arg(long, value_name = "SPLIT|none", default_value_t = DEFAULT_BAND_SPLIT.to_string())]
    pub band: String,
    /// Folder for loop.csv (the finest level's loop) and results.json.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Also set every normal contact law's quasi-static curve (default parameters, approach
    /// rate 0) beside the finest loop: RMS force error of loading and unloading; with --out,
    /// laws.csv.
    #[arg(long)]
    pub laws: bool,
}

/// Runs `twoball static`.
pub fn run(a: StaticArgs) -> Result<()> {
    let scene = super::read_scene(a.scene.as_deref(), &a.sets)?;
    let support = Support::from_name(&a.support)
        .ok_or_else(|| Error::invalid("--support", &a.support, Support::NAMES.join(" or ")))?;
    let to = match (a.to.as_deref(), a.value) {
        (None, _) => None,
        (Some("approach"), Some(v)) => Some(LoadTo::Approach(v)),
        (Some("force"), Some(v)) => Some(LoadTo::Force(v)),
        (Some("work"), Some(v)) => Some(LoadTo::Work(v)),
        (Some(t), _) => {
            return Err(Error::invalid("--to", t, "approach, force or work"));
        }
    };
    let split = match a.band.as_str() {
        "none" => None,
        v => Some(v.parse::<usize>().map_err(|_| {
            Error::invalid("--band", v, format!("a split 1..={MAX_SPLIT} or none"))
        })?),
    };
    let case = case_of_scene(&scene, support, to, a.level, a.increments)?;
    let (case, band) = match split {
        Some(split) => {
            let (case, band) = banded_case(&case, split)?;
            (case, Some(band))
        }
        None => (case, None),
    };
    let (loops, est) = run_loop_ladder(&case, a.levels)?;
    let finest = loops.last().expect("at least two levels");
    print!("{}", summary(&case, &loops, &est));
    if let Some(b) = &band {
        println!(
            "  edge band: rings split {}-fold at the contact edge {:.4e} m of the plain level-0 \
             loop ({} quads, {} Newton iterations)",
            b.split, b.edge_m, b.pilot_quads, b.pilot_iterations
        );
    }
    let (speed, wall) = impact_of_scene(&scene)?;
    let pair = LoopPair {
        material: case.material,
        diameter_m: case.diameter,
        rigid_wall: wall,
        approach_speed_m_per_s: speed,
    };
    let laws = if a.laws {
        let laws = laws_on_loop(finest, &pair, &Registry::builtin())?;
        print!("{}", table(&laws));
        Some(laws)
    } else {
        None
    };
    if let Some(dir) = &a.out {
        crate::atomic::ensure_dir(dir)?;
        crate::atomic::write_atomic(dir.join("loop.csv"), loop_csv(finest).as_bytes())?;
        if let Some(laws) = &laws {
            crate::atomic::write_atomic(dir.join("laws.csv"), csv(finest, laws).as_bytes())?;
        }
        let json = results_json(&case, &pair, &loops, &est, band.as_ref())?;
        crate::atomic::write_atomic(dir.join("results.json"), json.as_bytes())?;
        println!("wrote {}", dir.display());
    }
    Ok(())
}

/// The printed table: each number with its bar, and each level's.
fn summary(case: &StaticCase, loops: &[StaticLoop], est: &LoopEstimate) -> String {
    let mut s = String::new();
    let held = match case.support {
        Support::Held => "hemisphere held at its equator (δ: the equator's travel)",
        Support::Free => "free ball under balancing body force (δ: centre-of-mass approach)",
    };
    let _ = writeln!(
        s,
        "quasi-static loop: D = {} m, {} on a rigid frictionless plane, {} quads, to {:?}",
        case.diameter,
        held,
        case.formulation.name(),
        case.to
    );
    let row = |s: &mut String, name: &str, unit: &str, e: &Estimate, f: fn(&StaticLoop) -> f64| {
        let levels: Vec<String> = loops.iter().map(|l| format!("{:.6e}", f(l))).collect();
        let _ = writeln!(
            s,
            "  {name:<22} {:.6e} ± {:.2e} {unit:<3} (levels: {})",
            e.finest,
            e.error,
            levels.join(", ")
        );
    };
    row(&mut s, "delta_max", "m", &est.delta_max, |l| {
        l.summary.delta_max
    });
    row(&mut s, "F(delta_max/2)", "N", &est.force_at_half, |l| {
        l.summary.force_at_half
    });
    row(&mut s, "F(delta_max)", "N", &est.force_at_max, |l| {
        l.summary.force_at_max
    });
    row(
        &mut s,
        "residual approach",
        "m",
        &est.residual_approach,
        |l| l.summary.residual_approach,
    );
    row(&mut s, "work returned", "J", &est.work_returned, |l| {
        l.summary.work_returned
    });
    row(&mut s, "e (quasi-static)", "-", &est.e, |l| l.summary.e);
    row(&mut s, "contact radius", "m", &est.contact_radius, |l| {
        l.summary.contact_radius
    });
    let quads: Vec<String> = loops.iter().map(|l| l.quads.to_string()).collect();
    let iters: Vec<String> = loops.iter().map(|l| l.iterations.to_string()).collect();
    let facts: Vec<String> = loops.iter().map(|l| l.factorisations.to_string()).collect();
    let _ = writeln!(
        s,
        "  quads per level {}, Newton iterations {} (factorisations, every attempt: {})",
        quads.join(", "),
        iters.join(", "),
        facts.join(", ")
    );
    if let Some(last) = loops.last() {
        let r: Vec<String> = last
            .peak_residuals
            .iter()
            .map(|r| format!("{r:.1e}"))
            .collect();
        let _ = writeln!(
            s,
            "  Newton at the peak (finest level), relative residual before each iteration: {}",
            r.join(", ")
        );
    }
    s
}

/// loop.csv: the loading then the unloading points.
fn loop_csv(l: &StaticLoop) -> String {
    let mut s =
        String::from("phase,approach_m,force_N,contact_radius_m,plastic_work_J,stress_work_J\n");
    for (phase, points) in [("loading", &l.loading), ("unloading", &l.unloading)] {
        for p in points.iter() {
            let _ = writeln!(
                s,
                "{phase},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}",
                p.approach, p.force, p.contact_radius, p.plastic_work, p.stress_work
            );
        }
    }
    s
}

/// results.json: the case, the pair it stands for (what `laws fit --against-static` reads),
/// the estimates and each level's summary (SI units; keys name them).
fn results_json(
    case: &StaticCase,
    pair: &LoopPair,
    loops: &[StaticLoop],
    est: &LoopEstimate,
    band: Option<&BandPilot>,
) -> Result<String> {
    let levels: Vec<serde_json::Value> = loops
        .iter()
        .map(|l| {
            serde_json::json!({
                "quads": l.quads,
                "newton_iterations": l.iterations,
                "factorisations": l.factorisations,
                "peak_residuals": l.peak_residuals,
                "summary": l.summary,
            })
        })
        .collect();
    let v = serde_json::json!({
        "units": "SI: approach and radius m, force N, work J",
        "diameter_m": case.diameter,
        "contact_pair": pair,
        "support": case.support,
        "element": case.formulation,
        "load_to": case.to,
        "finest_level": case.level,
        "band": band,
        "estimate": est,
        "levels": levels,
    });
    serde_json::to_string_pretty(&v).map_err(|e| Error::Numerical(format!("results.json: {e}")))
}
