//! Issue 27 item 7: the `paper-like` sweep mesh, uniform 2 mm elements with the soft penalty of
//! the paper's ANSYS FKN = 0.1 (twoball FKN 0.1 = `contact.penalty_factor` 0.01).

use std::path::Path;
use twoball::scene::MeshSettings;
use twoball::study::run::simulate::default_fkn;
use twoball::study::sweep::SweepSpec;

#[test]
fn paper_like_cases_run_uniform_2mm_with_fkn_0_1() {
    let spec = SweepSpec::from_file(Path::new("verification/paper-like-study.toml")).unwrap();
    let cases = spec.cases().unwrap();
    let mut seen = [0; 3];
    for c in &cases {
        for b in [&c.scene.ball1, &c.scene.ball2] {
            let MeshSettings::Builtin { size, pole_size } = b.mesh else {
                panic!("{}: not a built-in mesh", c.id)
            };
            assert_eq!((size, pole_size), (0.002, 0.002), "{}", c.id);
        }
        let fkn = default_fkn() * c.scene.contact.penalty_factor;
        let (k, want) = match c.params.mesh.as_str() {
            "paper-like" => (0, 0.1),
            "uniform-2mm" => (1, 10.0),
            "uniform-2mm-fkn1" => (2, 1.0),
            m => panic!("unexpected mesh {m}"),
        };
        assert!((fkn - want).abs() < 1e-12 * want, "{}: FKN {fkn}", c.id);
        assert_eq!(c.params.v1t, 0.0);
        seen[k] += 1;
    }
    assert_eq!(seen, [20, 20, 20]);
}

#[test]
fn a_mesh_penalty_outside_its_range_is_an_error() {
    let text = std::fs::read_to_string("verification/paper-like-study.toml")
        .unwrap()
        .replace("penalty_factor = 0.01", "penalty_factor = 0");
    let e = SweepSpec::from_toml(&text, "sweep")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("mesh[0].penalty_factor") && e.contains("1e-3"),
        "{e}"
    );
    assert_eq!(e.lines().count(), 1);
}
