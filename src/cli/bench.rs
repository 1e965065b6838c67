//! `twoball bench kernel`: the cost of one explicit step per element ("time per zone cycle"),
//! on one thread and on all threads, for both hex formulations, on a ball mesh of about
//! 50 000 elements, and a check that the results do not depend on the thread count.

use crate::error::{Error, Result};
use crate::fe::profile::Totals;
use crate::fe::simd::{Kernel, KernelPath};
use crate::fe::{Formulation, Model, Settings, Solver};
use crate::material::Material;
use crate::mesh::ball::{ball, BallSpec, Cut};
use clap::{Args, Subcommand, ValueEnum};
use std::time::Instant;

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

impl From<KernelChoice> for KernelPath {
    fn from(c: KernelChoice) -> Self {
        match c {
            KernelChoice::Widest => KernelPath::Avx512,
            KernelChoice::Avx2 => KernelPath::Avx2,
            KernelChoice::Portable => KernelPath::Portable,
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

pub use super::bench_machine::MachineArgs;
pub use super::bench_profile::ProfileArgs;

/// Runs `twoball bench …`.
pub fn run(a: BenchArgs) -> Result<()> {
    match a.which {
        BenchKind::Kernel(k) => kernel(k),
        BenchKind::Profile(p) => super::bench_profile::profile(p),
        BenchKind::Machine(m) => super::bench_machine::machine(m),
        BenchKind::Study(s) => super::bench_study::run(s),
    }
}

/// Median ns per element-step, the final nodal positions and velocities of one run, and the
/// phase totals of the timed steps (all zero unless the phase timer was on).
struct Timing {
    ns: f64,
    x: Vec<[f64; 3]>,
    v: Vec<[f64; 3]>,
    phases: Totals,
    /// The kernel arithmetic alone (phase-timer runs only), ns per element.
    arithmetic: Option<f64>,
}

/// One timed configuration on `threads` threads; `phases` switches the solver's phase timer
/// on (its clock reads cost a little, so the timings to quote come from runs without it).
fn time_one(
    model: &Model,
    threads: usize,
    steps: u64,
    repeats: usize,
    phases: bool,
    kernel_cap: KernelPath,
) -> Result<Timing> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::External(format!("thread pool: {e}")))?;
    pool.install(|| {
        let settings = Settings {
            profile: phases,
            kernel_cap,
            ..Settings::default()
        };
        let mut s = Solver::new(model.clone(), vec![], settings)?;
        // Warm up (caches, page faults, first plastic steps).
        for _ in 0..5 {
            s.step()?;
        }
        let warm = s.profile().totals();
        let ne = model.hexes.len() as f64;
        let mut samples = Vec::with_capacity(repeats);
        for _ in 0..repeats {
            let t = Instant::now();
            for _ in 0..steps {
                s.step()?;
            }
            samples.push(t.elapsed().as_secs_f64() * 1e9 / (steps as f64 * ne));
        }
        samples.sort_by(f64::total_cmp);
        let mut timed = s.profile().totals();
        for (t, w) in timed.seconds.iter_mut().zip(warm.seconds) {
            *t -= w;
        }
        timed.steps -= warm.steps;
        timed.element_cycles -= warm.element_cycles;
        // The first lane group of the ball in its current state, its arithmetic repeated in
        // registers and L1: median of five runs of 20 000 updates.
        let arithmetic = phases.then(|| {
            let mut t: Vec<f64> = (0..5)
                .map(|_| s.blocks()[0].time_arithmetic_alone(s.x(), s.v(), s.dt(), 20_000))
                .collect();
            t.sort_by(f64::total_cmp);
            t[2]
        });
        Ok(Timing {
            ns: samples[samples.len() / 2],
            x: s.x().to_vec(),
            v: s.v().to_vec(),
            phases: timed,
            arithmetic,
        })
    })
}

fn kernel(a: KernelArgs) -> Result<()> {
    if !(a.size_per_d > 0.005 && a.size_per_d <= 0.5) {
        return Err(Error::invalid(
            "--size-per-d",
            a.size_per_d,
            "0.005 < size <= 0.5",
        ));
    }
    if a.steps == 0 || a.repeats == 0 {
        return Err(Error::invalid("--steps/--repeats", 0, "at least 1"));
    }
    let all = a.threads.unwrap_or_else(|| {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    });
    if all == 0 {
        return Err(Error::invalid("--threads", 0, "at least 1"));
    }
    let kernel_cap: KernelPath = a.kernel.into();
    let d = 0.02;
    let mesh = ball(&BallSpec {
        diameter: d,
        size: a.size_per_d * d,
        pole_size: None,
        cut: Cut::Full,
    })?;
    println!(
        "# twoball bench kernel: full ball D = 20 mm, {} elements, {} nodes, copper-fe elastic-plastic,",
        mesh.hexes.len(),
        mesh.nodes.len()
    );
    let path = Kernel::widest(kernel_cap).path();
    println!(
        "# {} timed steps x {} repeats (median), ns per element-cycle = step time / elements, kernel {:?} ({} lanes)",
        a.steps,
        a.repeats,
        path,
        path.lanes()
    );
    println!("formulation,threads,ns_per_element_cycle,speedup,bitwise_identical");
    let mut breakdowns = Vec::new();
    for &f in a.element.formulations() {
        let mut model = Model::new();
        let p = model.add_part("ball", &mesh, Material::preset("copper-fe")?, f)?;
        // A strong quadrupole plus spin: plastic flow near the surface, rotation everywhere.
        model.set_velocity_field(p, |x| {
            [
                4000.0 * x[0] - 500.0 * x[1],
                -4000.0 * x[1] + 500.0 * x[0],
                0.0,
            ]
        })?;
        let Timing {
            ns: t1,
            x: x1,
            v: v1,
            ..
        } = time_one(&model, 1, a.steps, a.repeats, false, kernel_cap)?;
        println!("{f:?},1,{t1:.1},1.00,-");
        if a.phases {
            let t = time_one(&model, 1, a.steps, a.repeats, true, kernel_cap)?;
            breakdowns.push((f, t.phases, t.arithmetic));
        }
        if all > 1 {
            let Timing {
                ns: tn,
                x: xn,
                v: vn,
                ..
            } = time_one(&model, all, a.steps, a.repeats, false, kernel_cap)?;
            let same = x1
                .iter()
                .zip(&xn)
                .chain(v1.iter().zip(&vn))
                .all(|(p, q)| p.iter().zip(q).all(|(a, b)| a.to_bits() == b.to_bits()));
            println!(
                "{f:?},{all},{tn:.1},{:.2},{}",
                t1 / tn,
                if same { "yes" } else { "NO" }
            );
        }
    }
    for (f, t, arithmetic) in breakdowns {
        println!("# {f:?}, 1 thread, phase timer on (its clock reads add a little):");
        print!("{}", t.table());
        if let Some(ns) = arithmetic {
            println!(
                "kernel arithmetic alone (one lane group kept in registers and L1)   {ns:6.1} ns/el-cyc"
            );
        }
    }
    Ok(())
}
