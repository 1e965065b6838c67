//! Issue 52, acceptance 4: a force history a researcher can compare with. The default scene
//! on the meridian section (its default run: the phase-ensemble mean F(δ) with a bar) and on
//! the 3D quarter model (the smoothed force of one run) give the same loading branch F(δ)
//! and peak force; history.csv keeps the raw force beside the smoothed one, whose impulse
//! equals the raw one's (verification/force-history.md).

use std::path::Path;
use std::process::Command;

/// Runs `twoball run` with `args` into `dir`; panics with its stderr on failure.
fn run(dir: &Path, args: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_twoball"))
        .arg("run")
        .args(args)
        .arg("--out")
        .arg(dir)
        .output()
        .expect("twoball runs");
    assert!(
        out.status.success(),
        "twoball run {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The rows of a CSV file with a header line, as numbers.
fn rows(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let data = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, data)
}

/// Column `name` of a CSV read by [`rows`].
fn column(header: &[String], data: &[Vec<f64>], name: &str) -> Vec<f64> {
    let k = header.iter().position(|h| h == name).unwrap();
    data.iter().map(|r| r[k]).collect()
}

/// y(x) by linear interpolation (x increasing).
fn at(x: &[f64], y: &[f64], v: f64) -> f64 {
    let k = x.partition_point(|&s| s <= v).clamp(1, x.len() - 1);
    y[k - 1] + (v - x[k - 1]) * (y[k] - y[k - 1]) / (x[k] - x[k - 1])
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The default scene on the 3D quarter model, with `extra` settings.
fn quarter_args(extra: &[&'static str]) -> Vec<&'static str> {
    let mut a = vec![
        "--no-error-estimate",
        "--set",
        "reduction.symmetry=\"auto-3d\"",
    ];
    a.extend_from_slice(extra);
    a
}

#[test]
fn section_and_quarter_give_one_loading_branch_and_one_peak_force() {
    check_against_the_section("quarter", &quarter_args(&[]));
}

/// The quarter with a bulk of D/10 (`cargo test --release --test suite force_history:: -- --ignored
/// --nocapture`, about a minute).
#[test]
#[ignore]
fn section_and_a_finer_quarter_give_one_loading_branch_and_one_peak_force() {
    check_against_the_section(
        "quarter-d10",
        &quarter_args(&[
            "--set",
            "ball1.mesh.size=0.002",
            "--set",
            "ball2.mesh.size=0.002",
        ]),
    );
}

/// Runs the default scene's section and the 3D model of `args`, prints their F(δ) side by
/// side and checks them.
fn check_against_the_section(name: &str, args: &[&str]) {
    let tmp = std::env::temp_dir().join(format!("twoball-force-{name}-{}", std::process::id()));
    let (section, quarter) = (tmp.join("section"), tmp.join(name));
    run(&section, &[]);
    run(&quarter, args);

    // The raw force stays, the smoothed one keeps the impulse.
    for dir in [&section, &quarter] {
        let (h, d) = rows(&dir.join("history.csv"));
        let t = column(&h, &d, "t [s]");
        let raw = column(&h, &d, "normal_force [N]");
        let smooth = column(&h, &d, "normal_force_smoothed [N]");
        let impulse = column(&h, &d, "impulse [N s]");
        assert!(raw.iter().zip(&smooth).any(|(r, s)| (r - s).abs() > 1.0));
        let trap = |f: &[f64]| {
            (1..t.len())
                .map(|k| 0.5 * (f[k] + f[k - 1]) * (t[k] - t[k - 1]))
                .sum::<f64>()
        };
        let total = impulse[impulse.len() - 1];
        assert!(
            (trap(&smooth) / total - 1.0).abs() < 2e-3,
            "{}: smoothed impulse {} against {total} N s",
            dir.display(),
            trap(&smooth)
        );
        assert!((trap(&raw) / total - 1.0).abs() < 2e-2);
    }

    // F(δ) from 10 µm to the smaller δ_max: within 2 % or within the section's bar.
    let (hs, ds) = rows(&section.join("force_curve.csv"));
    let (hq, dq) = rows(&quarter.join("force_curve.csv"));
    let (xs, fs, es) = (
        column(&hs, &ds, "delta [m]"),
        column(&hs, &ds, "force [N]"),
        column(&hs, &ds, "error [N]"),
    );
    let (xq, fq) = (column(&hq, &dq, "delta [m]"), column(&hq, &dq, "force [N]"));
    let top = xs[xs.len() - 1].min(xq[xq.len() - 1]);
    println!("| δ (µm) | section (N) | {name} (N) | difference |");
    println!("|---|---|---|---|");
    let mut d = 10e-6;
    while d <= top {
        let (s, e, q) = (at(&xs, &fs, d), at(&xs, &es, d), at(&xq, &fq, d));
        println!(
            "| {:.1} | {s:.1} ± {e:.1} | {q:.1} | {:+.2} % |",
            d * 1e6,
            100.0 * (q / s - 1.0)
        );
        assert!(
            (q - s).abs() <= (0.02 * s).max(e),
            "at {:.1} µm: section {s:.1} ± {e:.1} N, quarter {q:.1} N",
            d * 1e6
        );
        d += 2.5e-6;
    }

    // Peak forces: the section's ensemble mean against the quarter's smoothed peak.
    let js = json(&section.join("results.json"));
    let jq = json(&quarter.join("results.json"));
    let ps = js["error_estimate"]["peak_force"]["finest"]
        .as_f64()
        .unwrap();
    let pq = jq["fe"]["force"]["peak_smoothed"].as_f64().unwrap();
    let es = js["error_estimate"]["peak_force"]["error"]
        .as_f64()
        .unwrap();
    println!(
        "peak force: section {ps:.1} ± {es:.1} N, {name} {pq:.1} N ({:+.2} %)",
        100.0 * (pq / ps - 1.0)
    );
    assert!(
        (pq / ps - 1.0).abs() < 0.01,
        "peak: section {ps} N, {name} {pq} N"
    );
    let _ = std::fs::remove_dir_all(&tmp);
}
