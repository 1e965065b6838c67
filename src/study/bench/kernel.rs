//! The kernel benchmark of `twoball bench kernel`: the cost of one explicit step per element
//! ("time per zone cycle"), on one thread and on all threads, for the hex formulations, on a
//! ball mesh of about 50 000 elements, and a check that the results do not depend on the
//! thread count.

use crate::error::{Error, Result};
use crate::fe::profile::Totals;
use crate::fe::simd::{Kernel, KernelPath};
use crate::fe::{Formulation, Model, Settings, Solver};
use crate::material::Material;
use crate::mesh::ball::{ball, BallSpec, Cut};
use std::io::Write;
use std::time::Instant;

/// What `twoball bench kernel` times.
#[derive(Debug, Clone, PartialEq)]
pub struct KernelBench {
    /// Ball element size as a fraction of the diameter.
    pub size_per_d: f64,
    /// Timed steps per repetition.
    pub steps: u64,
    /// Repetitions (the median is reported).
    pub repeats: usize,
    /// Thread count of the parallel run (`None`: all available).
    pub threads: Option<usize>,
    /// Formulations timed, one after the other.
    pub formulations: Vec<Formulation>,
    /// Also time the one-thread step phase by phase (the solver's phase timer).
    pub phases: bool,
    /// Widest kernel path to use.
    pub kernel_cap: KernelPath,
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

/// Times the explicit step of `spec` and writes the CSV table (and, with phases, the phase
/// tables) to `out`.
///
/// Errors: an element size outside 0.005 < size/D <= 0.5, zero steps, repeats or threads
/// ([`Error::Invalid`] naming the flag); a thread pool that cannot be built; a failed mesh,
/// model or solver; a failed write to `out`.
pub fn kernel(a: &KernelBench, out: &mut impl Write) -> Result<()> {
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
    let kernel_cap = a.kernel_cap;
    let d = 0.02;
    let mesh = ball(&BallSpec {
        diameter: d,
        size: a.size_per_d * d,
        pole_size: None,
        cut: Cut::Full,
    })?;
    writeln!(out,
        "# twoball bench kernel: full ball D = 20 mm, {} elements, {} nodes, copper-fe elastic-plastic,",
        mesh.hexes.len(),
        mesh.nodes.len()
    ).map_err(put)?;
    let path = Kernel::widest(kernel_cap).path();
    writeln!(out,
        "# {} timed steps x {} repeats (median), ns per element-cycle = step time / elements, kernel {:?} ({} lanes)",
        a.steps,
        a.repeats,
        path,
        path.lanes()
    ).map_err(put)?;
    writeln!(
        out,
        "formulation,threads,ns_per_element_cycle,speedup,bitwise_identical"
    )
    .map_err(put)?;
    let mut breakdowns = Vec::new();
    for &f in &a.formulations {
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
        writeln!(out, "{f:?},1,{t1:.1},1.00,-").map_err(put)?;
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
            writeln!(
                out,
                "{f:?},{all},{tn:.1},{:.2},{}",
                t1 / tn,
                if same { "yes" } else { "NO" }
            )
            .map_err(put)?;
        }
    }
    for (f, t, arithmetic) in breakdowns {
        writeln!(
            out,
            "# {f:?}, 1 thread, phase timer on (its clock reads add a little):"
        )
        .map_err(put)?;
        write!(out, "{}", t.table()).map_err(put)?;
        if let Some(ns) = arithmetic {
            writeln!(out,
                "kernel arithmetic alone (one lane group kept in registers and L1)   {ns:6.1} ns/el-cyc"
            ).map_err(put)?;
        }
    }
    Ok(())
}

/// A failed write of the results.
fn put(e: std::io::Error) -> Error {
    Error::io("standard output", e)
}
