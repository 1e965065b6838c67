//! VTU output of a meridian section: read back independently by meshio (when python3 with
//! meshio is installed; CI=true makes its absence a failure), with the section's area, the
//! fields' cylindrical-to-picture mapping and the refusal of bad data.

use crate::tool_support as tools;

use std::process::Command;
use twoball::mesh::section::area;
use twoball::mesh::section::vtu::{to_vtu_bytes, write, SectionField};
use twoball::mesh::section::{ball, SectionSpec};
use twoball::mesh::vtu::VtuFormat;

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("twoball-section-vtu-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

fn section() -> twoball::mesh::section::SectionMesh {
    ball(&SectionSpec {
        diameter: 0.02,
        size: 0.004,
        pole_size: Some(5e-4),
    })
    .unwrap()
}

/// meshio reads the file back: quads only, the counts, the area (shoelace in x, y), the
/// displacement u = (1e-3 r, -2e-3 z) at every point, and the stress of cell k
/// (rr, zz, θθ, rz) = (k, 2k, 3k, 4k) Pa in the slots xx, yy, zz, xy.
const CHECK: &str = r#"
import sys, meshio, numpy as np
m = meshio.read(sys.argv[1])
assert {c.type for c in m.cells} == {"quad"}, [c.type for c in m.cells]
q = np.concatenate([c.data for c in m.cells])
assert len(q) == int(sys.argv[2]) and len(m.points) == int(sys.argv[3]), (len(q), len(m.points))
p = m.points[q][:, :, :2]
a = 0.5 * np.sum(p[:, :, 0] * np.roll(p[:, :, 1], -1, 1) - np.roll(p[:, :, 0], -1, 1) * p[:, :, 1], 1)
assert (a > 0).all() and abs(a.sum() / float(sys.argv[4]) - 1) < 1e-12, a.sum()
u = m.point_data["displacement"]
assert np.allclose(u, np.c_[1e-3 * m.points[:, 0], -2e-3 * m.points[:, 1], 0 * m.points[:, 0]], rtol=0, atol=1e-18)
s = np.concatenate(m.cell_data["stress"])
k = np.arange(len(q), dtype=float)
assert np.array_equal(s, np.c_[k, 2 * k, 3 * k, 4 * k, 0 * k, 0 * k]), s[:3]
e = np.concatenate(m.cell_data["plastic_strain"])
assert np.array_equal(e, 1e-6 * k)
print("ok")
"#;

#[test]
fn section_vtu_reads_in_meshio_with_mapped_fields() {
    let m = section();
    let u: Vec<[f64; 2]> = m
        .nodes
        .iter()
        .map(|p| [1e-3 * p[0], -2e-3 * p[1]])
        .collect();
    let stress: Vec<[f64; 4]> = (0..m.quads.len())
        .map(|k| [k as f64, 2.0 * k as f64, 3.0 * k as f64, 4.0 * k as f64])
        .collect();
    let eps: Vec<f64> = (0..m.quads.len()).map(|k| 1e-6 * k as f64).collect();
    let path = tmp("section.vtu");
    write(
        &path,
        &m,
        &[SectionField::Vectors("displacement", &u)],
        &[
            SectionField::Tensors("stress", &stress),
            SectionField::Scalars("plastic_strain", &eps),
        ],
        Some(1e-5),
    )
    .unwrap();
    // The ASCII form says what it holds without a reader.
    let text = String::from_utf8(
        to_vtu_bytes(
            &m,
            &[SectionField::Vectors("displacement", &u)],
            &[],
            None,
            VtuFormat::Ascii,
        )
        .unwrap(),
    )
    .unwrap();
    assert!(text.contains(&format!(
        "NumberOfPoints=\"{}\" NumberOfCells=\"{}\"",
        m.nodes.len(),
        m.quads.len()
    )));
    assert!(text.contains("Name=\"types\" format=\"ascii\">\n          9\n"));
    if !tools::require(
        tools::python("meshio, numpy"),
        "section_vtu_reads_in_meshio_with_mapped_fields",
        "python3 with meshio and numpy",
    ) {
        return;
    }
    let out = Command::new("python3")
        .args([
            "-c",
            CHECK,
            path.to_str().unwrap(),
            &m.quads.len().to_string(),
            &m.nodes.len().to_string(),
            &format!("{:e}", area(&m)),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success() && String::from_utf8_lossy(&out.stdout).contains("ok"),
        "meshio check failed: {}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn bad_fields_are_refused_and_nothing_is_written() {
    let m = section();
    let short = vec![[0.0; 2]; m.nodes.len() - 1];
    let path = tmp("bad.vtu");
    let err = write(
        &path,
        &m,
        &[SectionField::Vectors("velocity", &short)],
        &[],
        None,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("velocity"), "{err}");
    let mut nan = vec![0.0; m.quads.len()];
    nan[3] = f64::NAN;
    let err = write(&path, &m, &[], &[SectionField::Scalars("p", &nan)], None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("non-finite") && err.contains("cell 3"),
        "{err}"
    );
    assert!(!path.exists());
}
