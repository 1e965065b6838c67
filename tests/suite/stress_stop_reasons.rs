//! Issue 7 item 2: every instability stop of the explicit solver is provoked on a small
//! model and its message must name the element or node, the time and the likely cause.

use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::block::block;
use twoball::Material;

const SIDE: f64 = 2e-3;

/// A 2×2×2 copper block whose nodes move with the velocity field `v(x)`.
fn block_model(v: impl Fn([f64; 3]) -> [f64; 3]) -> Model {
    let mesh = block([SIDE; 3], [2; 3]);
    let mut m = Model::new();
    let mat = Material::preset("copper-fe").unwrap();
    m.add_part("cube", &mesh, mat, Formulation::OnePoint)
        .unwrap();
    m.velocity = m.nodes.iter().map(|&x| v(x)).collect();
    m
}

/// Runs at most `steps` steps and returns the stop message (panics if the run never stops).
fn stop_message(model: Model, settings: Settings, steps: usize) -> String {
    stop_error(model, settings, steps).to_string()
}

/// Runs at most `steps` steps and returns the stop (panics if the run never stops).
fn stop_error(model: Model, settings: Settings, steps: usize) -> twoball::Error {
    let mut s = Solver::new(model, vec![], settings).expect("valid start");
    for _ in 0..steps {
        if let Err(e) = s.step() {
            return e;
        }
    }
    panic!("the run did not stop within {steps} steps");
}

fn has_time(msg: &str) -> bool {
    msg.contains("t = ") && msg.contains(" s")
}

/// Uniform compression towards the centre at rate `rate` (1/s).
fn crush(rate: f64) -> impl Fn([f64; 3]) -> [f64; 3] {
    move |x| [0, 1, 2].map(|k| -rate * (x[k] - 0.5 * SIDE))
}

#[test]
fn inverted_element_names_the_element_time_and_cause() {
    // One fixed step longer than the time the compression needs to turn the cube inside out.
    let settings = Settings {
        fixed_dt: Some(3.0 / 1e3),
        ..Settings::default()
    };
    let msg = stop_message(block_model(crush(1e3)), settings, 5);
    assert!(msg.contains("element "), "{msg}");
    assert!(msg.contains("inverted"), "{msg}");
    assert!(has_time(&msg), "{msg}");
    assert!(msg.contains("time step too large"), "{msg}");
}

#[test]
fn time_step_collapse_names_the_controlling_element_time_and_cause() {
    // Crushing the cube shrinks its elements and with them the Courant step; stop when the
    // step falls below 98 % of the initial one (200 m/s at the corners: a few % strain).
    let settings = Settings {
        dt_collapse: 0.98,
        ..Settings::default()
    };
    let msg = stop_message(block_model(crush(2e5)), settings, 100_000);
    assert!(msg.contains("time step collapsed"), "{msg}");
    assert!(msg.contains("controlled by element "), "{msg}");
    assert!(has_time(&msg), "{msg}");
    assert!(msg.contains("crushed"), "{msg}");
}

#[test]
fn energy_growth_names_the_node_time_and_cause() {
    // A fixed step 1.5x the Courant limit: central differences amplify the vibration of the
    // freely vibrating cube every step; the balance check stops it before values overflow.
    let mat = Material::preset("copper-fe").unwrap();
    let h = SIDE / 2.0;
    let dt = 1.5 * h / mat.dilatational_wave_speed();
    let settings = Settings {
        fixed_dt: Some(dt),
        energy_interval: 1,
        energy_growth: 0.1,
        ..Settings::default()
    };
    // Tiny amplitude: the relative energy error grows long before any element inverts.
    let shake = |x: [f64; 3]| [1e-6 * (x[1] - 0.5 * SIDE) / SIDE, 5e-7 * (x[0] / SIDE), 0.0];
    let err = stop_error(block_model(shake), settings, 10_000);
    // The solver reports numbers; only the study, which knows the scene, names its keys.
    let twoball::Error::EnergyGrowth(g) = &err else {
        panic!("not an energy-growth stop: {err}")
    };
    assert!(g.created > g.limit && g.limit == 0.1, "{g:?}");
    assert!(
        g.time > 0.0 && g.step > 0 && g.fastest_node.1 > 0.0,
        "{g:?}"
    );
    let msg = err.to_string();
    assert!(msg.contains("energy grew by"), "{msg}");
    assert!(msg.contains("node "), "{msg}");
    assert!(has_time(&msg), "{msg}");
    assert!(msg.contains("time step is too large"), "{msg}");
    assert!(
        !msg.contains("solver.") && !msg.contains("contact."),
        "{msg}"
    );
    let advised = twoball::study::run::simulate::advice(err).to_string();
    assert!(advised.starts_with(&msg), "{advised}");
    assert!(
        advised.ends_with("lower solver.time_step_factor or contact.penalty_factor"),
        "{advised}"
    );
}

#[test]
fn non_finite_values_name_the_node_or_element_time_and_cause() {
    // An infinite initial velocity: the first position update makes the state non-finite.
    let mut model = block_model(|_| [0.0; 3]);
    model.velocity[5] = [f64::INFINITY, 0.0, 0.0];
    let msg = match Solver::new(model, vec![], Settings::default()) {
        Err(e) => e.to_string(),
        Ok(mut s) => {
            let mut m = None;
            for _ in 0..3 {
                if let Err(e) = s.step() {
                    m = Some(e.to_string());
                    break;
                }
            }
            m.expect("an infinite velocity must stop the run")
        }
    };
    assert!(msg.contains("non-finite"), "{msg}");
    assert!(msg.contains("node ") || msg.contains("element "), "{msg}");
    assert!(has_time(&msg), "{msg}");
    assert!(
        msg.contains("instability") || msg.contains("unstable"),
        "{msg}"
    );
}

#[test]
fn excessive_penetration_names_the_node_time_and_cause() {
    // A penalty a thousand times softer than default at 400 m/s: the balls sink into each other
    // by more than half an element before the contact can push back.
    let exe = env!("CARGO_BIN_EXE_twoball");
    let out = std::process::Command::new(exe)
        .args([
            "run",
            "--set",
            "reduction.symmetry=\"auto-3d\"",
            "--set",
            "contact.penalty_factor=0.001",
            "--set",
            "ball1.velocity=[200,0,0]",
            "--set",
            "ball2.velocity=[-200,0,0]",
        ])
        .args(["ball1", "ball2"].iter().flat_map(|b| {
            [
                "--set".to_string(),
                format!("{b}.mesh.size=0.0068"),
                "--set".to_string(),
                format!("{b}.mesh.pole_size=0.0034"),
            ]
        }))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let msg = err.lines().last().unwrap_or("");
    assert!(msg.starts_with("error: "), "{msg}");
    assert!(msg.contains("node ") && msg.contains("penetrates"), "{msg}");
    assert!(has_time(msg), "{msg}");
    assert!(msg.contains("raise the penalty factor"), "{msg}");
}
