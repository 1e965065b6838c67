//! A checked reader over a TOML table: every key is looked up by name, every key outside the
//! table's allowed set is an error naming its full dotted path, and every type or range error names the key, the value
//! and what is allowed. (Hand-written rather than serde-derived so that each message is one
//! line with the full dotted key, whatever nesting and `--set` overrides produced the value.)

use crate::error::{Error, Result};
use toml::{Table, Value};

/// A TOML table being read, with the dotted path that names it in messages.
pub(crate) struct Reader<'a> {
    path: String,
    table: &'a Table,
}

/// The TOML type name of a value, for messages.
fn type_name(v: &Value) -> &'static str {
    match v {
        Value::String(_) => "a string",
        Value::Integer(_) => "an integer",
        Value::Float(_) => "a number",
        Value::Boolean(_) => "a boolean",
        Value::Datetime(_) => "a date",
        Value::Array(_) => "an array",
        Value::Table(_) => "a table",
    }
}

/// A short one-line rendering of a value for messages (long values are cut).
pub(crate) fn show(v: &Value) -> String {
    let s = match v {
        Value::String(s) => format!("\"{s}\""),
        other => other.to_string(),
    };
    let s = s.replace('\n', " ");
    if s.chars().count() > 60 {
        format!("{}…", s.chars().take(60).collect::<String>())
    } else {
        s
    }
}

impl<'a> Reader<'a> {
    /// A reader over `table`, named `path` in messages (empty for the root).
    pub(crate) fn new(path: &str, table: &'a Table) -> Self {
        Reader {
            path: path.to_string(),
            table,
        }
    }

    /// The full dotted name of `key` in this table.
    pub(crate) fn key_path(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    /// The raw value of `key`.
    pub(crate) fn raw(&self, key: &str) -> Option<&'a Value> {
        self.table.get(key)
    }

    fn wrong_type(&self, key: &str, v: &Value, want: &str) -> Error {
        Error::Parse(format!(
            "{} = {} has the wrong type: expected {want}, found {}",
            self.key_path(key),
            show(v),
            type_name(v)
        ))
    }

    /// An error for a required key that is absent.
    pub(crate) fn missing(&self, key: &str, what: &str) -> Error {
        Error::Parse(format!(
            "missing required key {}: {what}",
            self.key_path(key)
        ))
    }

    /// A real number (integers accepted), checked finite and by `ok`.
    pub(crate) fn f64(
        &self,
        key: &str,
        ok: impl Fn(f64) -> bool,
        allowed: &str,
    ) -> Result<Option<f64>> {
        let Some(v) = self.raw(key) else {
            return Ok(None);
        };
        let x = number(v).ok_or_else(|| self.wrong_type(key, v, "a number"))?;
        if x.is_finite() && ok(x) {
            Ok(Some(x))
        } else {
            Err(Error::invalid(self.key_path(key), x, allowed))
        }
    }

    /// A non-negative integer, checked by `ok`.
    pub(crate) fn u64(
        &self,
        key: &str,
        ok: impl Fn(u64) -> bool,
        allowed: &str,
    ) -> Result<Option<u64>> {
        let Some(v) = self.raw(key) else {
            return Ok(None);
        };
        match v {
            Value::Integer(i) if *i >= 0 && ok(*i as u64) => Ok(Some(*i as u64)),
            Value::Integer(i) => Err(Error::invalid(self.key_path(key), i, allowed)),
            other => Err(self.wrong_type(key, other, "an integer")),
        }
    }

    /// A 3-vector of finite reals, each component checked by `ok`.
    pub(crate) fn vec3(
        &self,
        key: &str,
        ok: impl Fn(f64) -> bool,
        allowed: &str,
    ) -> Result<Option<[f64; 3]>> {
        self.array::<3>(key, ok, allowed)
    }

    /// An array of `N` finite reals, each component checked by `ok`.
    pub(crate) fn array<const N: usize>(
        &self,
        key: &str,
        ok: impl Fn(f64) -> bool,
        allowed: &str,
    ) -> Result<Option<[f64; N]>> {
        let Some(v) = self.raw(key) else {
            return Ok(None);
        };
        let what = format!("an array of {N} numbers");
        let Value::Array(a) = v else {
            return Err(self.wrong_type(key, v, &what));
        };
        if a.len() != N {
            return Err(Error::invalid(
                self.key_path(key),
                show(v),
                format!("an array of exactly {N} numbers"),
            ));
        }
        let mut out = [0.0; N];
        for (i, c) in a.iter().enumerate() {
            let x = number(c).ok_or_else(|| self.wrong_type(key, v, &what))?;
            if !(x.is_finite() && ok(x)) {
                return Err(Error::invalid(
                    format!("{}[{i}]", self.key_path(key)),
                    x,
                    allowed,
                ));
            }
            out[i] = x;
        }
        Ok(Some(out))
    }

    /// A string.
    pub(crate) fn string(&self, key: &str) -> Result<Option<&'a str>> {
        match self.raw(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.as_str())),
            Some(other) => Err(self.wrong_type(key, other, "a string")),
        }
    }

    /// One of a fixed set of words.
    pub(crate) fn choice(&self, key: &str, choices: &[&str]) -> Result<Option<&'a str>> {
        match self.string(key)? {
            None => Ok(None),
            Some(s) if choices.contains(&s) => Ok(Some(s)),
            Some(s) => Err(Error::invalid(
                self.key_path(key),
                format!("\"{s}\""),
                format!("one of {}", choices.join(", ")),
            )),
        }
    }

    /// A sub-table, as a reader.
    pub(crate) fn table(&self, key: &str) -> Result<Option<Reader<'a>>> {
        match self.raw(key) {
            None => Ok(None),
            Some(Value::Table(t)) => Ok(Some(Reader::new(&self.key_path(key), t))),
            Some(other) => Err(self.wrong_type(key, other, "a table")),
        }
    }

    /// Fails on the first key of this table that is not in `allowed`, listing the allowed
    /// keys. Called before reading, so a misspelt key is reported rather than the required
    /// key it fails to provide.
    pub(crate) fn only(&self, allowed: &[&str]) -> Result<()> {
        for k in self.table.keys() {
            if !allowed.contains(&k.as_str()) {
                return Err(Error::Parse(format!(
                    "unknown key {} (allowed here: {})",
                    self.key_path(k),
                    allowed.join(", ")
                )));
            }
        }
        Ok(())
    }
}

/// A TOML number (a float, or an integer taken as a real), else `None`.
fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Float(f) => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// Parses TOML text into a table; a syntax error becomes one line naming `origin`, line and
/// column.
pub(crate) fn parse_table(text: &str, origin: &str) -> Result<Table> {
    text.parse::<Table>().map_err(|e| {
        let (line, col) = match e.span() {
            Some(span) => {
                let before = &text[..span.start.min(text.len())];
                let line = before.matches('\n').count() + 1;
                let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
                (line, col)
            }
            None => (0, 0),
        };
        let msg = e.message().replace('\n', " ");
        Error::Parse(format!(
            "{origin}: TOML syntax error at line {line}, column {col}: {}",
            msg.trim()
        ))
    })
}
