//! Binary VTU (issue 25 item 6): compressed appended raw arrays as ParaView writes them,
//! named stress components and a time value per snapshot, read back independently with
//! meshio (installed by scripts/setup.sh) value for value.

use std::path::{Path, PathBuf};
use std::process::Command;
use twoball::mesh::ball::{ball, BallSpec, Cut};
use twoball::mesh::vtu::{write_with, Field, VtuFormat};

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("twoball-vtu-bin-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn meshio_available() -> bool {
    let ok = Command::new("python3")
        .args(["-c", "import meshio, numpy"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        eprintln!("NOTICE: python3 with meshio not found; skipping the meshio check (CI has it)");
    }
    ok
}

/// meshio's reading of `path`: the sums of every point and cell field per component, the
/// point and cell counts, the connectivity sum and the TimeValue, as JSON.
fn meshio_digest(path: &Path) -> serde_json::Value {
    let script = r#"
import json, sys, meshio, numpy as np
m = meshio.read(sys.argv[1])
out = {"points": len(m.points), "cells": sum(len(c.data) for c in m.cells),
       "connectivity_sum": int(sum(int(c.data.sum()) for c in m.cells)),
       "points_sum": np.asarray(m.points).sum(axis=0).tolist(),
       "time": [float(x) for x in np.ravel(m.field_data.get("TimeValue", []))]}
for k, v in m.point_data.items():
    out["p_" + k] = np.asarray(v).reshape(len(v), -1).sum(axis=0).tolist()
for k, blocks in m.cell_data.items():
    v = np.concatenate(blocks)
    out["c_" + k] = v.reshape(len(v), -1).sum(axis=0).tolist()
print(json.dumps(out))
"#;
    let o = Command::new("python3")
        .args(["-c", script])
        .arg(path)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "meshio failed on {}: {}",
        path.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0)
}

#[test]
fn binary_vtu_reads_back_in_meshio_with_named_components_and_time() {
    let m = ball(&BallSpec {
        diameter: 0.02,
        size: 0.002,
        pole_size: Some(2e-4),
        cut: Cut::Quarter,
    })
    .unwrap();
    let ne = m.hexes.len();
    let nn = m.nodes.len();
    // Fields whose every component differs, so a swapped or shifted array shows.
    let u: Vec<[f64; 3]> = m
        .nodes
        .iter()
        .map(|p| [1e-3 * p[0], -2e-3 * p[1], 3e-3 * p[2]])
        .collect();
    let stress: Vec<[f64; 6]> = (0..ne)
        .map(|e| {
            let x = e as f64;
            [-1e8 - x, 2e7 + x, 3e7, 4e6 * x, -5e6, 6e6 + 0.5 * x]
        })
        .collect();
    let eps: Vec<f64> = (0..ne).map(|e| e as f64 * 1e-6).collect();
    let dir = scratch("lib");
    let bin = dir.join("bin.vtu");
    let asc = dir.join("ascii.vtu");
    let time = 1.25e-5;
    for (path, format) in [(&bin, VtuFormat::Binary), (&asc, VtuFormat::Ascii)] {
        write_with(
            path,
            &m,
            &[Field::vectors("displacement", &u)],
            &[
                Field::sym_tensors("stress", &stress),
                Field::scalars("plastic_strain", &eps),
            ],
            Some(time),
            format,
        )
        .unwrap();
    }
    let bytes = std::fs::read(&bin).unwrap();
    let header = String::from_utf8_lossy(&bytes[..bytes.len().min(4000)]).into_owned();
    assert!(
        header.contains("compressor=\"vtkZLibDataCompressor\""),
        "{header}"
    );
    assert!(
        header.contains("<AppendedData encoding=\"raw\">"),
        "{header}"
    );
    assert!(
        header.contains(
            "ComponentName0=\"xx\" ComponentName1=\"yy\" ComponentName2=\"zz\" \
             ComponentName3=\"xy\" ComponentName4=\"yz\" ComponentName5=\"zx\""
        ),
        "{header}"
    );
    let ascii_len = std::fs::metadata(&asc).unwrap().len();
    assert!(
        (bytes.len() as u64) * 3 < ascii_len,
        "binary {} B is not much smaller than ASCII {ascii_len} B",
        bytes.len()
    );
    if !meshio_available() {
        return;
    }
    let expect_sum = |v: &[f64], k: usize, n: usize| -> f64 { v.iter().skip(k).step_by(n).sum() };
    for path in [&bin, &asc] {
        let d = meshio_digest(path);
        assert_eq!(d["points"], nn);
        assert_eq!(d["cells"], ne);
        let conn: u64 = m.hexes.iter().flatten().map(|&n| n as u64).sum();
        assert_eq!(d["connectivity_sum"], conn);
        assert!(close(d["time"][0].as_f64().unwrap(), time), "{d}");
        for k in 0..3 {
            let want: f64 = m.nodes.iter().map(|p| p[k]).sum();
            assert!(close(d["points_sum"][k].as_f64().unwrap(), want), "{d}");
            let want = expect_sum(u.as_flattened(), k, 3);
            assert!(close(d["p_displacement"][k].as_f64().unwrap(), want), "{d}");
        }
        for k in 0..6 {
            let want = expect_sum(stress.as_flattened(), k, 6);
            assert!(close(d["c_stress"][k].as_f64().unwrap(), want), "{k}: {d}");
        }
        let want: f64 = eps.iter().sum();
        assert!(
            close(d["c_plastic_strain"][0].as_f64().unwrap(), want),
            "{d}"
        );
    }
}

/// `twoball run --out DIR` writes binary snapshots by default: each reads in meshio with the
/// named stress components, and its TimeValue is the time the `.pvd` lists for it.
#[test]
fn run_snapshots_are_binary_with_the_pvd_time_in_each_file() {
    let dir = scratch("run");
    let out = Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args([
            "run",
            "--set",
            "reduction.symmetry=\"auto-3d\"",
            "--set",
            "output.vtu_snapshots=3",
            "--set",
            "ball1.mesh={size=0.004,pole_size=0.002}",
            "--set",
            "ball2.mesh={size=0.004,pole_size=0.002}",
            "--out",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let pvd = std::fs::read_to_string(dir.join("snapshots.pvd")).unwrap();
    let steps: Vec<(f64, String)> = pvd
        .lines()
        .filter(|l| l.contains("<DataSet"))
        .map(|l| {
            let attr = |k: &str| {
                l.split(&format!("{k}=\""))
                    .nth(1)
                    .unwrap()
                    .split('"')
                    .next()
                    .unwrap()
                    .to_string()
            };
            (attr("timestep").parse().unwrap(), attr("file"))
        })
        .collect();
    assert!(steps.len() >= 2, "{pvd}");
    if !meshio_available() {
        return;
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/check_vtu.py");
    for (t, f) in &steps {
        let head = std::fs::read(dir.join(f)).unwrap();
        assert!(
            String::from_utf8_lossy(&head[..200]).contains("vtkZLibDataCompressor"),
            "{f} is not compressed binary"
        );
        let o = Command::new("python3")
            .arg(&script)
            .arg(dir.join(f))
            .args([
                "--fields",
                "displacement,velocity,stress,von_mises,plastic_strain,part",
                "--components",
                "stress=xx,yy,zz,xy,yz,zx",
                "--components",
                "velocity=x,y,z",
                "--expect-time",
                &format!("{t:e}"),
            ])
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{f}: {}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
