//! MSH reading and writing: round trips through our own writer and through the real gmsh
//! program, and malformed or hostile files that must give errors, never panics.

use crate::tool_support as tools;

use proptest::prelude::*;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::Command;
use twoball::mesh::ball::{ball, BallSpec, Cut};
use twoball::mesh::block::block;
use twoball::mesh::msh::{parse, to_msh41};
use twoball::mesh::quality::{boundary_flux, summary};
use twoball::mesh::Mesh;

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("twoball-mesh-io-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// gmsh is installed (under CI=true its absence fails the test).
fn gmsh_available(test: &str) -> bool {
    tools::require(tools::gmsh(), test, "gmsh")
}

fn small_ball() -> twoball::mesh::Mesh {
    ball(&BallSpec {
        diameter: 0.02,
        size: 0.004,
        pole_size: Some(5e-4),
        cut: Cut::Half,
    })
    .unwrap()
}

/// The same nodes, elements and boundary, and the same non-empty sets (face sets compared
/// as sets of outward quads, since the writer groups quads by the sets they belong to).
fn assert_same(a: &Mesh, b: &Mesh) {
    assert!(a.nodes == b.nodes, "nodes differ");
    assert!(a.hexes == b.hexes, "hexes differ");
    assert!(a.boundary == b.boundary, "boundary differs");
    let faces = |m: &Mesh| -> BTreeMap<String, Vec<[u32; 4]>> {
        m.face_sets
            .iter()
            .filter(|(_, v)| !v.is_empty())
            .map(|(k, v)| {
                let mut v = v.clone();
                v.sort_unstable();
                (k.clone(), v)
            })
            .collect()
    };
    let nodes = |m: &Mesh| -> BTreeMap<String, Vec<u32>> {
        m.node_sets
            .iter()
            .filter(|(_, v)| !v.is_empty())
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect()
    };
    assert!(faces(a) == faces(b), "face sets differ");
    assert!(nodes(a) == nodes(b), "node sets differ");
}

#[test]
fn own_output_reads_back_identically() {
    let m = small_ball();
    let text = to_msh41(&m).unwrap();
    let back = parse(text.as_bytes(), "ball.msh").unwrap();
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    assert_same(&back.mesh, &m);
    // Node sets that are not the nodes of a face set travel as point groups.
    let b = block([1.0, 2.0, 3.0], [2, 3, 4]);
    let back = parse(to_msh41(&b).unwrap().as_bytes(), "block.msh").unwrap();
    assert_same(&back.mesh, &b);
}

#[test]
fn gmsh_reads_twoball_output_and_twoball_reads_gmsh_output() {
    if !gmsh_available("gmsh_reads_twoball_output_and_twoball_reads_gmsh_output") {
        return;
    }
    let m = small_ball();
    let ours = tmp("ours.msh");
    twoball::mesh::msh::write(&ours, &m).unwrap();
    let check = Command::new("gmsh")
        .arg(&ours)
        .arg("-check")
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&check.stdout).to_string()
        + &String::from_utf8_lossy(&check.stderr);
    assert!(check.status.success(), "{log}");
    assert!(!log.contains("Error"), "gmsh -check complains:\n{log}");
    // gmsh re-writes it in every format it has; each must read back as the same solid.
    for (format, extra) in [
        ("msh41", None),
        ("msh41", Some("-bin")),
        ("msh22", None),
        ("msh22", Some("-bin")),
    ] {
        let out = tmp(&format!("resaved-{format}{}.msh", extra.unwrap_or("")));
        let mut cmd = Command::new("gmsh");
        cmd.arg(&ours).args(["-0", "-format", format]);
        if let Some(e) = extra {
            cmd.arg(e);
        }
        let st = cmd.arg("-o").arg(&out).output().unwrap();
        assert!(st.status.success(), "{format} {extra:?}");
        let back = twoball::mesh::msh::read(&out).unwrap().mesh;
        // gmsh renumbers nodes and prints 16 digits: the same solid up to rounding.
        let moments = |m: &Mesh| {
            let s2: f64 = m
                .nodes
                .iter()
                .map(|p| p[0] * p[0] + p[1] * p[1] + p[2] * p[2])
                .sum();
            let s1: f64 = m.nodes.iter().map(|p| p[0] + 2.0 * p[1] + 3.0 * p[2]).sum();
            (m.nodes.len(), m.hexes.len(), s1, s2, summary(m).volume)
        };
        let (a, b) = (moments(&back), moments(&m));
        assert_eq!(
            (a.0, a.1),
            (b.0, b.1),
            "counts differ after gmsh {format} {extra:?}"
        );
        assert!(
            (a.2 - b.2).abs() < 1e-12 && (a.3 - b.3).abs() < 1e-12 * b.3,
            "{a:?} {b:?}"
        );
        assert!((a.4 - b.4).abs() < 1e-12 * b.4, "volume {a:?} {b:?}");
        assert!(summary(&back).min_scaled_jacobian > 0.2);
        assert_eq!(
            back.face_sets["contact"].len(),
            m.face_sets["contact"].len()
        );
    }
}

#[test]
fn geo_round_trip_through_gmsh() {
    if !gmsh_available("geo_round_trip_through_gmsh") {
        return;
    }
    let out = tmp("geo.msh");
    let run = Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args([
            "mesh",
            "gmsh",
            "meshes/ball.geo",
            "--set",
            "D=0.02",
            "--set",
            "h=0.002",
            "--json",
            "-o",
        ])
        .arg(&out)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let loaded = twoball::mesh::msh::read(&out).unwrap();
    let m = &loaded.mesh;
    let s = summary(m);
    assert_eq!(json["elements"].as_u64().unwrap() as usize, s.elements);
    let v = 4.0 / 3.0 * std::f64::consts::PI * 1e-6;
    assert!((s.volume - v).abs() < 0.03 * v, "{}", s.volume);
    assert!(s.min_scaled_jacobian > 0.2);
    assert!((boundary_flux(m) - 3.0 * s.volume).abs() < 1e-9 * 3.0 * s.volume);
    // The physical surface is the whole closed sphere: every boundary quad, outward.
    assert_eq!(m.face_sets["surface"].len(), m.boundary.len());
    for &i in &m.node_sets["surface"] {
        let p = m.nodes[i as usize];
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((r - 0.01).abs() < 1e-9, "{r}");
    }
    // A larger h gives fewer elements: the parameters reach the script.
    let coarse = tmp("geo-coarse.msh");
    let run = Command::new(env!("CARGO_BIN_EXE_twoball"))
        .args([
            "mesh",
            "gmsh",
            "meshes/ball.geo",
            "--set",
            "D=0.02",
            "--set",
            "h=0.004",
            "-o",
        ])
        .arg(&coarse)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(run.status.success());
    assert!(twoball::mesh::msh::read(&coarse).unwrap().mesh.hexes.len() * 4 < s.elements);
}

/// A valid two-hex MSH 4.1 file, to corrupt in the tests below.
fn two_hexes() -> String {
    let mut b = block([1.0, 1.0, 2.0], [1, 1, 2]);
    b.node_sets.clear();
    to_msh41(&b).unwrap()
}

fn err(text: &str) -> String {
    match parse(text.as_bytes(), "bad.msh") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn malformed_files_are_errors_that_say_what() {
    let good = two_hexes();
    assert!(parse(good.as_bytes(), "good.msh").is_ok());
    // Truncated anywhere: an error, never a panic.
    for cut in (0..good.len()).step_by(7) {
        let _ = parse(&good.as_bytes()[..cut], "cut.msh");
    }
    assert!(err(&good[..good.len() / 2]).contains("bad.msh"));
    // Huge declared sizes are refused before allocating.
    let huge = good.replacen("3 1 5 2", "3 1 5 18446744073709551615", 1);
    assert!(err(&huge).contains("declares"), "{}", err(&huge));
    let huge_nodes = good.replacen("3 1 0 12", "3 1 0 99999999999", 1);
    assert!(err(&huge_nodes).contains("declares"));
    // Wrong counts: fewer elements declared than present.
    let short = good.replacen("3 1 5 2", "3 1 5 1", 1);
    assert!(err(&short).contains("expected"), "{}", err(&short));
    // Non-finite coordinates name the node.
    let nan = good.replacen(
        "0.00000000000000000e0 0.00000000000000000e0 0.00000000000000000e0",
        "nan 0 0",
        1,
    );
    assert!(err(&nan).contains("node 1"), "{}", err(&nan));
    // Dangling node references name the element.
    let dangling = good.replacen("\n1 1 2 4 3 5 6 8 7\n", "\n1 1 2 4 3 5 6 8 77\n", 1);
    assert!(err(&dangling).contains("element 1"), "{}", err(&dangling));
    // Unsupported element type (a tetrahedron block) names the type.
    let tet = good.replacen(
        "3 1 5 2\n1 1 2 4 3 5 6 8 7",
        "3 1 4 1\n1 1 2 4 5\n3 1 5 1",
        1,
    );
    let e = err(&tet);
    assert!(e.contains("type 4") && e.contains("tetrahedron"), "{e}");
    // No hexahedra at all.
    let none = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 0 0\n$EndNodes\n";
    assert!(err(none).contains("no volume elements"));
    assert!(err("hello").contains("$Section"));
    assert!(err("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n").contains("version"));
}

#[test]
fn inverted_elements_are_rejected_and_mirrored_ones_reoriented() {
    let good = two_hexes();
    // Element 1 with its bottom and top faces swapped: every corner inverted (mirrored order).
    let mirrored = good.replacen("\n1 1 2 4 3 5 6 8 7\n", "\n1 5 6 8 7 1 2 4 3\n", 1);
    let loaded = parse(mirrored.as_bytes(), "m.msh").unwrap();
    assert_eq!(loaded.warnings.len(), 1);
    assert!(loaded.warnings[0].contains("element 1"));
    assert!(summary(&loaded.mesh).min_scaled_jacobian > 0.99);
    // Two nodes swapped: a tangled element.
    let tangled = good.replacen("\n1 1 2 4 3 5 6 8 7\n", "\n1 2 1 4 3 5 6 8 7\n", 1);
    let e = err(&tangled);
    assert!(e.contains("element 1") && e.contains("inverted"), "{e}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]
    /// Random byte edits of a valid file never panic the reader.
    #[test]
    fn reader_survives_random_corruption(edits in prop::collection::vec((any::<usize>(), any::<u8>()), 1..8)) {
        let mut bytes = two_hexes().into_bytes();
        let n = bytes.len();
        for (at, b) in edits {
            bytes[at % n] = b;
        }
        let _ = parse(&bytes, "fuzz.msh");
    }

    /// Random binary garbage after a binary 4.1 header never panics the reader.
    #[test]
    fn reader_survives_binary_garbage(body in prop::collection::vec(any::<u8>(), 0..400)) {
        let mut bytes = b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n$Nodes\n".to_vec();
        bytes.extend_from_slice(&body);
        let _ = parse(&bytes, "fuzz.msh");
        let mut v22 = b"$MeshFormat\n2.2 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n$Elements\n3\n".to_vec();
        v22.extend_from_slice(&body);
        let _ = parse(&v22, "fuzz.msh");
    }
}
