//! The gmsh path for meridian sections: meshes/ball_section.geo → gmsh (2D, recombined into
//! quadrangles) → `.msh` → `SectionMesh`, checked against the half-disc's geometry; and the
//! reader's refusals. gmsh is required under CI=true (tests/tool_support).

use crate::tool_support as tools;

use std::f64::consts::PI;
use std::process::Command;
use twoball::mesh::section::msh::{parse, read};
use twoball::mesh::section::SectionMesh;
use twoball::mesh::section::{area, corner_jacobians, quad_points, revolved_volume};

const R: f64 = 0.01;

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("twoball-section-msh-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

fn gmsh_section(format: &str, hp: f64) -> Option<SectionMesh> {
    if !tools::require(tools::gmsh(), "gmsh section meshes", "gmsh") {
        return None;
    }
    let out = tmp(&format!("section-{format}-{hp:e}.msh"));
    let geo = concat!(env!("CARGO_MANIFEST_DIR"), "/meshes/ball_section.geo");
    let run = Command::new("gmsh")
        .args([geo, "-2", "-format", format, "-setnumber", "hp"])
        .arg(hp.to_string())
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "gmsh failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    Some(read(&out).unwrap())
}

fn check_geometry(m: &SectionMesh, hp: f64) {
    // Counter-clockwise quads with positive corner Jacobians.
    for q in &m.quads {
        assert!(corner_jacobians(&quad_points(m, q))
            .iter()
            .all(|&j| j > 0.0));
    }
    // Area and volume of revolution of the inscribed polygon: below the exact values, by
    // less than the chord error of the longest facet L (area deficit L² / (6 R²) for
    // uniform facets; the bound allows twice that).
    let longest = m
        .boundary
        .iter()
        .map(|e| {
            let (p, q) = (m.nodes[e[0] as usize], m.nodes[e[1] as usize]);
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
        })
        .fold(0.0, f64::max);
    let bound = longest * longest / (3.0 * R * R);
    let (a, v) = (area(m), revolved_volume(m));
    let (a0, v0) = (PI * R * R / 2.0, 4.0 / 3.0 * PI * R.powi(3));
    assert!(
        a < a0 && a > a0 * (1.0 - bound),
        "area {a} vs {a0}, L {longest}"
    );
    assert!(
        v < v0 && v > v0 * (1.0 - bound),
        "volume {v} vs {v0}, L {longest}"
    );
    // Axis nodes exactly at r = 0, including both poles.
    let axis = &m.node_sets["axis"];
    assert!(axis.iter().all(|&i| m.nodes[i as usize][0] == 0.0));
    for pole in [R, -R] {
        assert!(axis
            .iter()
            .any(|&i| (m.nodes[i as usize][1] - pole).abs() < 1e-12));
    }
    // The boundary is the arc, chained from the south pole to the north pole.
    let b = &m.boundary;
    assert!((m.nodes[b[0][0] as usize][1] + R).abs() < 1e-12);
    assert!((m.nodes[b[b.len() - 1][1] as usize][1] - R).abs() < 1e-12);
    for w in b.windows(2) {
        assert_eq!(w[0][1], w[1][0]);
    }
    for e in b {
        for &i in e {
            let p = m.nodes[i as usize];
            assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - R).abs() < 1e-9);
        }
    }
    assert_eq!(&m.segment_sets["surface"], b);
    // The contact group: within 30 degrees of the pole, oriented as the boundary, finest
    // near the pole (gmsh's subdivision gives edges of about hp).
    let contact = &m.segment_sets["contact"];
    assert!(!contact.is_empty());
    let cos_c = 30f64.to_radians().cos();
    for e in contact {
        assert!(b.contains(e));
        assert!(e
            .iter()
            .all(|&i| m.nodes[i as usize][1] >= cos_c * R * (1.0 - 1e-9)));
    }
    let pole_seg = contact.last().unwrap();
    let (p, q) = (m.nodes[pole_seg[0] as usize], m.nodes[pole_seg[1] as usize]);
    let len = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
    assert!(
        len > 0.5 * hp && len < 2.0 * hp,
        "pole segment {len} for hp {hp}"
    );
}

#[test]
fn gmsh_sections_read_as_meridian_meshes() {
    for (format, hp) in [("msh41", 2e-4), ("msh22", 2e-4), ("msh41", 5e-5)] {
        if let Some(m) = gmsh_section(format, hp) {
            check_geometry(&m, hp);
        }
    }
}

#[test]
fn bad_section_files_are_refused_with_the_reason() {
    let head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    let nodes = "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n";
    let cases = [
        // No contact group.
        (
            format!("{head}{nodes}$Elements\n1\n1 3 2 1 1 1 2 3 4\n$EndElements\n"),
            "contact",
        ),
        // A node at r < 0.
        (
            format!(
                "{head}$Nodes\n4\n1 -1 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n\
                 $Elements\n1\n1 3 2 1 1 1 2 3 4\n$EndElements\n"
            ),
            "r >= 0",
        ),
        // A node off the plane.
        (
            format!(
                "{head}$Nodes\n4\n1 0 0 0.5\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n\
                 $Elements\n1\n1 3 2 1 1 1 2 3 4\n$EndElements\n"
            ),
            "z = 0",
        ),
        // A bow-tie quad.
        (
            format!("{head}{nodes}$Elements\n1\n1 3 2 1 1 1 3 2 4\n$EndElements\n"),
            "degenerate or partly inverted",
        ),
        // No quads.
        (
            format!("{head}{nodes}$Elements\n1\n1 1 2 1 1 1 2\n$EndElements\n"),
            "no quadrangles",
        ),
    ];
    for (text, why) in cases {
        let err = parse(text.as_bytes(), "bad.msh").unwrap_err().to_string();
        assert!(err.contains("bad.msh") && err.contains(why), "{why}: {err}");
    }
    // A clockwise quad is turned; a contact line on the boundary is kept, oriented.
    let text = format!(
        "{head}$PhysicalNames\n1\n1 7 \"contact\"\n$EndPhysicalNames\n{nodes}\
         $Elements\n2\n1 3 2 1 1 1 4 3 2\n2 1 2 7 1 3 2\n$EndElements\n"
    );
    let m = parse(text.as_bytes(), "ok.msh").unwrap();
    assert_eq!(m.quads, vec![[0, 1, 2, 3]]);
    assert_eq!(m.segment_sets["contact"], vec![[1, 2]]);
    assert_eq!(m.node_sets["axis"], vec![0, 3]);
}
