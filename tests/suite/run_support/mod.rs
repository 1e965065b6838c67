//! Runs `twoball run --no-error-estimate` into a folder and reads what it wrote.

use std::path::Path;
use std::process::Command;

/// Runs the scene file `scene` (the default scene if `None`) with the overrides `sets` into
/// `out`; returns results.json, the header line of history.csv and the printed summary.
/// Panics with the run's stderr if it fails.
pub fn run_cli(
    out: &Path,
    scene: Option<&Path>,
    sets: &[&str],
) -> (serde_json::Value, String, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_twoball"));
    cmd.args(["run", "--no-error-estimate", "--out"]).arg(out);
    if let Some(f) = scene {
        cmd.arg(f);
    }
    for s in sets {
        cmd.args(["--set", s]);
    }
    let run = cmd.output().unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let json =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let header = std::fs::read_to_string(out.join("history.csv"))
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .to_string();
    (
        json,
        header,
        String::from_utf8_lossy(&run.stdout).to_string(),
    )
}

/// The keys of a JSON value, recursively, as dotted paths from the root `.` (arrays by their
/// first item, as `[]`).
pub fn json_keys(v: &serde_json::Value) -> Vec<String> {
    let mut out = Vec::new();
    collect_keys(v, "", &mut out);
    out
}

fn collect_keys(v: &serde_json::Value, at: &str, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                let p = format!("{at}.{k}");
                out.push(p.clone());
                collect_keys(x, &p, out);
            }
        }
        serde_json::Value::Array(a) => {
            if let Some(x) = a.first() {
                collect_keys(x, &format!("{at}[]"), out);
            }
        }
        _ => {}
    }
}
