//! The resumable case cache that sweeps, the mesh bench and the law bench share: a folder
//! with one JSON file per finished case, named by the case's key and written atomically, so an
//! interrupted study reruns only what has no file and a rerun reads every answer back.
//!
//! A record says itself whether it belongs to the case asking for it (the caller's `accept`):
//! a file of another case, another model or an older format is not reused.

use crate::atomic::{ensure_dir, write_atomic};
use crate::error::{Error, Result};
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// How a record is laid out in its file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// Indented, one field a line (sweep and mesh-bench cases, read by people).
    Pretty,
    /// One line (the law bench's many points, committed to the repository).
    Compact,
}

/// A folder of case files `DIR/KEY.json`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CaseCache {
    dir: PathBuf,
}

impl CaseCache {
    /// The cache in folder `dir` (created by the first write).
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        CaseCache { dir: dir.into() }
    }

    /// The cache's folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The file of the case `key`.
    pub fn path(&self, key: &str) -> PathBuf {
        self.dir.join(format!("{key}.json"))
    }

    /// The record of case `key`, if its file exists, parses as `T` and `accept`s it; `None`
    /// otherwise (then the case is run again).
    pub fn read<T: DeserializeOwned>(
        &self,
        key: &str,
        accept: impl FnOnce(&T) -> bool,
    ) -> Option<T> {
        let text = std::fs::read_to_string(self.path(key)).ok()?;
        serde_json::from_str::<T>(&text).ok().filter(accept)
    }

    /// Writes the record of case `key` atomically, creating the folder.
    ///
    /// Errors: the folder or file cannot be written ([`Error::Io`] naming the path), a record
    /// that does not serialise.
    pub fn write<T: Serialize>(&self, key: &str, record: &T, layout: Layout) -> Result<()> {
        ensure_dir(&self.dir)?;
        let text = match layout {
            Layout::Pretty => serde_json::to_string_pretty(record),
            Layout::Compact => serde_json::to_string(record),
        }
        .map_err(|e| Error::Parse(format!("case {key}: {e}")))?;
        write_atomic(self.path(key), text.as_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_written_record_reads_back_and_a_refused_or_missing_one_is_none() {
        let dir = std::env::temp_dir().join(format!("twoball-case-cache-{}", std::process::id()));
        let cache = CaseCache::new(dir.join("cases"));
        assert_eq!(cache.read::<Vec<f64>>("a", |_| true), None);
        cache.write("a", &vec![1.5, 2.0], Layout::Compact).unwrap();
        assert_eq!(
            std::fs::read_to_string(cache.path("a")).unwrap(),
            "[1.5,2.0]"
        );
        assert_eq!(cache.read::<Vec<f64>>("a", |_| true), Some(vec![1.5, 2.0]));
        assert_eq!(cache.read::<Vec<f64>>("a", |v| v.len() == 3), None);
        assert_eq!(cache.read::<String>("a", |_| true), None);
        cache.write("b", &vec![1.0], Layout::Pretty).unwrap();
        assert_eq!(
            std::fs::read_to_string(cache.path("b")).unwrap(),
            "[\n  1.0\n]"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
