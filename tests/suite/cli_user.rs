//! What a new user meets first (issue 25): a report that stays beside its sweep, progress
//! under a pipe, warnings for results not to trust, a clean Ctrl-C, negative numbers read as
//! values, and a readable analytical table. Every test runs the `twoball` binary as a user
//! would, with stdout and stderr piped.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn twoball() -> Command {
    Command::new(env!("CARGO_BIN_EXE_twoball"))
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("twoball-user-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn run_in(dir: &Path, args: &[&str]) -> Output {
    twoball().current_dir(dir).args(args).output().unwrap()
}

/// A 12-case analytical sweep (fast), the same layout as the paper's study.
const SWEEP: &str = r#"
[study]
model = "analytic"
diameters = [0.005, 0.02]
left_velocity = 1.0
right_velocities = [-1.0, 0.5]
tangential = [[0.0, 0.0], [0.1, -0.1], [0.5, -0.5]]
history_points = 50
[base]
ball1.material = "copper-fe"
ball2.material = "copper-fe"
[[mesh]]
name = "coarse"
size_per_diameter = 0.2
pole_size_per_diameter = 0.05
"#;

/// Item 1: `twoball report DIR` writes beside the sweep, never into `verification/`; a
/// partial sweep goes into another folder only with `--partial` (and says so in its title),
/// and stale figures of an earlier report are removed.
#[test]
fn report_stays_beside_the_sweep_and_refuses_a_partial_sweep_elsewhere() {
    let root = scratch("report");
    std::fs::write(root.join("study.toml"), SWEEP).unwrap();
    // A committed report that must survive.
    let committed = root.join("verification");
    std::fs::create_dir_all(committed.join("ansys")).unwrap();
    std::fs::write(committed.join("REPORT.md"), "# committed\n").unwrap();
    std::fs::write(
        committed.join("NOTES.md"),
        "hand-written discussion of 144 cases\n",
    )
    .unwrap();
    std::fs::write(committed.join("ansys/fig99.svg"), "<svg/>").unwrap();
    // Half the sweep.
    let o = run_in(
        &root,
        &["sweep", "study.toml", "--out", "out", "--shard", "1/2"],
    );
    assert!(o.status.success(), "{}", text(&o.stderr));

    let o = run_in(&root, &["report", "out", "--sweep", "study.toml"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(
        text(&o.stdout).contains("partial: 6 of 12 cases"),
        "{}",
        text(&o.stdout)
    );
    let beside = std::fs::read_to_string(root.join("out/REPORT.md")).unwrap();
    assert!(beside.contains("(partial: 6 of 12 cases)"), "{beside}");
    assert_eq!(
        std::fs::read_to_string(committed.join("REPORT.md")).unwrap(),
        "# committed\n"
    );
    assert!(!committed.join("ansys/sweep.csv").exists());

    // Into the committed folder: refused while partial, nothing touched.
    let o = run_in(
        &root,
        &[
            "report",
            "out",
            "--sweep",
            "study.toml",
            "--to",
            "verification",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stdout));
    let err = text(&o.stderr);
    assert!(
        err.contains("--to") && err.contains("6 of 12") && err.contains("--partial"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert_eq!(
        std::fs::read_to_string(committed.join("REPORT.md")).unwrap(),
        "# committed\n"
    );

    // With --partial: written, titled partial, without the whole sweep's discussion, and no
    // stale figure left beside the new tables.
    let o = run_in(
        &root,
        &[
            "report",
            "out",
            "--sweep",
            "study.toml",
            "--to",
            "verification",
            "--partial",
        ],
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let md = std::fs::read_to_string(committed.join("REPORT.md")).unwrap();
    assert!(
        md.lines()
            .next()
            .unwrap()
            .contains("partial: 6 of 12 cases"),
        "{md}"
    );
    assert!(!md.contains("hand-written discussion"), "{md}");
    assert!(!committed.join("ansys/fig99.svg").exists());
    assert!(
        text(&o.stdout).contains("removed stale fig99.svg"),
        "{}",
        text(&o.stdout)
    );
    for e in std::fs::read_dir(committed.join("ansys"))
        .unwrap()
        .flatten()
    {
        let name = e.file_name().to_string_lossy().into_owned();
        assert!(
            !name.ends_with(".svg") || md.contains(&format!("ansys/{name}")),
            "{name} is not in the report"
        );
    }

    // The whole sweep: written into the committed folder without --partial, with the notes.
    let o = run_in(
        &root,
        &["sweep", "study.toml", "--out", "out", "--shard", "2/2"],
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let o = run_in(
        &root,
        &[
            "report",
            "out",
            "--sweep",
            "study.toml",
            "--to",
            "verification",
        ],
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let md = std::fs::read_to_string(committed.join("REPORT.md")).unwrap();
    assert!(!md.contains("partial"), "{md}");
    assert!(md.contains("hand-written discussion"), "{md}");
    let _ = std::fs::remove_dir_all(&root);
}

/// Item 2: under a pipe a sweep prints plain progress lines (cases done/failed, ETA), and a
/// run says when the FE starts and ends.
#[test]
fn progress_is_printed_when_stderr_is_a_pipe() {
    let root = scratch("progress");
    std::fs::write(root.join("study.toml"), SWEEP).unwrap();
    // 12 cases paced to 0.7 s each on one worker: about 8.4 s, a plain line about every
    // 2.1 s (3 cases, 25 %) and a final one.
    let o = run_in(
        &root,
        &[
            "sweep",
            "study.toml",
            "--out",
            "out",
            "--jobs",
            "1",
            "--pace-ms",
            "700",
        ],
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let err = text(&o.stderr);
    let lines: Vec<&str> = err
        .lines()
        .filter(|l| l.starts_with("sweep: ") && l.contains("cases done"))
        .collect();
    assert!(lines.len() >= 3, "too few progress lines:\n{err}");
    assert!(lines.iter().any(|l| l.contains("ETA")), "{err}");
    assert!(
        lines
            .last()
            .unwrap()
            .contains("12/12 cases done (0 failed)"),
        "{err}"
    );
    assert!(!err.contains('\r'), "a terminal bar on a pipe:\n{err:?}");

    let o = run_in(&root, &["run"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let err = text(&o.stderr);
    assert!(err.contains("run: FE started"), "{err}");
    assert!(err.contains("run: FE done"), "{err}");
    let _ = std::fs::remove_dir_all(&root);
}

/// The refinement after "FE done" of a `--tolerance` run counts its member runs (±5 m/s: a
/// short contact, a cheap family).
#[test]
fn a_tolerance_run_counts_its_member_runs() {
    let root = scratch("tolerance-progress");
    let o = run_in(
        &root,
        &[
            "run",
            "--tolerance",
            "0.5%",
            "--set",
            "ball1.velocity=[5,0,0]",
            "--set",
            "ball2.velocity=[-5,0,0]",
            "--out",
            "tol",
        ],
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let err = text(&o.stderr);
    let done = err
        .find("run: FE done")
        .expect("the scene's run ends first");
    let counted = err
        .find("tolerance: banded mesh family, member runs: 4/4 cases done (0 failed)")
        .unwrap_or_else(|| panic!("no member count:\n{err}"));
    assert!(done < counted, "{err}");
    let _ = std::fs::remove_dir_all(&root);
}

/// A default run on a Johnson-Cook metal carries a bar on e of at least 3 % (its levels' own
/// bar missed there) and says so in one line.
#[test]
fn a_default_run_on_a_johnson_cook_metal_floors_its_bar() {
    let root = scratch("jc-bar");
    let o = run_in(
        &root,
        &[
            "run",
            "--set",
            "ball1.material=\"ofhc-copper\"",
            "--set",
            "ball2.material=\"ofhc-copper\"",
            "--out",
            "jc",
        ],
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let err = text(&o.stderr);
    let lines: Vec<&str> = err
        .lines()
        .filter(|l| l.contains("at least 3 % on a rate-dependent"))
        .collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(warnings_of(&root.join("jc")).contains(&"rate_dependent_bar".to_string()));
    let bar = results_of(&root.join("jc"))["error_estimate"]["e"]["relative_error"]
        .as_f64()
        .unwrap();
    assert!(bar >= 0.03 * (1.0 - 1e-12), "relative bar {bar}");
    let _ = std::fs::remove_dir_all(&root);
}

/// The results.json a run wrote into `dir`.
fn results_of(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap()
}

fn warnings_of(dir: &Path) -> Vec<String> {
    results_of(dir)["warnings"]
        .as_array()
        .expect("results.json has `warnings`")
        .iter()
        .map(|w| w["check"].as_str().unwrap().to_string())
        .collect()
}

/// Item 3: the soft-penalty run warns about its penetration; the default run (converged
/// enough, resolved contact) warns about nothing; both record `warnings` in results.json.
#[test]
fn a_soft_penalty_run_warns_and_the_default_run_does_not() {
    let root = scratch("warn");
    let o = run_in(&root, &["run", "--out", "default"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(!text(&o.stderr).contains("warning:"), "{}", text(&o.stderr));
    assert!(warnings_of(&root.join("default")).is_empty());
    // The main job explains its 40 % delta_max difference.
    assert!(
        text(&o.stdout).contains("verification/NOTES.md"),
        "{}",
        text(&o.stdout)
    );

    let o = run_in(
        &root,
        &[
            "run",
            "--set",
            "contact.penalty_factor=0.001",
            "--set",
            "reduction.symmetry=\"auto-3d\"",
            "--out",
            "soft",
        ],
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let err = text(&o.stderr);
    let line = err
        .lines()
        .find(|l| l.starts_with("warning: penetration"))
        .unwrap_or_else(|| panic!("no penetration warning:\n{err}"));
    assert!(line.contains("contact.penalty_factor"), "{line}");
    assert!(warnings_of(&root.join("soft")).contains(&"penetration".to_string()));
    let _ = std::fs::remove_dir_all(&root);
}

/// Item 3: the stress matrix's flagged case (steel at 1 m/s on the matrix's coarse mesh,
/// energy error 1.8 %) prints its warnings.
#[test]
fn the_stress_matrix_prints_the_warnings_of_its_flagged_cases() {
    let root = scratch("stress");
    std::fs::write(
        root.join("m.toml"),
        r#"
[stress]
timeout_s = 120
energy_tolerance = 0.01
size_per_diameter = 0.34
pole_size_per_diameter = 0.17
quick = []
[axis]
speed = [{ label = "v1", set = ["ball1.velocity=[0.5,0,0]", "ball2.velocity=[-0.5,0,0]"] }]
material = [{ label = "steel", set = ["ball1.material=steel", "ball2.material=steel", "reduction.symmetry=\"auto-3d\""] }]
[[group]]
axes = ["speed", "material"]
"#,
    )
    .unwrap();
    let o = run_in(&root, &["stress", "--matrix", "m.toml", "--out", "out"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    assert!(out.contains("1 flagged"), "{out}");
    assert!(
        out.contains("speed-material_v1_steel: warning: energy error"),
        "{out}"
    );
    assert!(
        out.contains("speed-material_v1_steel: warning: the contact patch"),
        "{out}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

/// Item 3: the analytical model warns outside its range (δ_2 = 0.115 m for 20 mm balls).
#[test]
fn the_analytical_model_warns_outside_its_range() {
    let o = twoball()
        .args(["analytic", "--v1", "900", "--v2", "-900", "--json"])
        .output()
        .unwrap();
    assert!(o.status.success());
    let err = text(&o.stderr);
    assert!(err.starts_with("warning: analytical delta_2"), "{err}");
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["warnings"][0]["check"], "analytic_range");
    let o = twoball().args(["analytic"]).output().unwrap();
    assert!(!text(&o.stderr).contains("warning"), "{}", text(&o.stderr));
}

/// Item 4: Ctrl-C stops a run cleanly: exit 130, one line saying where it stopped and that
/// nothing was written, and no output folder that looks complete.
#[cfg(unix)]
#[test]
fn ctrl_c_stops_a_run_cleanly_and_leaves_no_output() {
    use std::io::{BufRead, BufReader};
    let root = scratch("sigint");
    let out = root.join("out");
    let mut child = twoball()
        .current_dir(&root)
        .args([
            "run",
            "--set",
            "ball1.mesh={size=0.0015,pole_size=0.0001}",
            "--set",
            "ball2.mesh={size=0.0015,pole_size=0.0001}",
            "--set",
            "output.vtu_snapshots=50",
            "--out",
            "out",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut err = BufReader::new(child.stderr.take().unwrap());
    let mut seen = String::new();
    // Wait until the FE loop runs and a snapshot is written, then press Ctrl-C.
    let start = Instant::now();
    let mut line = String::new();
    while err.read_line(&mut line).unwrap() > 0 {
        seen.push_str(&line);
        if line.starts_with("run: FE started") {
            break;
        }
        line.clear();
    }
    assert!(seen.contains("run: FE started"), "{seen}");
    while !out.join("snapshots.pvd").exists() && start.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(out.join("snapshots.pvd").exists());
    // SAFETY: kill(2) on our own child's pid with a valid signal number.
    let rc = unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) };
    assert_eq!(rc, 0);
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut err, &mut rest).unwrap();
    let status = child.wait().unwrap();
    seen.push_str(&rest);
    assert_eq!(status.code(), Some(130), "{seen}");
    let last = seen.trim().lines().last().unwrap();
    assert!(
        last.starts_with("interrupted at t = ") && last.contains("nothing written"),
        "{seen}"
    );
    assert!(!out.exists(), "the interrupted run left {}", out.display());
    let _ = std::fs::remove_dir_all(&root);
}

/// Item 5: negative numbers are values for every command, so the range check answers.
#[test]
fn negative_numbers_reach_the_range_check() {
    let root = scratch("negative");
    for (args, flag) in [
        (
            vec![
                "mesh",
                "ball",
                "--diameter",
                "-0.02",
                "--size",
                "0.002",
                "-o",
                "b.msh",
            ],
            "--diameter",
        ),
        (
            vec![
                "mesh",
                "ball",
                "--diameter",
                "0.02",
                "--size",
                "-2e-3",
                "-o",
                "b.msh",
            ],
            "--size",
        ),
        (vec!["analytic", "--diameter", "-1"], "--diameter"),
        (vec!["analytic", "--mu", "-0.5"], "--mu"),
        (
            vec!["sweep", "x.toml", "--out", "o", "--jobs", "-1"],
            "--jobs",
        ),
        (vec!["stress", "--out", "o", "--jobs", "-1"], "--jobs"),
    ] {
        let o = run_in(&root, &args);
        let err = text(&o.stderr);
        assert!(!o.status.success(), "{args:?}");
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
        assert!(err.contains(flag), "{args:?}: {err}");
    }
    // Negative speeds are ordinary input.
    let o = run_in(&root, &["analytic", "--v1t", "-0.3", "--v2", "-2"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let _ = std::fs::remove_dir_all(&root);
}

/// Item 8: the analytical table names ball 2 (or the wall) as such, prints zero as 0, and a
/// `--set` for both balls is blamed as the user wrote it.
#[test]
fn the_analytical_table_reads_plainly() {
    let o = twoball()
        .args(["analytic", "--set", "yield=1e12"])
        .output()
        .unwrap();
    let out = text(&o.stdout);
    assert!(out.contains("\nball 2: D = 0.02 m"), "{out}");
    assert!(!out.contains("body 2"), "{out}");
    assert!(!out.contains("0.000000e0"), "{out}");
    assert!(out.contains("delta_p = 0 "), "{out}");
    let o = twoball()
        .args(["analytic", "--wall", "rigid", "--v1", "1"])
        .output()
        .unwrap();
    assert!(text(&o.stdout).contains("\nwall: rigid half-space"));
    for (set, named) in [
        ("yield=-5", "invalid --set yield = -5"),
        (
            "ball2.material.yield=-5",
            "invalid ball2.material.yield = -5",
        ),
    ] {
        let o = twoball().args(["analytic", "--set", set]).output().unwrap();
        assert_eq!(o.status.code(), Some(1));
        let err = text(&o.stderr);
        assert!(err.contains(named), "{err}");
        assert!(!err.contains("ball1.material"), "{err}");
    }
}

/// Honest defaults, item 1: a setting the chosen model ignores gets one `note:` line and a
/// `ignored_setting` warning in results.json, on each model (the section, the quarter, the
/// half and the full 3D model); the same setting where the model uses it gets none.
#[test]
fn a_setting_the_model_ignores_is_noted_on_every_model() {
    let root = scratch("ignored");
    let coarse = [
        "--set",
        "ball1.mesh={size=0.0068,pole_size=0.0034}",
        "--set",
        "ball2.mesh={size=0.0068,pole_size=0.0034}",
    ];
    let cases: [(&str, &[&str], &str); 5] = [
        (
            "section",
            &["--set", "contact.penalty_factor=0.5"],
            "contact.penalty_factor",
        ),
        (
            "quarter",
            &[
                "--set",
                "contact.friction=0.3",
                "--set",
                "reduction.symmetry=\"quarter\"",
            ],
            "contact.friction",
        ),
        (
            "half",
            &[
                "--set",
                "contact.plane=\"penalty\"",
                "--set",
                "reduction.symmetry=\"half\"",
            ],
            "contact.plane",
        ),
        (
            "full",
            &[
                "--set",
                "solver.hold_time=1e-5",
                "--set",
                "solver.end_time=2e-4",
                "--set",
                "reduction.symmetry=\"off\"",
            ],
            "solver.hold_time",
        ),
        (
            "used",
            &[
                "--set",
                "contact.penalty_factor=0.5",
                "--set",
                "reduction.symmetry=\"quarter\"",
            ],
            "",
        ),
    ];
    for (name, sets, key) in cases {
        let mut args = vec!["run", "--no-error-estimate", "--out", name];
        args.extend_from_slice(&coarse);
        args.extend_from_slice(sets);
        let o = run_in(&root, &args);
        let err = text(&o.stderr);
        assert!(o.status.success(), "{name}: {err}");
        let notes: Vec<&str> = err.lines().filter(|l| l.starts_with("note: ")).collect();
        let checks = warnings_of(&root.join(name));
        let ignored = checks.iter().filter(|c| *c == "ignored_setting").count();
        if key.is_empty() {
            assert!(notes.is_empty() && ignored == 0, "{name}: {err}");
        } else {
            assert_eq!(notes.len(), 1, "{name}: {err}");
            assert!(
                notes[0].starts_with(&format!("note: {key} ")),
                "{name}: {err}"
            );
            assert_eq!(ignored, 1, "{name}: {checks:?}");
        }
    }
    let _ = std::fs::remove_dir_all(&root);
}

/// Honest defaults, item 5: usage errors are one line with exit code 1, as every other
/// error; `analytic` takes the scene's ranges; `report` names its missing folder; a run
/// refused or failed leaves no output folder behind.
#[test]
fn bad_input_gets_one_line_exit_1_and_leaves_nothing() {
    let root = scratch("bad");
    let one_line = |args: &[&str], needle: &str| {
        let o = run_in(&root, args);
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        let lines: Vec<&str> = err.lines().collect();
        assert_eq!(lines.len(), 1, "{args:?}: {err}");
        assert!(
            lines[0].starts_with("error: ") && lines[0].contains(needle),
            "{err}"
        );
    };
    one_line(&["analytic", "--v1", "abc"], "--v1");
    one_line(&["run", "--no-such-flag"], "--no-such-flag");
    one_line(&["analytic", "--diameter", "5"], "--diameter");
    one_line(&["analytic", "--v1", "2000"], "--v1");
    one_line(&["report", "no-such-sweep"], "no-such-sweep");
    one_line(
        &["run", "--tolerance", "200%", "--out", "tol"],
        "--tolerance",
    );
    assert!(!root.join("tol").exists(), "a refused run left its folder");
    std::fs::write(root.join("bad.msh"), "not a mesh").unwrap();
    std::fs::write(
        root.join("bad.toml"),
        "[ball1]\nmaterial = \"copper-fe\"\ndiameter = 0.02\nvelocity = [1.0, 0.0, 0.0]\nmesh = { file = \"bad.msh\" }\n[ball2]\nmaterial = \"copper-fe\"\ndiameter = 0.02\nvelocity = [-1.0, 0.0, 0.0]\n",
    )
    .unwrap();
    let o = run_in(&root, &["run", "bad.toml", "--out", "mesh"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
    assert!(!root.join("mesh").exists(), "a failed run left its folder");
    // Help is not an error.
    let o = run_in(&root, &["run", "--help"]);
    assert_eq!(o.status.code(), Some(0));
    let _ = std::fs::remove_dir_all(&root);
}

/// Honest defaults, item 5: hard head-on impacts complete by default; where the default
/// error estimate's mesh levels do not hold the contact, the run says so in one line and
/// answers from the scene's mesh.
#[test]
fn hard_head_on_impacts_complete_by_default() {
    let root = scratch("hard");
    for v in [70.0, 100.0, 300.0] {
        let name = format!("v{v}");
        let o = run_in(
            &root,
            &[
                "run",
                "--set",
                &format!("ball1.velocity=[{v},0,0]"),
                "--set",
                &format!("ball2.velocity=[-{v},0,0]"),
                "--out",
                &name,
            ],
        );
        let err = text(&o.stderr);
        assert!(o.status.success(), "±{v} m/s: {err}");
        let results = results_of(&root.join(&name));
        let e = results["e"].as_f64().unwrap();
        assert!(e > 0.0 && e < 1.0, "±{v} m/s: e = {e}");
        let bar = results["error_estimate"].is_object();
        let noted = warnings_of(&root.join(&name)).contains(&"no_error_estimate".to_string());
        assert!(
            bar != noted,
            "±{v} m/s: a bar or a note, not both or neither: {err}"
        );
    }
    let _ = std::fs::remove_dir_all(&root);
}
