//! Running a deck in the installed DEM code and comparing its collision with the law's own
//! (`twoball laws run` of the same law and parameters).

use super::trace::{read, DemOutcome};
use super::Code;
use crate::analytic::law_fit::predict;
use crate::analytic::laws::{NormalSpec, Params};
use crate::analytic::Body;
use crate::error::{Error, Result};
use crate::material::Material;
use std::path::Path;
use std::process::Command;

/// The program that runs `code`'s decks.
pub fn program(code: Code) -> Option<&'static str> {
    match code {
        Code::Liggghts => Some("liggghts"),
        Code::Lammps => Some("lmp"),
        Code::Yade => Some("yade"),
        Code::MercuryDpm => None,
    }
}

/// Runs the deck `dir/<code file>` unedited at relative speed `speed` (m/s), inside `dir`
/// (the deck writes `dir/trace.txt`), and reads the trace for balls of diameter `d` (m).
///
/// Errors: MercuryDPM (not run here), a program that cannot be started or exits non-zero
/// (its last output lines in the message), a trace that cannot be read.
pub fn run_deck(code: Code, dir: &Path, d: f64, speed: f64, tensile: bool) -> Result<DemOutcome> {
    let exe = program(code).ok_or_else(|| {
        Error::External(format!(
            "{} decks are not run here (no installed program)",
            code.name()
        ))
    })?;
    let v = format!("{speed:.12e}");
    let mut cmd = Command::new(exe);
    match code {
        Code::Liggghts => cmd.args(["-in", code.file(), "-var", "vr", &v, "-log", "none"]),
        Code::Lammps => cmd.args(["-in", code.file(), "-var", "vr", &v, "-log", "none"]),
        _ => cmd.args(["-n", "-x", code.file(), &v]),
    };
    // LIGGGHTS and LAMMPS start as Open MPI singletons, which by default spawn a support
    // daemon and connect to it; under load that start-up can fail before MPI_Init completes.
    // A serial deck never spawns processes, so the daemon is not started.
    cmd.env("OMPI_MCA_ess_singleton_isolated", "1");
    let trace = dir.join("trace.txt");
    let _ = std::fs::remove_file(&trace);
    let start = |cmd: &mut Command| {
        cmd.current_dir(dir).output().map_err(|e| {
            Error::External(format!(
                "{exe}: cannot start ({e}); scripts/setup.sh installs it"
            ))
        })
    };
    let mut out = start(&mut cmd)?;
    // A start-up that failed inside MPI_Init never read the deck: it is tried once more.
    if !out.status.success() && mpi_start_failed(&out.stdout, &out.stderr) {
        out = start(&mut cmd)?;
    }
    if !out.status.success() || !trace.exists() {
        let text = String::from_utf8_lossy(&out.stdout).into_owned()
            + &String::from_utf8_lossy(&out.stderr);
        let tail: Vec<&str> = text
            .lines()
            .filter(|l| !l.contains("mca_base_component"))
            .rev()
            .take(4)
            .collect();
        return Err(Error::External(format!(
            "{exe} on {}: exit {:?}: {}",
            dir.join(code.file()).display(),
            out.status.code(),
            tail.into_iter().rev().collect::<Vec<_>>().join(" | ")
        )));
    }
    let text = std::fs::read_to_string(&trace).map_err(|e| Error::io(&trace, e))?;
    read(&text, &trace.display().to_string(), d, speed, tensile)
}

/// Whether a program's output says Open MPI gave up before `MPI_Init` completed.
fn mpi_start_failed(stdout: &[u8], stderr: &[u8]) -> bool {
    let says = |b: &[u8]| String::from_utf8_lossy(b).contains("before MPI_INIT completed");
    says(stdout) || says(stderr)
}

/// e, δ_max (m) and contact duration (s) of `twoball laws run` for `spec` with `params` on
/// two balls of `material` and diameter `d` (m) at relative speed `speed` (m/s).
pub fn law_outcome(
    spec: &NormalSpec,
    params: &Params,
    material: &Material,
    d: f64,
    speed: f64,
) -> Result<DemOutcome> {
    let b = Body::ball(*material, d, "ball")?;
    let pair = crate::analytic::laws::ContactPair::between(&b, &b, material.mu);
    let (e, delta_max, contact_duration) = predict(spec, &pair, params, &b, &b, speed)?;
    Ok(DemOutcome {
        e,
        delta_max,
        contact_duration,
    })
}

/// Whether a law with `params` may pull (its contact then ends at zero overlap).
pub fn tensile(spec: &NormalSpec, params: &Params) -> bool {
    spec.params.iter().any(|p| p.key == "tension") && params.tension()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_an_mpi_start_up_failure_is_tried_again() {
        let start =
            b"*** on a NULL communicator\n[vm:18871] Local abort before MPI_INIT completed \
                      completed successfully, but am not able to aggregate error messages";
        assert!(mpi_start_failed(b"", start));
        assert!(mpi_start_failed(start, b""));
        assert!(!mpi_start_failed(
            b"ERROR: Unknown command: pair_styl hertz",
            b""
        ));
    }
}
