//! The Python front (python/): builds the `twoball` Python package with maturin into a
//! virtual environment under the target folder, then runs its pytest suite (the same results
//! as the command line to the bit, history arrays, one-line ValueErrors, Ctrl-C stopping a run
//! where it is, the GIL released) and the example script, which must write its PNG.
//!
//! Needs python3 with the venv module and pip access to maturin, numpy, pytest and
//! matplotlib: missing, the test fails under `CI=true` and is skipped with a notice otherwise.
//! The package is built with maturin's `--profile python` (the test profile's optimisation,
//! Cargo.toml) into its own folder of this target folder; cargo releases the folder's lock
//! while tests run.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use crate::tool_support as tools;

/// Python packages the suite needs, installed into the virtual environment.
const PACKAGES: &[&str] = &["maturin>=1.5,<2", "numpy", "pytest", "matplotlib"];

fn target_dir() -> PathBuf {
    // CARGO_BIN_EXE_twoball is TARGET/<profile>/twoball.
    let exe = Path::new(env!("CARGO_BIN_EXE_twoball"));
    exe.parent().and_then(Path::parent).unwrap().to_path_buf()
}

fn run(cmd: &mut Command, what: &str) -> bool {
    let t0 = Instant::now();
    let status = cmd.status().unwrap_or_else(|e| panic!("{what}: {e}"));
    eprintln!("{what}: {:.1} s", t0.elapsed().as_secs_f64());
    status.success()
}

/// The virtual environment with the packages, made once (None: it cannot be made here).
fn venv(root: &Path) -> Option<PathBuf> {
    let venv = root.join("venv");
    let python = venv.join("bin/python");
    let ready = venv.join(".packages-installed");
    if ready.exists() {
        return Some(python);
    }
    let made = run(
        Command::new("python3")
            .args(["-m", "venv", "--clear"])
            .arg(&venv),
        "python3 -m venv",
    ) && run(
        Command::new(&python)
            .args([
                "-m",
                "pip",
                "install",
                "--quiet",
                "--disable-pip-version-check",
            ])
            .args(PACKAGES),
        "pip install maturin numpy pytest matplotlib",
    );
    if !made {
        return None;
    }
    std::fs::write(&ready, PACKAGES.join("\n")).unwrap();
    Some(python)
}

#[test]
#[ignore = "builds the Python package with maturin (about 6 min on 2 cores); .ci/run runs it"]
fn python_front_pytest_suite_and_example() {
    let test = "python_front_pytest_suite_and_example";
    if !tools::require(
        tools::python("venv, ensurepip"),
        test,
        "python3 with the venv module",
    ) {
        return;
    }
    let target = target_dir();
    let root = target.join("python-front");
    std::fs::create_dir_all(&root).unwrap();
    let venv_python = venv(&root);
    if !tools::require(
        venv_python.is_some(),
        test,
        "a virtual environment with maturin, numpy, pytest and matplotlib (pip install)",
    ) {
        return;
    }
    let python = venv_python.unwrap();
    let bin = python.parent().unwrap().to_path_buf();
    let venv = bin.parent().unwrap().to_path_buf();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("python");
    assert!(
        run(
            Command::new(bin.join("maturin"))
                .args(["develop", "--profile", "python"])
                .current_dir(&crate_dir)
                .env("VIRTUAL_ENV", &venv)
                .env("PATH", &path)
                .env("CARGO_TARGET_DIR", &target),
            "maturin develop --profile python",
        ),
        "maturin develop failed"
    );
    assert!(
        run(
            Command::new(&python)
                .args([
                    "-m",
                    "pytest",
                    "-q",
                    "-s",
                    "-p",
                    "no:cacheprovider",
                    "tests"
                ])
                .current_dir(&crate_dir)
                .env("TWOBALL_BIN", env!("CARGO_BIN_EXE_twoball"))
                .env("PATH", &path),
            "pytest python/tests",
        ),
        "the Python front's pytest suite failed"
    );
    let png = root.join("default_scene.png");
    let _ = std::fs::remove_file(&png);
    assert!(
        run(
            Command::new(&python)
                .arg(crate_dir.join("examples/plot_default.py"))
                .arg(&png)
                .env("PATH", &path),
            "python/examples/plot_default.py",
        ),
        "the example failed"
    );
    let bytes = std::fs::read(&png).expect("the example wrote no PNG");
    assert!(
        bytes.starts_with(b"\x89PNG") && bytes.len() > 10_000,
        "{} is not a plot ({} bytes)",
        png.display(),
        bytes.len()
    );
}
