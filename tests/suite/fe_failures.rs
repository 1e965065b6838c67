//! The solver stops with a message that names where, when and why, instead of producing
//! garbage: a forced time step far above the Courant limit, and invalid settings.

use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::block::block;
use twoball::{Error, Material};

fn cube_model() -> Model {
    let mesh = block([2e-3; 3], [2, 2, 2]);
    let mut model = Model::new();
    let p = model
        .add_part(
            "cube",
            &mesh,
            Material::preset("steel").unwrap(),
            Formulation::OnePoint,
        )
        .unwrap();
    model
        .set_velocity_field(p, |x| [1000.0 * x[0], 0.0, 0.0])
        .unwrap();
    model
}

#[test]
fn unstable_step_is_reported_not_written() {
    // Courant limit of a 1 mm steel cube element is about 1.7e-7 s; force 20x that.
    let settings = Settings {
        fixed_dt: Some(3.4e-6),
        ..Settings::default()
    };
    let mut s = Solver::new(cube_model(), vec![], settings).unwrap();
    let err = s.run_until(|s| s.step_count() > 500).unwrap_err();
    let msg = err.to_string();
    assert!(matches!(err, Error::Numerical(_)), "{msg}");
    assert!(
        msg.contains("t = ") && (msg.contains("element") || msg.contains("node")),
        "{msg}"
    );
}

#[test]
fn invalid_settings_name_the_field() {
    for (settings, field) in [
        (
            Settings {
                time_step_factor: 1.5,
                ..Settings::default()
            },
            "solver.time_step_factor",
        ),
        (
            Settings {
                hourglass: -0.1,
                ..Settings::default()
            },
            "solver.hourglass",
        ),
        (
            Settings {
                fixed_dt: Some(f64::NAN),
                ..Settings::default()
            },
            "solver.fixed_dt",
        ),
        (
            Settings {
                energy_interval: 0,
                ..Settings::default()
            },
            "solver.energy_interval",
        ),
    ] {
        let msg = Solver::new(cube_model(), vec![], settings)
            .err()
            .expect("must fail")
            .to_string();
        assert!(msg.contains(field) && msg.contains("allowed"), "{msg}");
    }
}
