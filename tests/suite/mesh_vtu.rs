//! VTU output: files that ParaView's readers accept (checked independently with meshio via
//! scripts/check_vtu.py when python3 and meshio are installed), and refusal to write bad data.

use crate::tool_support as tools;

use std::process::Command;
use twoball::mesh::ball::{ball, BallSpec, Cut};
use twoball::mesh::vtu::{to_vtu, write, write_pvd, write_with, Field, VtuFormat};

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("twoball-mesh-vtu-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// python3 with meshio is installed (under CI=true its absence fails the test).
fn meshio_available() -> bool {
    tools::require(
        tools::python("meshio, numpy"),
        "vtu_with_fields_reads_in_meshio (independent VTU check)",
        "python3 with meshio and numpy",
    )
}

#[test]
fn vtu_with_fields_reads_in_meshio() {
    let m = ball(&BallSpec {
        diameter: 0.02,
        size: 0.004,
        pole_size: Some(5e-4),
        cut: Cut::Quarter,
    })
    .unwrap();
    // Fields with known values: a rigid translation velocity, a displacement growing with x,
    // a uniaxial stress and a plastic strain ramp.
    let u: Vec<[f64; 3]> = m.nodes.iter().map(|p| [1e-3 * p[0], 0.0, 0.0]).collect();
    let v = vec![[-1.0, 0.5, 0.0]; m.nodes.len()];
    let stress = vec![[-1e8, 0.0, 0.0, 0.0, 0.0, 0.0]; m.hexes.len()];
    let eps: Vec<f64> = (0..m.hexes.len()).map(|e| e as f64 * 1e-6).collect();
    let path = tmp("ball.vtu");
    write_with(
        &path,
        &m,
        &[
            Field::vectors("displacement", &u),
            Field::vectors("velocity", &v),
        ],
        &[
            Field::sym_tensors("stress", &stress),
            Field::scalars("plastic_strain", &eps),
        ],
        None,
        VtuFormat::Ascii,
    )
    .unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(&format!(
        "NumberOfPoints=\"{}\" NumberOfCells=\"{}\"",
        m.nodes.len(),
        m.hexes.len()
    )));
    assert_eq!(
        text.matches("<DataArray").count(),
        text.matches("</DataArray>").count()
    );
    assert_eq!(text.matches("<DataArray").count(), 4 + 1 + 3);
    if !meshio_available() {
        return;
    }
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/check_vtu.py");
    let out = Command::new("python3")
        .arg(script)
        .arg(&path)
        .args(["--expect-cells", &m.hexes.len().to_string()])
        .args(["--expect-points", &m.nodes.len().to_string()])
        .args(["--fields", "displacement,velocity,stress,plastic_strain"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "check_vtu.py failed:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    // meshio's volume (its own hexahedron integration) matches ours.
    let line = String::from_utf8_lossy(&out.stdout).to_string();
    let vol: f64 = line
        .split("volume ")
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let ours = twoball::mesh::quality::summary(&m).volume;
    assert!((vol - ours).abs() < 1e-6 * ours, "{vol} vs {ours}");
    let pvd = tmp("series.pvd");
    write_pvd(&pvd, &[(0.0, "ball.vtu".into()), (1e-6, "ball.vtu".into())]).unwrap();
    assert!(std::fs::read_to_string(&pvd)
        .unwrap()
        .contains("timestep=\"1e-6\""));
}

#[test]
fn bad_fields_are_refused_and_nothing_is_written() {
    let m = twoball::mesh::block::block([1.0, 1.0, 1.0], [2, 2, 2]);
    let short = vec![[0.0; 3]; 3];
    assert!(to_vtu(&m, &[Field::vectors("u", &short)], &[]).is_err());
    let mut nan = vec![0.0; m.hexes.len()];
    nan[5] = f64::NAN;
    let path = tmp("nan.vtu");
    let e = write(&path, &m, &[], &[Field::scalars("eps", &nan)])
        .unwrap_err()
        .to_string();
    assert!(e.contains("eps") && e.contains("cell 5"), "{e}");
    assert!(!path.exists());
    let ok = vec![0.0; m.hexes.len()];
    assert!(to_vtu(&m, &[], &[Field::scalars("a<b", &ok)]).is_err());
    assert!(to_vtu(
        &m,
        &[],
        &[Field {
            name: "w",
            components: 2,
            values: &[0.0; 16]
        }]
    )
    .is_err());
}
