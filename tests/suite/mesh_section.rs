//! The built-in meridian-section mesher against geometry it must reproduce: the half-disc's
//! area and the ball's volume of revolution (converging at second order), counter-clockwise
//! quads with positive corner Jacobians, a surface arc that covers the circle from pole to
//! pole, exact axis nodes, the requested pole size, and the 3D mesher's cut plane.

use std::collections::HashMap;
use std::f64::consts::PI;
use twoball::mesh::ball::{ball as ball3d, BallSpec, Cut, CONTACT_HALF_ANGLE_DEG};
use twoball::mesh::section::{area, corner_jacobians, quad_area, quad_points, revolved_volume};
use twoball::mesh::section::{ball, SectionMesh, SectionSpec};

const R: f64 = 0.01;

fn spec(size: f64, pole: Option<f64>) -> SectionSpec {
    SectionSpec {
        diameter: 2.0 * R,
        size,
        pole_size: pole,
    }
}

/// The specs the tests sweep: uniform, the default scene's pole (D/200), a fine pole
/// (D/2000) and a very fine one.
fn specs() -> Vec<SectionSpec> {
    vec![
        spec(0.004, None),
        spec(0.002, None),
        spec(0.002, Some(1e-4)),
        spec(0.002, Some(1e-5)),
        spec(0.001, Some(2e-6)),
        spec(0.01, Some(5e-4)),
    ]
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

#[test]
fn quads_are_counter_clockwise_with_positive_corner_jacobians() {
    for s in specs() {
        let m = ball(&s).unwrap();
        assert!(!m.quads.is_empty());
        let mut worst = f64::INFINITY;
        for q in &m.quads {
            let p = quad_points(&m, q);
            assert!(quad_area(&p) > 0.0, "{s:?}: clockwise quad {q:?}");
            let e: Vec<f64> = (0..4).map(|i| dist(p[i], p[(i + 1) % 4])).collect();
            for (i, j) in corner_jacobians(&p).into_iter().enumerate() {
                // Scaled corner Jacobian: sin of the corner angle.
                let scaled = j / (e[i] * e[(i + 3) % 4]);
                worst = worst.min(scaled);
            }
        }
        assert!(worst > 0.3, "{s:?}: worst scaled corner Jacobian {worst}");
        assert!(m.nodes.iter().all(|p| p[0] >= 0.0), "{s:?}: node at r < 0");
    }
}

#[test]
fn the_mesh_is_conforming_and_its_boundary_is_the_arc_and_the_axis() {
    for s in specs() {
        let m = ball(&s).unwrap();
        // Every edge is used once in each direction (interior) or once (boundary).
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for q in &m.quads {
            for e in 0..4 {
                *edges.entry((q[e], q[(e + 1) % 4])).or_default() += 1;
            }
        }
        assert!(edges.values().all(|&c| c == 1), "{s:?}: repeated edge");
        let mut arc = 0;
        for &(a, b) in edges.keys() {
            if edges.contains_key(&(b, a)) {
                continue;
            }
            let (pa, pb) = (m.nodes[a as usize], m.nodes[b as usize]);
            if pa[0] == 0.0 && pb[0] == 0.0 {
                // Axis edges run from north to south (counter-clockwise around the section).
                assert!(pb[1] < pa[1], "{s:?}: axis edge {pa:?} -> {pb:?}");
            } else {
                assert!(m.boundary.contains(&[a, b]), "{s:?}: boundary edge {a}-{b}");
                arc += 1;
            }
        }
        assert_eq!(arc, m.boundary.len(), "{s:?}");
    }
}

#[test]
fn area_and_volume_of_revolution_converge_at_second_order() {
    let half_disc = PI * R * R / 2.0;
    let sphere = 4.0 / 3.0 * PI * R.powi(3);
    let mut errs = Vec::new();
    for h in [0.004, 0.002, 0.001, 0.0005] {
        let m = ball(&spec(h, None)).unwrap();
        let ea = (area(&m) - half_disc).abs() / half_disc;
        let ev = (revolved_volume(&m) - sphere).abs() / sphere;
        // Inscribed chords of about h/2: the area error is about (h/2)² / (6 R²)... bounded
        // by the segment-area estimate (π/6) (h / 2R)².
        assert!(ea < 0.6 * (h / R).powi(2), "h {h}: area error {ea}");
        assert!(ev < 0.6 * (h / R).powi(2), "h {h}: volume error {ev}");
        assert!(
            area(&m) < half_disc && revolved_volume(&m) < sphere,
            "h {h}"
        );
        errs.push((ea, ev));
    }
    for w in errs.windows(2) {
        let oa = (w[0].0 / w[1].0).log2();
        let ov = (w[0].1 / w[1].1).log2();
        assert!(oa > 1.8 && oa < 2.2, "area order {oa} from {errs:?}");
        assert!(ov > 1.8 && ov < 2.2, "volume order {ov} from {errs:?}");
    }
    // Pole refinement only makes the polygon closer to the circle.
    let coarse = ball(&spec(0.002, None)).unwrap();
    let fine = ball(&spec(0.002, Some(1e-5))).unwrap();
    assert!(area(&fine) > area(&coarse) && area(&fine) < half_disc);
}

#[test]
fn the_pole_elements_have_the_requested_size_and_grow_geometrically() {
    // Every pole size below the surface facet (about h / 2, where the mesh becomes uniform),
    // from a mild refinement to a very fine one.
    for (h, pole) in [
        (0.004, 1e-3),
        (0.004, 1e-4),
        (0.002, 5e-4),
        (0.002, 2e-4),
        (0.002, 1e-4),
        (0.002, 1e-5),
        (0.001, 2e-4),
        (0.001, 2e-6),
    ] {
        let m = ball(&spec(h, Some(pole))).unwrap();
        let north = m.nodes.iter().position(|p| *p == [0.0, R]).unwrap() as u32;
        let at_pole: Vec<&[u32; 4]> = m.quads.iter().filter(|q| q.contains(&north)).collect();
        assert_eq!(at_pole.len(), 1, "one quad at the pole");
        let p = quad_points(&m, at_pole[0]);
        for i in 0..4 {
            let e = dist(p[i], p[(i + 1) % 4]);
            assert!(
                (e - pole).abs() < 0.1 * pole,
                "pole {pole}: pole element edge {e}"
            );
        }
        // Along the axis and along the surface, segment lengths grow away from the pole by
        // at most 1.3 per element and never shrink by more than that.
        let mut axis: Vec<f64> = m.node_sets["axis"]
            .iter()
            .map(|&i| m.nodes[i as usize][1])
            .collect();
        axis.sort_by(|a, b| b.total_cmp(a));
        let steps: Vec<f64> = axis.windows(2).map(|w| w[0] - w[1]).collect();
        assert!((steps[0] - pole).abs() < 0.1 * pole, "{}", steps[0]);
        let arc: Vec<f64> = m
            .boundary
            .iter()
            .rev()
            .map(|e| dist(m.nodes[e[0] as usize], m.nodes[e[1] as usize]))
            .collect();
        assert!((arc[0] - pole).abs() < 0.1 * pole, "{}", arc[0]);
        let facet = PI * R / (2.0 * (PI * R / h).ceil());
        if pole > facet / 5.0 {
            continue; // a mild refinement has no long geometric run to check
        }
        for seq in [&steps, &arc] {
            for w in seq.windows(2) {
                let ratio = w[1] / w[0];
                assert!(
                    ratio < 1.3 && ratio > 1.0 / 1.3,
                    "pole {pole}: ratio {ratio}"
                );
            }
            // No edge larger than the far-field size.
            assert!(seq.iter().all(|&e| e <= h), "pole {pole}");
        }
        // Refinement stays local: the element count grows with log(R / pole) only.
        assert!(
            m.quads.len() < 10_000,
            "pole {pole}: {} quads",
            m.quads.len()
        );
    }
}

#[test]
fn the_surface_arc_lies_on_the_circle_and_covers_it_from_pole_to_pole() {
    for s in specs() {
        let m = ball(&s).unwrap();
        let b = &m.boundary;
        assert_eq!(
            m.nodes[b[0][0] as usize],
            [0.0, -R],
            "{s:?}: starts at the south pole"
        );
        assert_eq!(
            m.nodes[b[b.len() - 1][1] as usize],
            [0.0, R],
            "{s:?}: ends at the north pole"
        );
        let mut swept = 0.0;
        for w in b.windows(2) {
            assert_eq!(w[0][1], w[1][0], "{s:?}: gap in the arc");
        }
        for e in b {
            let (p, q) = (m.nodes[e[0] as usize], m.nodes[e[1] as usize]);
            for x in [p, q] {
                let rad = (x[0] * x[0] + x[1] * x[1]).sqrt();
                assert!((rad - R).abs() < 1e-15, "{s:?}: node {x:?} off the circle");
            }
            // Counter-clockwise: the polar angle increases along every segment.
            let dth = q[1].atan2(q[0]) - p[1].atan2(p[0]);
            assert!(dth > 0.0, "{s:?}");
            swept += dth;
        }
        assert!((swept - PI).abs() < 1e-12, "{s:?}: arc sweeps {swept}");
        assert_eq!(m.segment_sets["surface"], *b);
        let mut nodes: Vec<u32> = b.iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        assert_eq!(m.node_sets["surface"], nodes);
    }
}

#[test]
fn axis_nodes_are_exactly_on_the_axis_and_the_contact_set_is_around_the_pole() {
    let cos_c = CONTACT_HALF_ANGLE_DEG.to_radians().cos();
    for s in specs() {
        let m = ball(&s).unwrap();
        let axis = &m.node_sets["axis"];
        let near: Vec<u32> = (0..m.nodes.len() as u32)
            .filter(|&i| m.nodes[i as usize][0] < 1e-9 * R)
            .collect();
        assert_eq!(&near, axis, "{s:?}");
        assert!(axis.iter().all(|&i| m.nodes[i as usize][0] == 0.0));
        let contact = &m.segment_sets["contact"];
        assert_eq!(contact.last(), m.boundary.last(), "{s:?}: pole segment");
        for e in contact {
            assert!(m.boundary.contains(e));
            assert!(e
                .iter()
                .any(|&i| m.nodes[i as usize][1] >= cos_c * R * (1.0 - 1e-12)));
        }
        for e in &m.boundary {
            if e.iter().all(|&i| m.nodes[i as usize][1] >= cos_c * R) {
                assert!(contact.contains(e), "{s:?}: {e:?} missing from contact");
            }
        }
        let mut nodes: Vec<u32> = contact.iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        assert_eq!(m.node_sets["contact"], nodes);
    }
}

#[test]
fn the_section_is_the_3d_quarter_ball_on_its_cut_plane() {
    // The 3D ball's pole is at +x; its cut plane z = 0 holds the axis x and the radius y.
    let quarter = |h: f64, pole: Option<f64>| {
        ball3d(&BallSpec {
            diameter: 2.0 * R,
            size: h,
            pole_size: pole,
            cut: Cut::Quarter,
        })
        .unwrap()
    };
    // Unrefined: the same nodes and as many quads as the cut plane has faces.
    for h in [0.004, 0.002, 0.0015] {
        let m = ball(&spec(h, None)).unwrap();
        let q = quarter(h, None);
        let key = |r: f64, z: f64| ((r / R * 1e9).round() as i64, (z / R * 1e9).round() as i64);
        let mut ours: Vec<_> = m.nodes.iter().map(|p| key(p[0], p[1])).collect();
        let mut slice: Vec<_> = q
            .nodes
            .iter()
            .filter(|p| p[2] == 0.0)
            .map(|p| key(p[1], p[0]))
            .collect();
        ours.sort_unstable();
        slice.sort_unstable();
        assert_eq!(ours, slice, "h {h}");
        assert_eq!(m.quads.len(), q.face_sets["sym_z"].len(), "h {h}");
    }
    // Refined well below the surface facet: the pole faces agree within 5 %.
    for (h, pole) in [(0.002, 1e-4), (0.002, 2e-5), (0.004, 1e-4)] {
        let m = ball(&spec(h, Some(pole))).unwrap();
        let q = quarter(h, Some(pole));
        let north = m.nodes.iter().position(|p| *p == [0.0, R]).unwrap() as u32;
        let ours = quad_points(&m, m.quads.iter().find(|q| q.contains(&north)).unwrap());
        let pole3 = q.nodes.iter().position(|p| *p == [R, 0.0, 0.0]).unwrap() as u32;
        let face = q.face_sets["sym_z"]
            .iter()
            .find(|f| f.contains(&pole3))
            .unwrap()
            .map(|i| [q.nodes[i as usize][1], q.nodes[i as usize][0]]);
        let a2 = quad_area(&ours);
        let a3 = quad_area(&face).abs();
        assert!((a2 / a3 - 1.0).abs() < 0.1, "pole {pole}: areas {a2} {a3}");
        let e = |p: &[[f64; 2]; 4]| (0..4).map(|i| dist(p[i], p[(i + 1) % 4])).sum::<f64>();
        assert!(
            (e(&ours) / e(&face) - 1.0).abs() < 0.05,
            "pole {pole}: perimeters {} {}",
            e(&ours),
            e(&face)
        );
    }
}

#[test]
fn output_is_deterministic() {
    let a: SectionMesh = ball(&spec(0.002, Some(1e-5))).unwrap();
    let b = ball(&spec(0.002, Some(1e-5))).unwrap();
    assert_eq!(a, b);
}

#[test]
fn bad_sizes_are_refused_with_the_field_named() {
    for (s, field) in [
        (spec(0.0, None), "size"),
        (spec(f64::NAN, None), "size"),
        (spec(0.02, None), "size"),
        (spec(1e-6, None), "size"),
        (spec(0.002, Some(0.003)), "pole_size"),
        (spec(0.002, Some(1e-8)), "pole_size"),
        (spec(0.002, Some(-1e-4)), "pole_size"),
        (
            SectionSpec {
                diameter: -1.0,
                size: 0.002,
                pole_size: None,
            },
            "diameter",
        ),
    ] {
        let err = ball(&s).unwrap_err().to_string();
        assert!(err.contains(field), "{s:?}: {err}");
        assert!(!err.contains('\n'), "{err}");
    }
}
