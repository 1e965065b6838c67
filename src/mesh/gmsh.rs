//! Meshes from the gmsh program: a parametric `.geo` script meshed into a temporary file next
//! to the output, read and checked (hexahedra only, no inverted elements, closed outward
//! boundary), then renamed into place.

use super::msh::{self, Loaded};
use super::quality::{boundary_flux, summary};
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Runs `gmsh` on the script `geo` with the script parameters `sets` (gmsh `-setnumber NAME
/// VALUE`), checks the mesh and writes it to `output` (.msh 4.1); returns it as read.
///
/// Errors: `geo` is not a file ([`Error::Invalid`]); gmsh missing or failing
/// ([`Error::External`], with its error lines); a mesh `msh::read` refuses; an open or
/// inconsistently oriented boundary ([`Error::Numerical`]); a failed rename.
pub fn run(gmsh: &Path, geo: &Path, sets: &[(String, f64)], output: &Path) -> Result<Loaded> {
    if !geo.is_file() {
        return Err(Error::invalid(
            "geo",
            geo.display(),
            "an existing .geo file",
        ));
    }
    let mut cmd = Command::new(gmsh);
    cmd.arg(geo).args(["-3", "-format", "msh41"]);
    for (name, v) in sets {
        cmd.args(["-setnumber", name, &format!("{v:e}")]);
    }
    let tmp = temp_next_to(output);
    cmd.arg("-o").arg(&tmp);
    let out = cmd.output().map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            Error::External(format!(
                "gmsh not found ({}): install it (Debian/Ubuntu: apt-get install gmsh; or \
                 pip install gmsh) or pass --gmsh PATH",
                gmsh.display()
            ))
        } else {
            Error::External(format!("cannot run {}: {e}", gmsh.display()))
        }
    })?;
    let cleanup = || {
        let _ = std::fs::remove_file(&tmp);
    };
    if !out.status.success() || !tmp.is_file() {
        cleanup();
        let text = String::from_utf8_lossy(&out.stdout).to_string()
            + &String::from_utf8_lossy(&out.stderr);
        let tail: Vec<&str> = text
            .lines()
            .filter(|l| l.contains("rror"))
            .take(5)
            .collect();
        return Err(Error::External(format!(
            "gmsh failed on {} ({}): {}",
            geo.display(),
            out.status,
            if tail.is_empty() {
                text.lines().last().unwrap_or("").to_string()
            } else {
                tail.join(" | ")
            }
        )));
    }
    let loaded = match msh::read(&tmp) {
        Ok(l) => l,
        Err(e) => {
            cleanup();
            return Err(e);
        }
    };
    let s = summary(&loaded.mesh);
    let flux = boundary_flux(&loaded.mesh);
    let closed = s.volume > 0.0 && (flux - 3.0 * s.volume).abs() <= 1e-6 * 3.0 * s.volume;
    if !closed {
        cleanup();
        return Err(Error::Numerical(format!(
            "gmsh mesh of {} has an open or inconsistently oriented boundary (surface integral \
             of x.n = {flux:e}, 3V = {:e})",
            geo.display(),
            3.0 * s.volume
        )));
    }
    std::fs::rename(&tmp, output).map_err(|e| {
        cleanup();
        Error::io(output, e)
    })?;
    Ok(loaded)
}

/// A hidden temporary `.msh` name in the folder of `p`, unique to this process.
fn temp_next_to(p: &Path) -> PathBuf {
    let name = p
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let dir = match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    dir.join(format!(".{name}.{}.tmp.msh", std::process::id()))
}
