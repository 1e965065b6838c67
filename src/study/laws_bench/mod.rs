//! `twoball laws bench`: every contact law of the registry against FE over a matrix of
//! metals, speeds and diameters (head-on, on the meridian section) and against oblique 3D
//! impacts (tangential laws), with a cached FE side, a report, figures and fits.
//!
//! - [`matrix`]: the matrix (defaults, TOML) and the pair's yield speed v_y;
//! - [`fe`]: the FE answer for one head-on point ([`fe::head_on_fe`], with error bars under
//!   an [`fe::FePlan`]) or oblique point;
//! - [`similarity`]: which head-on points are scaled from another diameter;
//! - [`cache`]: one JSON per FE point, reused, written as each finishes, run in parallel;
//! - [`law_side`]: the laws on the same points;
//! - [`loops`]: the laws' quasi-static curves against an FE loop (`twoball static --laws`);
//!   [`loop_fit`]: a law fitted to such a loop (`twoball laws fit --against-static`);
//!   [`loop_points`]: the bench's FE loops (per metal, at three speeds) and the laws on them,
//!   [`loop_report`] their part of the report;
//! - [`bars`]: the FE error bars in e per metal and the laws within them;
//! - [`ranking`]: each law's errors against FE and the ranking;
//! - [`calibrated`]: the damped laws calibrated at one point per metal and ranked;
//! - [`fit`]: the laws fitted to the FE points;
//! - [`figures`]: the SVG figures; [`report`]: REPORT.md.

pub mod bars;
pub mod cache;
pub mod calibrated;
pub mod fe;
pub mod figures;
pub mod fit;
pub mod law_side;
pub mod loop_fit;
pub mod loop_points;
pub mod loop_report;
pub mod loops;
pub mod matrix;
pub mod oblique_report;
pub mod ranking;
pub mod report;
pub mod similarity;

use crate::analytic::law_fit::Observation;
use crate::analytic::laws::Registry;
use crate::error::Result;
use cache::{CacheKey, CacheStats, FeCache, Stored};
use fe::{FePlan, FePoint, ObliqueFe};
use law_side::{LawPoint, ObliqueLaw};
use loop_points::{LoopCase, LoopFe};
use loops::LawOnLoop;
use matrix::{HeadOnPoint, Matrix, ObliquePoint};
use rayon::prelude::*;
use std::path::PathBuf;

/// What a benchmark run does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// FE (missing points), laws, report.
    Full,
    /// Only the FE points (fill the cache).
    FeOnly,
    /// Only the laws and the report, on the cached FE points.
    LawsOnly,
}

/// A benchmark run.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// Output folder (the FE cache is `out/fe`).
    pub out: PathBuf,
    /// The matrix.
    pub matrix: Matrix,
    /// What to run.
    pub mode: Mode,
    /// FE points run at once.
    pub jobs: usize,
    /// How converged each head-on FE point is.
    pub plan: FePlan,
    /// Scale the smaller diameters of rate-independent metals from the largest
    /// ([`similarity`]) instead of running them.
    pub similarity: bool,
    /// The commands that reproduce the run, quoted at the top of the report.
    pub command: String,
}

/// One head-on point: FE and every law.
#[derive(Debug, Clone)]
pub struct HeadOnResult {
    /// The point.
    pub point: HeadOnPoint,
    /// The pair's yield speed, m/s ([`matrix::yield_speed`]).
    pub yield_speed: f64,
    /// The FE answer (None: not in the cache with `--laws-only`).
    pub fe: Option<Stored<FePoint>>,
    /// Every normal law, in registry order.
    pub laws: Vec<LawPoint>,
}

impl HeadOnResult {
    /// The finished FE answer.
    pub fn fe_done(&self) -> Option<&FePoint> {
        self.fe.as_ref().and_then(|s| s.done())
    }
}

/// One oblique point: FE and every tangential law.
#[derive(Debug, Clone)]
pub struct ObliqueResult {
    /// The point.
    pub point: ObliquePoint,
    /// The FE answer.
    pub fe: Option<Stored<ObliqueFe>>,
    /// Every tangential law, in registry order.
    pub laws: Vec<ObliqueLaw>,
    /// Maw, Barber & Fawcett's elastic theory on an elastic twin's point (`None` otherwise).
    pub theory: Option<law_side::Theory>,
}

/// One quasi-static loop: FE and every normal law on it.
#[derive(Debug, Clone)]
pub struct LoopResult {
    /// The head-on point whose ball the loop loads.
    pub point: HeadOnPoint,
    /// The FE loop (None: not in the cache with `--laws-only`).
    pub fe: Option<Stored<LoopFe>>,
    /// Every normal law on the finest loop, in registry order (empty without the FE loop).
    pub laws: Vec<LawOnLoop>,
}

/// Everything a benchmark run produced.
#[derive(Debug, Clone)]
pub struct BenchResults {
    /// The matrix.
    pub matrix: Matrix,
    /// The head-on FE plan.
    pub plan: FePlan,
    /// Normal law names, in registry order.
    pub normal_laws: Vec<String>,
    /// Tangential law names, in registry order.
    pub tangential_laws: Vec<String>,
    /// The head-on points.
    pub head_on: Vec<HeadOnResult>,
    /// The oblique points.
    pub oblique: Vec<ObliqueResult>,
    /// The quasi-static loops.
    pub loops: Vec<LoopResult>,
    /// The fits, one per metal.
    pub fits: Vec<fit::MetalFit>,
    /// The damped laws calibrated per metal and ranked.
    pub calibrated: Vec<calibrated::MetalCalibration>,
    /// Cache use of the head-on and oblique FE points and of the loops.
    pub stats: [CacheStats; 3],
}

/// What `run_bench` did.
#[derive(Debug, Clone)]
pub struct BenchSummary {
    /// Cache use of the head-on and oblique FE points and of the loops.
    pub stats: [CacheStats; 3],
    /// The report written (None with [`Mode::FeOnly`]).
    pub report: Option<PathBuf>,
    /// The results (None with [`Mode::FeOnly`]).
    pub results: Option<BenchResults>,
}

/// The FE observations of `metal` at `diameter` within `range` (m/s).
pub fn observations(
    head_on: &[HeadOnResult],
    metal: &str,
    diameter: f64,
    range: (f64, f64),
) -> Vec<Observation> {
    head_on
        .iter()
        .filter(|h| h.point.metal == metal && h.point.diameter == diameter)
        .filter(|h| h.point.speed >= range.0 && h.point.speed <= range.1)
        .filter_map(|h| {
            h.fe_done().map(|f| Observation {
                speed: h.point.speed,
                e: f.e.finest,
                delta_max: f.delta_max.finest,
            })
        })
        .collect()
}

/// The FE answers of the head-on `points`: run (through `cache`) or, with
/// `opts.similarity`, scaled from the run point of the largest diameter
/// ([`similarity::sources`]); a scaled point is stored in the cache under the model name
/// with ", scaled by similarity" added.
///
/// Errors: a cache file that cannot be written, the thread pool.
fn head_on_fe_all(
    opts: &BenchOptions,
    cache: &FeCache,
    points: &[HeadOnPoint],
    progress: &(dyn Fn(&str) + Sync),
) -> Result<(Vec<Option<Stored<FePoint>>>, CacheStats)> {
    let sources = if opts.similarity {
        similarity::sources(points)
    } else {
        vec![similarity::Source::Run; points.len()]
    };
    let run: Vec<usize> = (0..points.len())
        .filter(|&i| sources[i] == similarity::Source::Run)
        .collect();
    let run_points: Vec<HeadOnPoint> = run.iter().map(|&i| points[i].clone()).collect();
    let plan = opts.plan;
    let (answers, mut stats) = cache.run_all(
        &run_points,
        opts.jobs,
        opts.mode == Mode::LawsOnly,
        |p: &HeadOnPoint| fe::head_on_fe(p, &plan),
        progress,
    )?;
    let mut fe: Vec<Option<Stored<FePoint>>> = vec![None; points.len()];
    for (i, a) in run.into_iter().zip(answers) {
        fe[i] = a;
    }
    let scaled_cache = FeCache::new(
        &opts.out,
        &format!("{}, scaled by similarity", opts.plan.model()),
    );
    for (i, source) in sources.iter().enumerate() {
        let similarity::Source::Scaled { from } = *source else {
            continue;
        };
        let (p, q) = (&points[i], &points[from]);
        fe[i] = match &fe[from] {
            Some(Stored::Done(f)) => {
                Some(Stored::Done(f.scaled(p.diameter / q.diameter, q.diameter)))
            }
            Some(Stored::Failed(m)) => Some(Stored::Failed(format!(
                "scaled from the failed D = {} mm point: {m}",
                1e3 * q.diameter
            ))),
            None => None,
        };
        if let Some(f) = &fe[i] {
            stats.scaled += 1;
            if scaled_cache.load::<_, FePoint>(p).is_none() {
                scaled_cache.store(p, f)?;
            }
        } else {
            stats.missing += 1;
        }
    }
    Ok((fe, stats))
}

/// The FE answers of `points` under the FE model `model`, through the bench's cache
/// (`opts.jobs` at once; none run with `--laws-only`), and the cache's use.
///
/// Errors: a cache file that cannot be written, the thread pool.
fn cached<P, T>(
    opts: &BenchOptions,
    model: &str,
    points: &[P],
    run: impl Fn(&P) -> Result<T> + Sync,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<(Vec<Option<Stored<T>>>, CacheStats)>
where
    P: CacheKey + Sync,
    T: serde::Serialize + serde::de::DeserializeOwned + Send,
{
    let laws_only = opts.mode == Mode::LawsOnly;
    FeCache::new(&opts.out, model).run_all(points, opts.jobs, laws_only, run, progress)
}

/// Runs the benchmark: FE points (cached, `jobs` at once), the laws, the fits, the report
/// and figures in `opts.out`. `progress` receives one line per FE point run and per stage.
///
/// Errors: an unknown metal, an output folder that cannot be written, a law that fails to
/// integrate (FE failures are reported, not fatal).
pub fn run_bench(
    opts: &BenchOptions,
    registry: &Registry,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<BenchSummary> {
    let cache = FeCache::new(&opts.out, &opts.plan.model());
    let points = opts.matrix.head_on_points()?;
    let (fe, s1) = head_on_fe_all(opts, &cache, &points, progress)?;
    let oblique_points = opts.matrix.oblique_points()?;
    let (ofe, s2) = cached(
        opts,
        fe::OBLIQUE_MODEL,
        &oblique_points,
        fe::oblique_fe,
        progress,
    )?;
    let loop_cases: Vec<LoopCase> = opts
        .matrix
        .loop_points()?
        .into_iter()
        .map(LoopCase)
        .collect();
    let (lfe, s3) = cached(
        opts,
        loop_points::LOOP_MODEL,
        &loop_cases,
        loop_points::loop_fe,
        progress,
    )?;
    let stats = [s1, s2, s3];
    if opts.mode == Mode::FeOnly {
        return Ok(BenchSummary {
            stats,
            report: None,
            results: None,
        });
    }
    progress("laws on the head-on points");
    let head_on = points
        .into_par_iter()
        .zip(fe)
        .map(|(point, fe)| {
            Ok(HeadOnResult {
                yield_speed: matrix::yield_speed(&point.material, point.diameter)?,
                laws: law_side::laws_on_point(registry, &point)?,
                point,
                fe,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let normal_laws: Vec<String> = registry.normal.iter().map(|s| s.name.into()).collect();
    let rank = ranking::rank_all(&head_on, &normal_laws);
    progress("damped laws calibrated");
    let calibrated = calibrated::calibrate_all(registry, &head_on)?;
    let oblique = oblique_points
        .into_iter()
        .zip(ofe)
        .map(|(point, fe)| {
            let normal = if point.elastic {
                "hertz"
            } else {
                ranking::best_for(&rank, &point.metal).unwrap_or("thornton")
            };
            Ok(ObliqueResult {
                laws: law_side::tangential_laws_on_point(registry, normal, &point)?,
                theory: point
                    .elastic
                    .then(|| law_side::theory_on_point(&point))
                    .transpose()?,
                point,
                fe,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let loops = loop_cases
        .into_iter()
        .zip(lfe)
        .map(|(LoopCase(point), fe)| {
            let laws = match fe.as_ref().and_then(|f| f.done()) {
                Some(f) => loop_points::laws_on(f, &point, registry)?,
                None => vec![],
            };
            Ok(LoopResult { point, fe, laws })
        })
        .collect::<Result<Vec<_>>>()?;
    progress("fits");
    let dmax = opts.matrix.largest_diameter();
    let fits = opts
        .matrix
        .metals
        .par_iter()
        .map(|metal| {
            let material = crate::material::Material::preset(metal)?;
            let obs = observations(&head_on, metal, dmax, fit::FIT_RANGE);
            fit::fit_metal(registry, metal, material, dmax, obs)
        })
        .collect::<Result<Vec<_>>>()?;
    let results = BenchResults {
        matrix: opts.matrix.clone(),
        plan: opts.plan,
        normal_laws,
        tangential_laws: registry.tangential.iter().map(|s| s.name.into()).collect(),
        head_on,
        oblique,
        loops,
        fits,
        calibrated,
        stats,
    };
    progress("report and figures");
    let figures = figures::write_figures(&opts.out, &results, registry)?;
    let path = report::write_report(&opts.out, &results, &rank, &figures, &opts.command)?;
    Ok(BenchSummary {
        stats,
        report: Some(path),
        results: Some(results),
    })
}
