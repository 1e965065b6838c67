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

/// Whether a line (or a fenced `sh` block's line) names a command a reader can run.
fn names_a_command(text: &str) -> bool {
    ["twoball ", "cargo ", "scripts/", "python3 "]
        .iter()
        .any(|c| text.contains(c))
}

/// The tables of one markdown text: (first line number, header row) of each table whose
/// section (from the heading before it to the heading after it) names no command.
fn tables_without_command(text: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let is_rule =
        |l: &str| l.starts_with('|') && l.chars().all(|c| matches!(c, '|' | '-' | ':' | ' '));
    let mut out = Vec::new();
    let mut i = 0;
    while i + 1 < lines.len() {
        if !(lines[i].starts_with('|') && is_rule(lines[i + 1])) {
            i += 1;
            continue;
        }
        let start = i;
        while i < lines.len() && lines[i].starts_with('|') {
            i += 1;
        }
        let from = (0..start)
            .rev()
            .find(|&j| lines[j].starts_with('#'))
            .unwrap_or(0);
        let to = (i..lines.len())
            .find(|&j| lines[j].starts_with('#'))
            .unwrap_or(lines.len());
        // Commands stand in backticks or in fenced blocks; a table's own cells count too.
        let section = lines[from..to].join("\n");
        if !names_a_command(&section) {
            out.push((start + 1, lines[start].to_string()));
        }
    }
    out
}

/// Every table in `docs/` stands in a section that prints the command reproducing it
/// (issue "study in rooms": docs are reference; a table with no command cannot be checked).
#[test]
fn every_docs_table_has_its_command_beside_it() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs");
    let mut missing = Vec::new();
    let mut entries: Vec<_> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    entries.sort();
    let mut tables = 0;
    for p in entries {
        let text = std::fs::read_to_string(&p).unwrap();
        tables += text.lines().filter(|l| l.starts_with("|---")).count();
        for (line, header) in tables_without_command(&text) {
            missing.push(format!("{}:{line}: {header}", p.display()));
        }
    }
    assert!(tables > 20, "docs/ should hold its tables; found {tables}");
    assert!(
        missing.is_empty(),
        "tables with no command in their section:\n{}",
        missing.join("\n")
    );
}

/// The table check finds a table whose section names no command, and passes one that does.
#[test]
fn the_docs_table_check_can_fail() {
    let bare = "# A\ntext\n\n| a | b |\n|---|---|\n| 1 | 2 |\n\n# B\n";
    assert_eq!(tables_without_command(bare).len(), 1);
    let told = "# A\n`twoball run`:\n\n| a | b |\n|---|---|\n| 1 | 2 |\n";
    assert!(tables_without_command(told).is_empty());
}

/// Every `.rs` file below `dir`, as (path relative to the crate root with `/`, text).
fn sources(dir: &Path, root: &Path) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(sources(&p, root));
        } else if p.extension().is_some_and(|x| x == "rs") {
            let rel = p
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            out.push((rel, std::fs::read_to_string(&p).unwrap()));
        }
    }
    out
}

/// Whether `name` is declared in `text`: an item (`fn`, `struct`, `trait`, `enum`, `type`,
/// `const`, `mod`, `static`) or an enum variant at the start of a line.
fn declares(text: &str, name: &str) -> bool {
    let item = [
        "fn", "struct", "trait", "enum", "type", "const", "mod", "static",
    ]
    .iter()
    .any(|k| {
        text.match_indices(&format!("{k} {name}")).any(|(i, m)| {
            let after = text[i + m.len()..].chars().next();
            !after.is_some_and(|c| c.is_alphanumeric() || c == '_')
        })
    });
    item || text.lines().any(|l| {
        let t = l.trim_start();
        t.strip_prefix(name)
            .and_then(|rest| rest.trim_start().chars().next())
            .is_some_and(|c| matches!(c, ',' | '(' | '{'))
    })
}

/// The architecture's tables name functions, types and files that exist: each backticked
/// identifier (`Type::method`, `function`, `Trait<2>::method`) is declared somewhere in
/// `src/`, and each backticked `.rs` path is a file: from the crate root, or the tail of a
/// path under `src/` (the tables abbreviate).
#[test]
fn architecture_names_exist() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let code = sources(&root.join("src"), root);
    let all: String = code
        .iter()
        .map(|(_, t)| t.as_str())
        .collect::<Vec<_>>()
        .join("\n");
    let doc = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let (mut names, mut files, mut missing) = (0, 0, Vec::new());
    for line in doc.lines().filter(|l| l.starts_with('|')) {
        for tok in line.split('`').skip(1).step_by(2) {
            if tok.ends_with(".rs") && !tok.contains('<') && !tok.contains(' ') {
                files += 1;
                let tail = format!("/{tok}");
                let found =
                    root.join(tok).is_file() || code.iter().any(|(p, _)| p.ends_with(&tail));
                if !found {
                    missing.push(format!("file {tok}"));
                }
                continue;
            }
            let path: Vec<&str> = tok.split("::").collect();
            let ident = |s: &str| {
                let s = s.split('<').next().unwrap_or("");
                !s.is_empty()
                    && !s.starts_with(|c: char| c.is_ascii_digit())
                    && s.chars().all(|c| c.is_alphanumeric() || c == '_')
            };
            if path.len() > 2
                || !path.iter().all(|s| ident(s))
                || !tok
                    .split('<')
                    .skip(1)
                    .all(|g| g.trim_end_matches('>').parse::<u32>().is_ok())
            {
                continue;
            }
            for seg in path {
                let seg = seg.split('<').next().unwrap();
                names += 1;
                if !declares(&all, seg) {
                    missing.push(format!("name {seg}"));
                }
            }
        }
    }
    assert!(names > 100 && files > 20, "names {names}, files {files}");
    assert!(
        missing.is_empty(),
        "docs/architecture.md names what src/ lacks: {missing:?}"
    );
}
