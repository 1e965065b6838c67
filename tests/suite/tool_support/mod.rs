#![allow(dead_code)]
//! External programs the tests drive (gmsh, python3 with meshio and numpy, CalculiX `ccx`,
//! the DEM codes LIGGGHTS `liggghts`, LAMMPS `lmp` and Yade `yade`).
//! Under CI (`CI=true`, as `.ci/run` is run) a missing program fails the test that needs it;
//! locally the test is skipped with a line saying what is missing and how to install it.

use std::process::Command;

/// True when the environment variable `CI` is `true` or `1` (set by CI services and by
/// `CI=true bash .ci/run`).
pub fn in_ci() -> bool {
    matches!(std::env::var("CI").as_deref(), Ok("true") | Ok("1"))
}

/// True when `program args` can be started (whatever its exit status: `ccx -v` exits 201).
pub fn starts(program: &str, args: &[&str]) -> bool {
    Command::new(program).args(args).output().is_ok()
}

/// True when `program args` runs and exits successfully.
pub fn succeeds(program: &str, args: &[&str]) -> bool {
    Command::new(program)
        .args(args)
        .output()
        .is_ok_and(|o| o.status.success())
}

/// `gmsh` is installed.
pub fn gmsh() -> bool {
    succeeds("gmsh", &["--version"])
}

/// `ccx` (CalculiX) is installed.
pub fn ccx() -> bool {
    starts("ccx", &["-v"])
}

/// The DEM code whose decks are run by `program` (`liggghts`, `lmp`, `yade`) is installed.
pub fn dem_code(program: &str) -> bool {
    match program {
        "yade" => succeeds("yade", &["--version"]),
        "lmp" => succeeds("lmp", &["-h"]),
        // LIGGGHTS prints its help and exits 1 (`-log none`: no log.liggghts left behind).
        p => starts(p, &["-log", "none", "-h"]),
    }
}

/// python3 imports every module of `modules` (comma-separated, e.g. "meshio, numpy").
pub fn python(modules: &str) -> bool {
    succeeds("python3", &["-c", &format!("import {modules}")])
}

/// Whether `test` may go on: true when the tool `what` was `found`. When it is missing, fails
/// under CI (a missing tool is a broken CI set-up, not a pass) and otherwise prints why the
/// test is skipped and returns false.
pub fn require(found: bool, test: &str, what: &str) -> bool {
    if found {
        return true;
    }
    assert!(
        !in_ci(),
        "{test}: {what} not found under CI=true (scripts/setup.sh installs it)"
    );
    eprintln!("SKIPPED {test}: {what} not found (scripts/setup.sh installs it; CI=true makes this a failure)");
    false
}
