//! `twoball bench`: the arguments of the benchmarks; the harnesses are in the study
//! (`study::bench::{kernel, profile, machine}`, `study::bench`).

use crate::error::Result;
use crate::fe::Formulation;
use crate::study::bench::kernel::{KernelBench, KernelCap};
use clap::{Args, Subcommand, ValueEnum};

/// Arguments of `twoball bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Which benchmark.
    #[command(subcommand)]
    pub which: BenchKind,
}

/// The benchmarks.
#[derive(Debug, Subcommand)]
pub enum BenchKind {
    /// Explicit element kernel + step: ns per element-cycle, 1 thread vs all threads.
    Kernel(KernelArgs),
    /// Where a scene's run spends its wall time, phase by phase.
    Profile(ProfileArgs),
    /// This machine's limits: FMA throughput and memory bandwidth per core (roofline).
    Machine(MachineArgs),
    /// Run time against error on a ladder of meshes, elements and time-step factors.
    Study(super::bench_study::StudyArgs),
    /// Chung & Ooi's DEM benchmark tests 1-8 (verification/dem-benchmarks/) by converged FE,
    /// beside Hertz, Maw, Barber & Fawcett's theory and every DEM law: one report.
    Dem(DemArgs),
}

/// Arguments of `twoball bench dem`.
#[derive(Debug, Args)]
pub struct DemArgs {
    /// Folder for report.md and cases.csv (written whole at the end; none without it).
    #[arg(long)]
    pub out: Option<std::path::PathBuf>,
    /// Run only the cases whose names start with one of these (e.g. test1, test4-alumina@30,
    /// test6-aluminium@w3).
    #[arg(long, num_args = 1..)]
    pub only: Vec<String>,
    /// Relative tolerance on e and the tangential restitution of the oblique and spinning
    /// cases, each run on its pole ladder (the pole halved per level, the bulk at most D/8),
    /// e.g. 1% or 0.01. The normal cases converge to 0.5 %.
    #[arg(long, value_name = "FRACTION|PERCENT%", default_value = "1%")]
    pub tolerance: String,
}

/// Arguments of `twoball bench kernel`.
#[derive(Debug, Args)]
pub struct KernelArgs {
    /// Ball element size as a fraction of the diameter (1/14.3 gives about 55 000 elements).
    #[arg(long, default_value_t = 0.07)]
    pub size_per_d: f64,
    /// Timed steps per repetition.
    #[arg(long, default_value_t = 20)]
    pub steps: u64,
    /// Repetitions (the median is reported).
    #[arg(long, default_value_t = 5)]
    pub repeats: usize,
    /// Thread count of the parallel run (default: all available).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Formulation to time.
    #[arg(long, value_enum, default_value_t = ElementChoice::Both)]
    pub element: ElementChoice,
    /// Also print where the one-thread step time goes (element phase, force gather, node
    /// passes, stable step), from the solver's phase timer.
    #[arg(long)]
    pub phases: bool,
    /// Widest element kernel to use: `widest` (the default: eight AVX-512 lanes where the CPU
    /// has them, else four AVX2 lanes, else portable), `avx2` (four lanes, the path of a CPU
    /// without AVX-512) or `portable` (plain arrays, any CPU). The header line names the path
    /// used. Same results on every path.
    #[arg(long, value_enum, default_value_t = KernelChoice::Widest)]
    pub kernel: KernelChoice,
}

/// The `--kernel` choice of `bench kernel`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum KernelChoice {
    /// The widest kernel this CPU supports (eight AVX-512 lanes where it can).
    Widest,
    /// At most the four-lane AVX2 kernel.
    Avx2,
    /// The portable kernel (four lanes as plain arrays).
    Portable,
}

impl From<KernelChoice> for KernelCap {
    fn from(c: KernelChoice) -> Self {
        match c {
            KernelChoice::Widest => KernelCap::Widest,
            KernelChoice::Avx2 => KernelCap::Avx2,
            KernelChoice::Portable => KernelCap::Portable,
        }
    }
}

/// Which hex formulations `bench kernel` times.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ElementChoice {
    /// The one-point hex with hourglass control.
    OnePoint,
    /// The 2x2x2 B-bar hex.
    BBar,
    /// Both, one after the other.
    Both,
}

impl ElementChoice {
    /// The formulations chosen.
    fn formulations(self) -> &'static [Formulation] {
        match self {
            ElementChoice::OnePoint => &[Formulation::OnePoint],
            ElementChoice::BBar => &[Formulation::BBar],
            ElementChoice::Both => &[Formulation::OnePoint, Formulation::BBar],
        }
    }
}

pub use super::bench_profile::ProfileArgs;

/// Arguments of `twoball bench machine`.
#[derive(Debug, Args)]
pub struct MachineArgs {
    /// Repetitions per measurement (the best is reported, as STREAM does).
    #[arg(long, default_value_t = 5)]
    pub repeats: usize,
}

/// Runs `twoball bench …`.
pub fn run(a: BenchArgs) -> Result<()> {
    match a.which {
        BenchKind::Kernel(k) => crate::study::bench::kernel::kernel(
            &KernelBench {
                size_per_d: k.size_per_d,
                steps: k.steps,
                repeats: k.repeats,
                threads: k.threads,
                formulations: k.element.formulations().to_vec(),
                phases: k.phases,
                kernel_cap: k.kernel.into(),
            },
            &mut std::io::stdout().lock(),
        ),
        BenchKind::Profile(p) => super::bench_profile::profile(p),
        BenchKind::Machine(m) => {
            crate::study::bench::machine::machine(m.repeats, &mut std::io::stdout().lock())
        }
        BenchKind::Study(s) => super::bench_study::run(s),
        BenchKind::Dem(d) => {
            let tolerance = super::run::parse_tolerance(&d.tolerance)?;
            crate::study::bench::dem::bench(&d.only, tolerance, d.out.as_deref()).map(|_| ())
        }
    }
}
