//! `twoball laws bench` end to end on a tiny matrix (copper-fe, D = 20 mm, 3.73 and 10 m/s,
//! no oblique points): the FE points, the cache (a second run runs no FE and leaves the
//! files untouched), the report naming every law, and a bad matrix file's one-line error.

use std::path::{Path, PathBuf};
use std::process::Command;
use twoball::analytic::laws::Registry;
use twoball::study::laws_bench::matrix::Matrix;
use twoball::study::laws_bench::{run_bench, BenchOptions, Mode};

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("twoball-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn tiny() -> Matrix {
    Matrix::from_toml(
        "metals = [\"copper-fe\"]\nspeeds = [3.7276, 10.0]\ndiameters = [0.02]\noblique = false",
        "tiny",
    )
    .unwrap()
}

fn options(out: &Path, mode: Mode) -> BenchOptions {
    BenchOptions {
        out: out.to_path_buf(),
        matrix: tiny(),
        mode,
        jobs: 2,
        command: "twoball laws bench --out DIR --matrix tiny.toml".into(),
    }
}

fn mtimes(dir: &Path) -> Vec<(PathBuf, std::time::SystemTime)> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (e.path(), e.metadata().unwrap().modified().unwrap())
        })
        .collect();
    v.sort();
    v
}

#[test]
fn tiny_matrix_runs_end_to_end_and_reuses_its_cache() {
    let out = scratch("laws-bench");
    let registry = Registry::builtin();
    let quiet = |_: &str| {};
    let first = run_bench(&options(&out, Mode::Full), &registry, &quiet).unwrap();
    assert_eq!((first.stats[0].computed, first.stats[0].reused), (2, 0));
    let r = first.results.unwrap();
    // The FE physics: a plastic impact restitutes less the faster it is, and well below 1.
    let e: Vec<f64> = r
        .head_on
        .iter()
        .map(|h| h.fe_done().unwrap().e.value)
        .collect();
    assert!(e[1] < e[0] && e[0] < 0.6 && e[1] > 0.1, "FE e {e:?}");
    // Hertz is elastic: its e is 1 and its error is 1/e_FE − 1.
    let k = r.normal_laws.iter().position(|l| l == "hertz").unwrap();
    let lh = &r.head_on[1].laws[k];
    assert!((lh.e - 1.0).abs() < 1e-6);
    let report = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
    for s in &registry.normal {
        assert!(
            report.contains(&format!("| {} |", s.name)),
            "report lacks {}",
            s.name
        );
    }
    assert!(report.contains(&format!("{:+.1}", 100.0 * (1.0 / e[1] - 1.0))));
    for f in ["e_v_copper-fe.svg", "e_v_over_vy.svg"] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let cached = mtimes(&out.join("fe"));
    assert_eq!(cached.len(), 2);
    std::thread::sleep(std::time::Duration::from_millis(20));
    let second = run_bench(&options(&out, Mode::Full), &registry, &quiet).unwrap();
    assert_eq!((second.stats[0].computed, second.stats[0].reused), (0, 2));
    assert_eq!(mtimes(&out.join("fe")), cached, "the cache was rewritten");
    let again = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
    assert_eq!(again, report, "a rerun from the cache changed the report");
    let empty = scratch("laws-bench-empty");
    let none = run_bench(&options(&empty, Mode::LawsOnly), &registry, &quiet).unwrap();
    assert_eq!((none.stats[0].computed, none.stats[0].missing), (0, 2));
    assert!(std::fs::read_to_string(empty.join("REPORT.md"))
        .unwrap()
        .contains("2 head-on points not in the cache"));
    let _ = std::fs::remove_dir_all(&out);
    let _ = std::fs::remove_dir_all(&empty);
}

#[test]
fn a_bad_matrix_file_is_one_line_naming_the_field() {
    let dir = scratch("laws-bench-bad");
    let cases = [
        ("speeds = [0.5, \"fast\"]", "speeds[1]"),
        ("diameters = [0.02, 5.0]", "diameters[1]"),
        ("metals = [\"copper-fe\", \"gold\"]", "metals[1]"),
        ("[oblique]\nratios = [0.5, -1]", "oblique.ratios[1]"),
        ("speed = [1.0]", "speed"),
    ];
    for (text, field) in cases {
        let m = dir.join("matrix.toml");
        std::fs::write(&m, text).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_twoball"))
            .args(["laws", "bench", "--laws-only", "--out"])
            .arg(dir.join("out"))
            .arg("--matrix")
            .arg(&m)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{text}: accepted");
        assert_eq!(err.trim().lines().count(), 1, "{text}: {err}");
        assert!(err.contains(&format!("invalid {field} =")), "{text}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
