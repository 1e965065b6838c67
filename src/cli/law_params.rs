//! The `--param KEY=VALUE` lists of the `laws` subcommands.

use crate::error::{Error, Result};

/// Parses `KEY=VALUE` strings of flag `flag` into (key, value) pairs.
pub(super) fn parse_params(flag: &str, items: &[String]) -> Result<Vec<(String, f64)>> {
    items
        .iter()
        .map(|s| {
            let (k, v) = s.split_once('=').ok_or_else(|| {
                Error::Parse(format!("{flag} {s}: expected KEY=VALUE, e.g. {flag} e=0.7"))
            })?;
            let x: f64 = v
                .trim()
                .parse()
                .map_err(|_| Error::Parse(format!("{flag} {s}: value '{v}' is not a number")))?;
            Ok((k.trim().to_string(), x))
        })
        .collect()
}
