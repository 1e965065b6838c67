//! Crash-safe output: every file is written to a temporary name in its own folder, flushed to
//! disk and renamed over the target, so a reader (or a restarted sweep) sees either the
//! complete previous file, the complete new one, or none — never a truncated one.

use crate::error::{Error, Result};
use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// Marker in the names of temporary files; [`remove_stale_temporaries`] deletes such files.
pub const TMP_MARKER: &str = ".tmp-";

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Writes `bytes` to `path` atomically (temporary file in the same folder, fsync, rename).
///
/// Errors: the folder does not exist or is not writable ([`Error::Io`] naming the path).
pub fn write_atomic(path: impl AsRef<Path>, bytes: &[u8]) -> Result<()> {
    let path = path.as_ref();
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| Error::Parse(format!("{}: not a file name", path.display())))?;
    let tmp = dir.join(format!(
        ".{}{TMP_MARKER}{}-{}",
        name.to_string_lossy(),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        drop(f);
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::io(path, e));
    }
    Ok(())
}

/// Deletes temporary files left in `dir` by a killed writer; returns how many were removed.
/// Only for a folder no other process writes into (else see [`remove_temporaries_older_than`]).
pub fn remove_stale_temporaries(dir: &Path) -> Result<usize> {
    remove_temporaries_older_than(dir, std::time::Duration::ZERO)
}

/// Deletes temporary files in `dir` last modified at least `age` ago (a live writer renames
/// its temporary within moments, so old ones are a killed writer's); returns how many.
pub fn remove_temporaries_older_than(dir: &Path, age: std::time::Duration) -> Result<usize> {
    let mut n = 0;
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(Error::io(dir, e)),
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let name = name.to_string_lossy();
        let old_enough = age.is_zero()
            || entry
                .metadata()
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok())
                .is_some_and(|e| e >= age);
        if name.starts_with('.') && name.contains(TMP_MARKER) && old_enough {
            std::fs::remove_file(entry.path()).map_err(|e| Error::io(entry.path(), e))?;
            n += 1;
        }
    }
    Ok(n)
}

/// Creates `dir` and its parents if needed.
pub fn ensure_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_replace_whole_files_and_leave_no_temporaries() {
        let dir = std::env::temp_dir().join(format!("twoball-atomic-{}", std::process::id()));
        ensure_dir(&dir).unwrap();
        let p = dir.join("a.json");
        write_atomic(&p, b"first version, long").unwrap();
        write_atomic(&p, b"second").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"second");
        std::fs::write(dir.join(format!(".b.json{TMP_MARKER}1-0")), b"trunc").unwrap();
        assert_eq!(remove_stale_temporaries(&dir).unwrap(), 1);
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("a.json")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn missing_folder_is_an_io_error_naming_the_path() {
        let e = write_atomic(Path::new("/nonexistent-twoball-dir/x.json"), b"x").unwrap_err();
        assert!(e.to_string().contains("nonexistent-twoball-dir"), "{e}");
    }
}
