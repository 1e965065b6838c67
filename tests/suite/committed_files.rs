//! Every committed `.toml` under `verification/` and `examples/` is read as the command that
//! takes it reads it (a scene, a sweep, a robustness matrix, a damper file), and every scene
//! it names is built and checked: an old key that a rename left behind must still be accepted.
//! Cheap: nothing is run.

use std::path::{Path, PathBuf};
use twoball::scene::{Override, Scene};
use twoball::study::bench::robustness::StressSpec;
use twoball::study::sweep::SweepSpec;

/// Every `.toml` below `dir`, sorted.
fn tomls(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return out;
    };
    for e in entries {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(tomls(&p));
        } else if p.extension().is_some_and(|x| x == "toml") {
            out.push(p);
        }
    }
    out.sort();
    out
}

/// What a file is, from its top-level tables.
#[derive(Debug, PartialEq)]
enum Kind {
    Sweep,
    Robustness,
    Damper,
    Scene,
}

fn kind(text: &str, path: &Path) -> Kind {
    let table: toml::Table = text
        .parse()
        .unwrap_or_else(|e| panic!("{}: not TOML: {e}", path.display()));
    if table.contains_key("study") {
        Kind::Sweep
    } else if table.contains_key("stress") {
        Kind::Robustness
    } else if table.contains_key("frame") {
        Kind::Damper
    } else {
        Kind::Scene
    }
}

/// Reads one file as its command does and builds every scene it names; returns the number
/// of scenes built.
fn check(path: &Path) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    let name = path.display();
    match kind(&text, path) {
        Kind::Sweep => {
            let spec = SweepSpec::from_file(path).unwrap_or_else(|e| panic!("{name}: {e}"));
            let cases = spec.cases().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(!cases.is_empty(), "{name}: no cases");
            cases.len()
        }
        Kind::Robustness => {
            let spec = StressSpec::from_file(path).unwrap_or_else(|e| panic!("{name}: {e}"));
            let cases = spec.cases().unwrap_or_else(|e| panic!("{name}: {e}"));
            for c in &cases {
                let sets: Vec<Override> = c
                    .sets
                    .iter()
                    .map(|s| Override::parse(s).unwrap_or_else(|e| panic!("{name} {}: {e}", c.id)))
                    .collect();
                Scene::from_toml(c.base.text(), Path::new("."), &sets)
                    .unwrap_or_else(|e| panic!("{name} {}: {e}", c.id));
            }
            assert!(!cases.is_empty(), "{name}: no cases");
            cases.len()
        }
        Kind::Damper => {
            let file = twoball::damper::file::read(path).unwrap_or_else(|e| panic!("{name}: {e}"));
            let cases = file
                .cases(&Default::default())
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(!cases.is_empty(), "{name}: no cases");
            cases.len()
        }
        Kind::Scene => {
            Scene::from_file(path, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
            1
        }
    }
}

#[test]
fn every_committed_toml_is_accepted() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files: Vec<PathBuf> = ["verification", "examples"]
        .iter()
        .flat_map(|d| tomls(&root.join(d)))
        .collect();
    assert!(files.len() >= 7, "found only {files:?}");
    for f in &files {
        let scenes = check(f);
        println!("{}: {scenes} scene(s)", f.display());
    }
}

#[test]
fn a_misspelt_key_in_a_committed_kind_is_still_refused() {
    // The check above cannot pass by accepting anything: an unknown key fails each reader.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("verification/wall.toml")).unwrap();
    let bad = format!("{text}\n[solver]\ntime_step_factr = 0.9\n");
    let err = Scene::from_toml(&bad, root, &[]).unwrap_err().to_string();
    assert!(err.contains("time_step_factr"), "{err}");
    let sweep = std::fs::read_to_string(root.join("verification/head-on-study.toml")).unwrap();
    let bad = sweep.replacen("[study]", "[study]\ndiameterz = [0.01]", 1);
    let err = SweepSpec::from_toml(&bad, "bad.toml")
        .unwrap_err()
        .to_string();
    assert!(err.contains("diameterz"), "{err}");
}

/// No import cycle of more than two files in `src/` (`python3 scripts/import_cycles.py`
/// exits 1 and lists them while one exists): layers call down.
#[test]
fn the_source_has_no_import_cycle_of_more_than_two_files() {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = std::process::Command::new("python3")
        .arg(format!("{root}/scripts/import_cycles.py"))
        .arg(format!("{root}/src"))
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
}
