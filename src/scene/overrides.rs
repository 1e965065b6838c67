//! `--set PATH=VALUE`: dotted-path overrides applied to the scene's TOML tree before it is
//! read, so that every override passes the same key and range checks as the file itself.

use super::reader::show;
use crate::error::{Error, Result};
use toml::{Table, Value};

/// One parsed override: the dotted path split into keys, and the value.
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    /// Keys from the root, e.g. `["ball1", "material", "yield"]`.
    pub path: Vec<String>,
    /// The value to put there.
    pub value: Value,
}

impl Override {
    /// Parses `PATH=VALUE`. VALUE is read as a TOML value (`1e11`, `[-2.5, 0, 0]`, `"steel"`,
    /// `{ preset = "steel" }`); a bare word that is not valid TOML is taken as a string
    /// (`ball1.material=steel`).
    pub fn parse(text: &str) -> Result<Override> {
        let bad = |why: &str| {
            Error::Parse(format!(
                "--set {text}: {why} (expected PATH=VALUE, e.g. ball1.material.yield=1e11)"
            ))
        };
        let (path, value) = text.split_once('=').ok_or_else(|| bad("no '='"))?;
        let path: Vec<String> = path
            .trim()
            .split('.')
            .map(|s| s.trim().to_string())
            .collect();
        if path.iter().any(|k| {
            k.is_empty()
                || !k
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        }) {
            return Err(bad(
                "the path must be dotted keys of letters, digits, '_' or '-'",
            ));
        }
        let value = value.trim();
        if value.is_empty() {
            return Err(bad("empty value"));
        }
        let value = match format!("v = {value}").parse::<Table>() {
            Ok(mut t) => t.remove("v").ok_or_else(|| bad("unreadable value"))?,
            Err(_) if !value.contains(['"', '[', ']', '{', '}', '\'']) => {
                Value::String(value.to_string())
            }
            Err(e) => {
                return Err(bad(&format!(
                    "value is not valid TOML ({})",
                    e.message().replace('\n', " ")
                )))
            }
        };
        Ok(Override { path, value })
    }

    /// Puts the value at its path in `root`, creating tables on the way. A material given as a
    /// preset name becomes `{ preset = NAME }` when a field below it is set, so presets take
    /// field-by-field overrides.
    pub fn apply(&self, root: &mut Table) -> Result<()> {
        let mut table = root;
        let (last, parents) = self.path.split_last().expect("path has at least one key");
        for (depth, key) in parents.iter().enumerate() {
            let dotted = self.path[..=depth].join(".");
            let slot = table
                .entry(key.clone())
                .or_insert_with(|| Value::Table(Table::new()));
            if let Value::String(name) = slot {
                if key == "material" {
                    let mut t = Table::new();
                    t.insert("preset".into(), Value::String(name.clone()));
                    *slot = Value::Table(t);
                }
            }
            table = match slot {
                Value::Table(t) => t,
                other => {
                    return Err(Error::Parse(format!(
                        "--set {}: {dotted} = {} is not a table, so it has no field {}",
                        self.path.join("."),
                        show(other),
                        self.path[depth + 1]
                    )))
                }
            };
        }
        table.insert(last.clone(), self.value.clone());
        Ok(())
    }
}
