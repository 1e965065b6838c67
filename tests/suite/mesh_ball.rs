//! The built-in ball mesher against geometry it must reproduce: the sphere's volume (with
//! second-order convergence), the divergence theorem on its boundary, symmetry cuts and
//! a pole refinement with the requested smallest edge.

use std::collections::HashMap;
use std::f64::consts::PI;
use twoball::mesh::ball::{ball, BallSpec, Cut, CONTACT_HALF_ANGLE_DEG};
use twoball::mesh::quality::{boundary_flux, max_neighbour_size_ratio, summary};
use twoball::mesh::Mesh;

fn spec(size: f64, pole: Option<f64>, cut: Cut) -> BallSpec {
    BallSpec {
        diameter: 0.02,
        size,
        pole_size: pole,
        cut,
    }
}

fn sphere_volume(r: f64) -> f64 {
    4.0 / 3.0 * PI * r.powi(3)
}

/// Every face is shared by at most two elements, and every edge of the boundary surface by
/// exactly two boundary quads traversed in opposite directions (closed, consistently
/// oriented surface, no hanging nodes).
fn assert_closed(m: &Mesh) {
    let mut faces: HashMap<[u32; 4], u32> = HashMap::new();
    for h in &m.hexes {
        for f in twoball::mesh::topology::HEX_FACES {
            let mut k = f.map(|i| h[i]);
            k.sort_unstable();
            *faces.entry(k).or_default() += 1;
        }
    }
    assert!(
        faces.values().all(|&c| c <= 2),
        "a face shared by three elements"
    );
    assert_eq!(
        faces.values().filter(|&&c| c == 1).count(),
        m.boundary.len()
    );
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for q in &m.boundary {
        for e in 0..4 {
            let (a, b) = (q[e], q[(e + 1) % 4]);
            *edges.entry((a.min(b), a.max(b))).or_default() += if a < b { 1 } else { -1 };
        }
    }
    assert!(
        edges.values().all(|&s| s == 0),
        "boundary edge not shared by two opposite quads"
    );
}

#[test]
fn default_ball_volume_quality_and_closed_outward_boundary() {
    let m = ball(&spec(0.002, None, Cut::Full)).unwrap();
    let s = summary(&m);
    let v = sphere_volume(0.01);
    let err = (s.volume - v).abs() / v;
    assert!(err < 0.005, "volume error {err}");
    assert!(s.min_scaled_jacobian > 0.2, "{}", s.min_scaled_jacobian);
    assert!(s.max_edge <= 0.002, "{}", s.max_edge);
    let ratio = max_neighbour_size_ratio(&m);
    assert!(ratio <= 1.3, "neighbour size ratio {ratio}");
    assert_closed(&m);
    // Divergence theorem: the surface integral of x . n is 3 V.
    let flux = boundary_flux(&m);
    assert!(
        (flux - 3.0 * s.volume).abs() <= 1e-9 * flux.abs(),
        "{flux} vs {}",
        3.0 * s.volume
    );
    // Surface nodes lie on the sphere.
    for &i in &m.node_sets["surface"] {
        let p = m.nodes[i as usize];
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((r - 0.01).abs() < 1e-15, "{r}");
    }
}

#[test]
fn volume_error_shrinks_quadratically() {
    // Quarter balls (a quarter of the full volume by symmetry) keep the finest mesh small.
    let v = sphere_volume(0.01) / 4.0;
    let errs: Vec<f64> = [0.004, 0.002, 0.001]
        .iter()
        .map(|&h| (summary(&ball(&spec(h, None, Cut::Quarter)).unwrap()).volume - v).abs() / v)
        .collect();
    for w in errs.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!(order >= 1.9, "observed order {order} from errors {errs:?}");
    }
}

#[test]
fn pole_refinement_puts_the_smallest_edge_at_the_pole() {
    let m = ball(&spec(0.002, Some(1e-4), Cut::Full)).unwrap();
    let s = summary(&m);
    assert!(
        (s.min_edge - 1e-4).abs() <= 0.2e-4,
        "min edge {}",
        s.min_edge
    );
    let p = s.min_edge_at;
    let dist = ((p[0] - 0.01).powi(2) + p[1] * p[1] + p[2] * p[2]).sqrt();
    assert!(dist < 0.002, "shortest edge {dist} m from the pole");
    // The cells at the pole itself have the requested size (edges within 5 % of it).
    let pole = m.nodes.iter().position(|p| *p == [0.01, 0.0, 0.0]).unwrap() as u32;
    let at_pole: Vec<&[u32; 8]> = m.hexes.iter().filter(|h| h.contains(&pole)).collect();
    assert_eq!(at_pole.len(), 4);
    for h in at_pole {
        for [a, b] in twoball::mesh::quality::HEX_EDGES {
            let (p, q) = (m.nodes[h[a] as usize], m.nodes[h[b] as usize]);
            let e = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
            assert!((e - 1e-4).abs() < 0.05e-4, "pole edge {e}");
        }
    }
    assert!(s.elements < 80_000, "{}", s.elements);
    assert!(s.min_scaled_jacobian > 0.2);
    assert!(max_neighbour_size_ratio(&m) <= 1.3);
    assert_closed(&m);
    let flux = boundary_flux(&m);
    assert!((flux - 3.0 * s.volume).abs() <= 1e-9 * flux.abs());
    // Far from the pole the mesh is as coarse as the unrefined one.
    assert!(
        (s.max_edge - summary(&ball(&spec(0.002, None, Cut::Full)).unwrap()).max_edge).abs()
            < 1e-12
    );
}

#[test]
fn cuts_keep_their_side_with_nodes_exactly_on_the_planes() {
    let full = summary(&ball(&spec(0.002, Some(2e-4), Cut::Full)).unwrap()).volume;
    for (cut, parts) in [(Cut::Half, 2.0), (Cut::Quarter, 4.0)] {
        let m = ball(&spec(0.002, Some(2e-4), cut)).unwrap();
        let s = summary(&m);
        assert!((s.volume * parts - full).abs() < 1e-12 * full, "{cut:?}");
        assert!(m.nodes.iter().all(|p| p[2] >= 0.0));
        let sym_z = &m.node_sets["sym_z"];
        assert!(!sym_z.is_empty());
        assert!(sym_z.iter().all(|&i| m.nodes[i as usize][2] == 0.0));
        // Every node with z == 0 is in the set, and every node near the plane is on it.
        let near: Vec<u32> = (0..m.nodes.len() as u32)
            .filter(|&i| m.nodes[i as usize][2].abs() < 1e-9)
            .collect();
        assert_eq!(&near, sym_z);
        if cut == Cut::Quarter {
            assert!(m.nodes.iter().all(|p| p[1] >= 0.0));
            assert!(m.node_sets["sym_y"]
                .iter()
                .all(|&i| m.nodes[i as usize][1] == 0.0));
            assert!(!m.face_sets["sym_y"].is_empty());
        } else {
            assert!(m.node_sets["sym_y"].is_empty());
        }
        // Boundary = sphere + cut planes; the divergence theorem holds for the whole.
        let f = &m.face_sets;
        assert_eq!(
            f["surface"].len() + f["sym_y"].len() + f["sym_z"].len(),
            m.boundary.len()
        );
        let flux = boundary_flux(&m);
        assert!((flux - 3.0 * s.volume).abs() <= 1e-9 * flux.abs());
        assert_closed(&m);
    }
}

#[test]
fn contact_patch_surrounds_the_pole() {
    let m = ball(&spec(0.002, Some(1e-4), Cut::Half)).unwrap();
    let cos_c = CONTACT_HALF_ANGLE_DEG.to_radians().cos();
    let contact = &m.node_sets["contact"];
    // Every surface node within the contact angle is in the set, and nothing far beyond it.
    for &i in &m.node_sets["surface"] {
        if m.nodes[i as usize][0] >= cos_c * 0.01 {
            assert!(contact.binary_search(&i).is_ok());
        }
    }
    let cos_outer = (CONTACT_HALF_ANGLE_DEG + 10.0).to_radians().cos();
    assert!(contact
        .iter()
        .all(|&i| m.nodes[i as usize][0] >= cos_outer * 0.01));
    let pole = contact
        .iter()
        .find(|&&i| m.nodes[i as usize] == [0.01, 0.0, 0.0]);
    assert!(pole.is_some(), "the pole node is in the contact set");
    // Contact quads are outward: their normals point away from the centre.
    for q in &m.face_sets["contact"] {
        let p = q.map(|i| m.nodes[i as usize]);
        let d1 = [0, 1, 2].map(|a| p[2][a] - p[0][a]);
        let d2 = [0, 1, 2].map(|a| p[3][a] - p[1][a]);
        let n = [
            d1[1] * d2[2] - d1[2] * d2[1],
            d1[2] * d2[0] - d1[0] * d2[2],
            d1[0] * d2[1] - d1[1] * d2[0],
        ];
        assert!(n[0] * p[0][0] + n[1] * p[0][1] + n[2] * p[0][2] > 0.0);
    }
    // The patch covers the 30-degree cap and a little more (the half ball holds half of it).
    let area: f64 = m.face_sets["contact"]
        .iter()
        .map(|q| {
            let p = q.map(|i| m.nodes[i as usize]);
            let d1 = [0, 1, 2].map(|a| p[2][a] - p[0][a]);
            let d2 = [0, 1, 2].map(|a| p[3][a] - p[1][a]);
            let n = [
                d1[1] * d2[2] - d1[2] * d2[1],
                d1[2] * d2[0] - d1[0] * d2[2],
                d1[0] * d2[1] - d1[1] * d2[0],
            ];
            0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
        })
        .sum();
    let cap = PI * 1e-4 * (1.0 - cos_c);
    let outer = PI * 1e-4 * (1.0 - cos_outer);
    assert!(area > cap && area < outer, "{area} vs {cap}..{outer}");
}

#[test]
fn two_balls_in_one_numbering() {
    let one = ball(&spec(0.004, Some(5e-4), Cut::Quarter)).unwrap();
    let two = one.mirrored_x().translated([0.02, 0.0, 0.0]);
    let s2 = summary(&two);
    assert!(
        s2.min_scaled_jacobian > 0.2,
        "mirroring keeps Jacobians positive"
    );
    assert!((boundary_flux(&two) - 3.0 * s2.volume).abs() <= 1e-9 * s2.volume);
    // Ball 2's pole faces ball 1's pole at x = R.
    assert!(two.nodes.contains(&[0.01, 0.0, 0.0]));
    let mut both = one.clone();
    both.prefix_sets("ball1");
    let (node_off, elem_off) = both.append(&two, "ball2").unwrap();
    assert_eq!((node_off, elem_off), (one.nodes.len(), one.hexes.len()));
    assert_eq!(
        both.node_sets["ball2.contact"].len(),
        one.node_sets["contact"].len()
    );
    assert_eq!(
        both.node_sets["ball2.contact"][0],
        one.node_sets["contact"][0] + node_off as u32
    );
    assert!(both.node_sets.contains_key("ball1.sym_z"));
    let s = summary(&both);
    assert!((s.volume - 2.0 * summary(&one).volume).abs() < 1e-15);
    assert!((boundary_flux(&both) - 3.0 * s.volume).abs() <= 1e-9 * s.volume);
}

#[test]
fn deterministic_and_rejects_bad_input() {
    let a = ball(&spec(0.003, Some(3e-4), Cut::Half)).unwrap();
    let b = ball(&spec(0.003, Some(3e-4), Cut::Half)).unwrap();
    assert_eq!(a, b);
    for bad in [
        BallSpec {
            diameter: f64::NAN,
            size: 0.002,
            pole_size: None,
            cut: Cut::Full,
        },
        BallSpec {
            diameter: -0.02,
            size: 0.002,
            pole_size: None,
            cut: Cut::Full,
        },
        BallSpec {
            diameter: 0.02,
            size: 0.0,
            pole_size: None,
            cut: Cut::Full,
        },
        BallSpec {
            diameter: 0.02,
            size: 0.02,
            pole_size: None,
            cut: Cut::Full,
        },
        BallSpec {
            diameter: 0.02,
            size: 1e-6,
            pole_size: None,
            cut: Cut::Full,
        },
        BallSpec {
            diameter: 0.02,
            size: 0.002,
            pole_size: Some(0.003),
            cut: Cut::Full,
        },
        BallSpec {
            diameter: 0.02,
            size: 0.002,
            pole_size: Some(1e-9),
            cut: Cut::Full,
        },
        BallSpec {
            diameter: 0.02,
            size: 0.002,
            pole_size: Some(f64::INFINITY),
            cut: Cut::Full,
        },
    ] {
        let e = ball(&bad).unwrap_err().to_string();
        assert!(e.contains("invalid"), "{e}");
    }
    assert!("sideways".parse::<Cut>().is_err());
    assert_eq!("quarter".parse::<Cut>().unwrap(), Cut::Quarter);
}
