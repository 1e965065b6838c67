//! Command-line interface: one file per subcommand; this file only dispatches.
//!
//! Every failure is printed as one line `error: …` on stderr with exit code 1 (2 for
//! malformed flags, as clap does); nothing panics on user input. Ctrl-C during `run`,
//! `sweep` or `stress` prints one line `interrupted at …` saying what was written, and exits
//! with 130. Negative numbers are values everywhere (`--diameter -0.02` reaches the range
//! check).

mod analytic;
mod bench;
mod bench_profile;
mod bench_study;
mod damper;
mod law_params;
mod laws;
mod laws_export;
mod laws_fit;
mod laws_mbf;
mod mesh;
mod report;
mod run;
mod static_loop;
mod stress;
mod sweep;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

pub use laws::main_with as laws_main_with;

/// twoball: finite-element verifier for the collision of two elastic-plastic balls.
#[derive(Debug, Parser)]
#[command(name = "twoball", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Analytical three-phase collision model (Li, Yang & Shi 2019) for two balls.
    Analytic(analytic::AnalyticArgs),
    /// Table 1: particle damping index and energy dissipation factor of nine materials.
    Materials(analytic::MaterialsArgs),
    /// Parametric studies (paper Figures 11-14) as CSV and SVG.
    Parametric(analytic::ParametricArgs),
    /// Ball meshes: generate, check, run gmsh.
    Mesh(mesh::MeshArgs),
    /// One scene: FE beside the analytical model (default: the paper's Figure 8 case).
    Run(run::RunArgs),
    /// A parameter sweep (e.g. the paper's ANSYS study): resumable, shardable, one CSV.
    Sweep(sweep::SweepArgs),
    /// Benchmarks: `bench kernel` (explicit step cost per element, threads, determinism),
    /// `bench study` (run time against error).
    Bench(bench::BenchArgs),
    /// The verification report (REPORT.md, CSV, Figures 6-10) from a finished sweep.
    Report(report::ReportArgs),
    /// Stability matrix of extreme scenes: every case completes cleanly or stops with a reason.
    Stress(stress::StressArgs),
    /// Contact laws: list them, `laws run` one impact under a law, `laws fit` calibrate one.
    Laws(laws::LawsArgs),
    /// Particle damper: the frame's free decay with balls in the box (paper Section 6).
    Damper(damper::DamperArgs),
    /// The quasi-static loading-unloading loop of the scene's ball on a rigid plane, by the
    /// implicit static solver, with error bars from a mesh ladder.
    #[command(name = "static")]
    Static(static_loop::StaticArgs),
}

/// The scene file `path` (the built-in default scene when `None`) with the `--set`
/// overrides `sets` applied.
fn read_scene(
    path: Option<&std::path::Path>,
    sets: &[String],
) -> crate::error::Result<crate::scene::Scene> {
    use crate::scene::{Override, Scene, DEFAULT_SCENE};
    let sets = sets
        .iter()
        .map(|s| Override::parse(s))
        .collect::<crate::error::Result<Vec<_>>>()?;
    match path {
        Some(p) => Scene::from_file(p, &sets),
        None => Scene::from_toml(DEFAULT_SCENE, std::path::Path::new("."), &sets),
    }
}

/// Whether `arg` takes a number (its value parser is that of a numeric type).
fn takes_number(arg: &clap::Arg) -> bool {
    let id = arg.get_value_parser().type_id();
    let of = |p: clap::builder::ValueParser| p.type_id();
    [
        of(clap::value_parser!(f64).into()),
        of(clap::value_parser!(usize).into()),
        of(clap::value_parser!(u64).into()),
        of(clap::value_parser!(u32).into()),
        of(clap::value_parser!(i64).into()),
    ]
    .contains(&id)
}

/// `cmd` and all its subcommands reading `-0.02` and `-2e-3` as values of numeric flags,
/// never as flags: a negative number reaches the range check, which names the flag and the
/// allowed range.
fn negative_numbers_everywhere(cmd: clap::Command) -> clap::Command {
    cmd.allow_negative_numbers(true)
        .mut_args(|a| {
            if takes_number(&a) {
                a.allow_hyphen_values(true)
            } else {
                a
            }
        })
        .mut_subcommands(negative_numbers_everywhere)
}

/// The JSON object of `twoball ARGS --json` without a process (the first of `args` is the
/// program name): `analytic`, `materials` and `laws run` give what they print with `--json`,
/// `laws` the list of laws. Bad input is the error the command would print (one line); how
/// library callers such as the Python binding get the CLI's results and messages.
pub fn json_from<I, T>(args: I) -> crate::Result<serde_json::Value>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = negative_numbers_everywhere(Cli::command())
        .try_get_matches_from(args)
        .and_then(|m| Cli::from_arg_matches(&m))
        .map_err(|e| {
            let text = e.to_string();
            let line = text.lines().next().unwrap_or_default();
            crate::Error::Parse(line.trim_start_matches("error: ").to_string())
        })?;
    let registry = crate::analytic::laws::Registry::builtin();
    match cli.command {
        Command::Analytic(a) => analytic::analytic_json(&a),
        Command::Materials(_) => analytic::materials_json(),
        Command::Laws(laws::LawsArgs {
            command: None | Some(laws::LawsCommand::List),
        }) => laws::list_json(&registry),
        Command::Laws(laws::LawsArgs {
            command: Some(laws::LawsCommand::Run(r)),
        }) => laws::law_run_json(&r, &registry),
        _ => Err(crate::Error::Parse(
            "only analytic, materials, laws and laws run give a JSON object".into(),
        )),
    }
}

/// Prints a command-line parsing outcome and returns its exit code: help and version as clap
/// writes them; a usage error as one line `error: ...` with exit code 1, as every other error.
fn usage_error(e: &clap::Error) -> i32 {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            e.exit_code()
        }
        _ => {
            let text = e.to_string();
            let line = text.lines().next().unwrap_or_default();
            eprintln!("error: {}", line.trim_start_matches("error: "));
            1
        }
    }
}

/// Runs the command line and returns the process exit code.
pub fn main() -> i32 {
    main_from(std::env::args_os())
}

/// Runs the command line `args` (the first is the program name) and returns the exit code:
/// [`main`] without the process's own arguments (the `benches/` harnesses call it).
pub fn main_from<I, T>(args: I) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let parsed = negative_numbers_everywhere(Cli::command())
        .try_get_matches_from(args)
        .and_then(|m| Cli::from_arg_matches(&m));
    let cli = match parsed {
        Ok(c) => c,
        Err(e) => return usage_error(&e),
    };
    if matches!(
        cli.command,
        Command::Run(_) | Command::Sweep(_) | Command::Stress(_) | Command::Damper(_)
    ) {
        crate::study::common::interrupt::install();
    }
    let dispatch = move || match cli.command {
        Command::Analytic(a) => analytic::run_analytic(a),
        Command::Materials(a) => analytic::run_materials(a),
        Command::Parametric(a) => analytic::run_parametric(a),
        Command::Mesh(a) => mesh::run(a),
        Command::Run(a) => run::run(a),
        Command::Static(a) => static_loop::run(a),
        Command::Sweep(a) => sweep::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Report(a) => report::run(a),
        Command::Stress(a) => stress::run(a),
        Command::Laws(a) => laws::run(a),
        Command::Damper(a) => damper::run(a),
    };
    // The command runs on a worker of the thread pool: the solver's parallel loops (a dozen
    // per time step) then fork and join inside the pool instead of handing work from the
    // main thread to the pool and sleeping until it is done, which costs the operating
    // system's thread wake-ups at every loop (about a quarter of a small model's run time).
    let result = match rayon::ThreadPoolBuilder::new().build() {
        Ok(pool) => pool.install(dispatch),
        Err(_) => dispatch(),
    };
    match result {
        Ok(()) => 0,
        Err(e @ crate::Error::Interrupted(_)) => {
            eprintln!("{e}");
            crate::study::common::interrupt::EXIT_CODE
        }
        Err(e) => {
            eprintln!("error: {e}");
            1
        }
    }
}
