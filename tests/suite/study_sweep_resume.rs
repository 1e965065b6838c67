//! Sweeps survive being killed: a `twoball sweep` subprocess is killed mid-way (SIGKILL, no
//! chance to clean up), restarted, and must finish with every case exactly once in the CSV,
//! no finished case redone, and no truncated or temporary file left. Shards partition the
//! sweep. (Issue 7, acceptance 4; issue 6, item 5.)

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant, SystemTime};
use twoball::study::sweep::{run_sweep, Shard, SweepOptions, SweepSpec};

const SWEEP: &str = r#"
[study]
model = "analytic"
diameters = [0.005, 0.02]
left_velocity = 1.0
right_velocities = [-2.5, -1.5, -1.0, 0.0, 0.5, 1.0]
tangential = [[0.0, 0.0], [0.1, -0.1], [0.5, -0.5]]
[base]
ball1.material = "copper-fe"
ball2.material = "copper-fe"
[[mesh]]
name = "coarse"
size_per_diameter = 0.2
pole_size_per_diameter = 0.05
"#;
const N_CASES: usize = 2 * 6 * 3;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "twoball-study-sweep-resume-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn case_files(out: &Path) -> BTreeMap<String, SystemTime> {
    let Ok(rd) = std::fs::read_dir(out.join("cases")) else {
        return BTreeMap::new();
    };
    rd.flatten()
        .filter(|e| {
            e.file_name().to_string_lossy().ends_with(".json")
                && !e.file_name().to_string_lossy().starts_with('.')
        })
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                e.metadata().unwrap().modified().unwrap(),
            )
        })
        .collect()
}

fn all_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        if e.path().is_dir() {
            all_files(&e.path(), out);
        } else {
            out.push(e.path());
        }
    }
}

fn sweep_cmd(file: &Path, out: &Path, pace_ms: u64) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_twoball"));
    c.args([
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--jobs",
        "2",
    ]);
    c.args(["--pace-ms", &pace_ms.to_string()]);
    c.stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped());
    c
}

#[test]
fn killed_sweep_resumes_and_finishes_every_case_exactly_once() {
    let dir = scratch("resume");
    let file = dir.join("sweep.toml");
    std::fs::write(&file, SWEEP).unwrap();
    let out = dir.join("out");

    // Kill twice at different moments, then let it finish.
    let mut survivors: BTreeMap<String, SystemTime> = BTreeMap::new();
    for kill_after in [5usize, 17] {
        let mut child = sweep_cmd(&file, &out, 40).spawn().unwrap();
        let t0 = Instant::now();
        while case_files(&out).len() < kill_after {
            assert!(
                t0.elapsed() < Duration::from_secs(60),
                "sweep made no progress"
            );
            assert!(
                child.try_wait().unwrap().is_none(),
                "sweep ended before it could be killed"
            );
            std::thread::sleep(Duration::from_millis(5));
        }
        child.kill().unwrap(); // SIGKILL: no cleanup possible
        child.wait().unwrap();
        let now = case_files(&out);
        assert!(now.len() < N_CASES, "killed too late to test anything");
        // Files that existed before this run were not rewritten by it.
        for (name, mtime) in &survivors {
            assert_eq!(now.get(name), Some(mtime), "{name} was redone");
        }
        survivors = now;
    }
    let status = sweep_cmd(&file, &out, 0).status().unwrap();
    assert!(status.success());
    let done = case_files(&out);
    assert_eq!(done.len(), N_CASES);
    for (name, mtime) in &survivors {
        assert_eq!(
            done.get(name),
            Some(mtime),
            "{name} was redone after restart"
        );
    }

    // The CSV: header + every case exactly once, every case file complete JSON.
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    assert!(
        header.contains("[m/s]") && header.contains("[m]") && header.contains("[s]"),
        "units in header"
    );
    let ids: Vec<&str> = lines.map(|l| l.split(',').next().unwrap()).collect();
    assert_eq!(ids.len(), N_CASES);
    assert_eq!(
        ids.iter().collect::<BTreeSet<_>>().len(),
        N_CASES,
        "a case appears twice"
    );
    assert!(!csv.contains("NaN") && !csv.contains("inf"));
    let no_impact = csv.lines().filter(|l| l.contains(",no_impact,")).count();
    assert_eq!(
        no_impact,
        2 * 3,
        "the +1.0 m/s right-ball cases are no impact"
    );

    let mut files = Vec::new();
    all_files(&out, &mut files);
    for f in &files {
        let name = f.file_name().unwrap().to_string_lossy();
        assert!(
            !name.contains(".tmp-"),
            "temporary file left: {}",
            f.display()
        );
        if name.ends_with(".json") {
            let text = std::fs::read_to_string(f).unwrap();
            serde_json::from_str::<serde_json::Value>(&text)
                .unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn shards_partition_the_sweep() {
    let dir = scratch("shards");
    let spec = SweepSpec::from_toml(SWEEP, "test").unwrap();
    let mut seen = BTreeSet::new();
    for i in 1..=3 {
        let opts = SweepOptions {
            out: dir.clone(),
            jobs: 1,
            shard: Shard::parse(&format!("{i}/3")).unwrap(),
            pace: Duration::ZERO,
            verbose: false,
            mesh: None,
        };
        let before = case_files(&dir);
        let s = run_sweep(&spec, &opts, None).unwrap();
        assert_eq!(s.in_shard, N_CASES / 3);
        assert_eq!(s.skipped, 0);
        let new: BTreeSet<String> = case_files(&dir)
            .keys()
            .filter(|k| !before.contains_key(*k))
            .cloned()
            .collect();
        assert_eq!(new.len(), N_CASES / 3);
        assert!(seen.is_disjoint(&new));
        seen.extend(new);
        assert_eq!(s.in_csv, seen.len());
    }
    assert_eq!(seen.len(), N_CASES);
    // A rerun of the whole sweep finds everything done.
    let opts = SweepOptions {
        out: dir.clone(),
        jobs: 2,
        shard: Shard::ALL,
        pace: Duration::ZERO,
        verbose: false,
        mesh: None,
    };
    let s = run_sweep(&spec, &opts, None).unwrap();
    assert_eq!((s.skipped, s.ran, s.in_csv), (N_CASES, 0, N_CASES));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_sweep_flags_and_files_are_one_line_errors() {
    for s in ["0/3", "4/3", "1/0", "x", "1/2/3"] {
        let e = Shard::parse(s).unwrap_err().to_string();
        assert!(e.contains("--shard") && !e.contains('\n'), "{e}");
    }
    for (text, key) in [
        (
            SWEEP.replace("diameters = [0.005, 0.02]", "diameters = [-1]"),
            "study.diameters[0]",
        ),
        (
            SWEEP.replace("model = \"analytic\"", "model = \"guess\""),
            "study.model",
        ),
        (
            SWEEP.replace("left_velocity", "left_speed"),
            "study.left_speed",
        ),
        (
            SWEEP.replace(
                "ball1.material = \"copper-fe\"",
                "ball1.material = \"cheese\"",
            ),
            "ball1.material",
        ),
        (
            SWEEP.replace(
                "size_per_diameter = 0.2",
                "size_per_diameter = 0.2\nsize = 0.001",
            ),
            "size",
        ),
        (format!("{SWEEP}\n[extra]\n"), "extra"),
        (
            SWEEP.replace(
                "model = \"analytic\"",
                "model = \"analytic\"\ntolerance = 1.5",
            ),
            "study.tolerance",
        ),
        (
            SWEEP.replace(
                "model = \"analytic\"",
                "model = \"analytic\"\ntolerance = 0",
            ),
            "study.tolerance",
        ),
    ] {
        let e = SweepSpec::from_toml(&text, "test").unwrap_err().to_string();
        assert!(e.contains(key) && !e.contains('\n'), "{key}: {e}");
    }
    // A tolerance for the head-on section cases, as a fraction.
    let spec = SweepSpec::from_toml(
        &SWEEP.replace(
            "model = \"analytic\"",
            "model = \"analytic\"\ntolerance = 0.005",
        ),
        "test",
    )
    .unwrap();
    assert_eq!(spec.tolerance, Some(0.005));
    assert_eq!(SweepSpec::from_toml(SWEEP, "test").unwrap().tolerance, None);
    // The command line: a missing file is a one-line error and exit code 1.
    let o = Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args(["sweep", "/nonexistent/sweep.toml", "--out", "/tmp/x"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.starts_with("error: ") && err.trim_end().lines().count() == 1,
        "{err}"
    );
}

/// `--mesh NAME` runs only that setting's cases; an unknown name is a one-line error that
/// lists the settings.
#[test]
fn mesh_filter_runs_one_setting() {
    let two = format!(
        "{SWEEP}[[mesh]]\nname = \"fine\"\nsize_per_diameter = 0.1\npole_size_per_diameter = 0.05\n"
    );
    let spec = SweepSpec::from_toml(&two, "test").unwrap();
    let dir = scratch("mesh-filter");
    let opts = |mesh: &str| SweepOptions {
        out: dir.clone(),
        jobs: 2,
        shard: Shard::ALL,
        pace: Duration::ZERO,
        verbose: false,
        mesh: Some(mesh.to_string()),
    };
    let s = run_sweep(&spec, &opts("fine"), None).unwrap();
    assert_eq!(
        (s.total, s.in_shard, s.ran),
        (2 * N_CASES, N_CASES, N_CASES)
    );
    assert!(case_files(&dir).keys().all(|k| k.contains("fine")));
    let err = run_sweep(&spec, &opts("medium"), None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("--mesh") && err.contains("coarse") && err.contains("fine"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
