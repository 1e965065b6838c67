//! Subcycled integration of the meridian model against single-rate integration: on the
//! default scene (two D = 20 mm copper-fe balls at ±1 m/s, D/6 bulk, D/200 pole) the
//! power-of-two step classes reproduce e, δ_max and the contact duration within 0.1 % with
//! an energy error below 1e-3 and far fewer element updates; with one level they are Box 6.1.

use twoball::fe::contact::section::plane_nodal::{NodalPlane, Side};
use twoball::fe::interaction::Interaction;
use twoball::fe::materials::J2Material;
use twoball::fe::section::solver::{SectionModel, SectionSolver};
use twoball::fe::subcycle::Integration;
use twoball::material::Material;
use twoball::mesh::section::{ball, ladder_ball, SectionMesh, SectionSpec};
use twoball::study::run::section_impact::{HeadOn, ImpactResult, PlaneContact, Target};

const D: f64 = 0.02;

fn default_mesh() -> SectionMesh {
    ball(&SectionSpec {
        diameter: D,
        size: D / 6.0,
        pole_size: Some(D / 200.0),
    })
    .unwrap()
}

fn run(integration: Integration) -> ImpactResult {
    let material = Material::preset("copper-fe").unwrap();
    let mut h = HeadOn::new(default_mesh(), material, 1.0, Target::MirrorBall);
    h.integration = integration;
    h.run().unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b) / b
}

#[test]
fn subcycled_default_scene_agrees_with_single_rate() {
    let one = run(Integration::SingleRate);
    let sub = run(Integration::subcycled());
    eprintln!(
        "single-rate e {:.6} δ {:.6e} t_c {:.6e} err {:.1e}; subcycled e {:.6} δ {:.6e} t_c {:.6e} err {:.1e}",
        one.e,
        one.delta_max,
        one.contact_duration,
        one.energy_error,
        sub.e,
        sub.delta_max,
        sub.contact_duration,
        sub.energy_error
    );
    assert!(rel(sub.e, one.e).abs() < 1e-3, "e {} vs {}", sub.e, one.e);
    assert!(
        rel(sub.delta_max, one.delta_max).abs() < 1e-3,
        "δ_max {} vs {}",
        sub.delta_max,
        one.delta_max
    );
    assert!(
        rel(sub.contact_duration, one.contact_duration).abs() < 1e-3,
        "t_c {} vs {}",
        sub.contact_duration,
        one.contact_duration
    );
    assert!(sub.energy_error < 1e-3, "energy error {}", sub.energy_error);
    assert!(one.energy_error < 1e-3, "energy error {}", one.energy_error);
    // The fine step is the single-rate step.
    assert!(rel(sub.dt, one.dt).abs() < 1e-12);
}

/// On the ladder mesh of contact radius 600 µm (level 0), a surface ring's stiff spring set
/// the fine step while the node under it, limited by its quads alone, ran 2^2 times longer
/// steps: it sampled the ring's spring oscillation too slowly and the run gained 7.6e-3 of
/// the energy (e 0.32137 against 0.32253 single rate). A node's step is now capped at twice
/// its quad neighbours' limits. Fails with `NEIGHBOUR_RATIO` = 1e9 in `subcycle.rs`.
#[test]
fn a_spring_node_s_neighbours_keep_the_energy_on_the_ladder_mesh() {
    let material = Material::preset("copper-fe").unwrap();
    let run = |integration| {
        let mesh = ladder_ball(D, 600e-6, 0).unwrap();
        let mut h = HeadOn::new(mesh, material, 1.0, Target::MirrorBall);
        h.integration = integration;
        // The penalty plane's springs are what this guards.
        h.plane_contact = PlaneContact::Nodal;
        h.run().unwrap()
    };
    let one = run(Integration::SingleRate);
    let sub = run(Integration::subcycled());
    eprintln!(
        "single-rate e {:.5} err {:.1e}; subcycled e {:.5} err {:.1e}",
        one.e, one.energy_error, sub.e, sub.energy_error
    );
    assert!(sub.energy_error < 1e-3, "energy error {}", sub.energy_error);
    assert!(rel(sub.e, one.e).abs() < 3e-3, "e {} vs {}", sub.e, one.e);
}

#[test]
fn one_level_is_single_rate_integration() {
    let one = run(Integration::SingleRate);
    let sub = run(Integration::Subcycled { max_level: 0 });
    assert_eq!(sub.steps, one.steps);
    assert_eq!(sub.e.to_bits(), one.e.to_bits());
    assert_eq!(sub.delta_max.to_bits(), one.delta_max.to_bits());
    assert_eq!(sub.peak_force.to_bits(), one.peak_force.to_bits());
}

#[test]
fn default_scene_updates_under_a_third_of_the_quads_per_step() {
    let mesh = default_mesh();
    let material = Material::preset("copper-fe").unwrap();
    let n = mesh.nodes.len();
    let mut model = SectionModel::new(
        mesh.nodes.clone(),
        mesh.quads.clone(),
        J2Material::new(&material, false),
    );
    model.velocity = vec![[0.0, 1.0]; n];
    model.integration = Integration::Subcycled { max_level: 3 };
    let contact = &mesh.segment_sets["contact"];
    let plane =
        NodalPlane::new(&mesh, contact, D / 2.0, Side::Below, 10.0, material.youngs).unwrap();
    let s = SectionSolver::new(model, vec![Box::new(plane) as Box<dyn Interaction<2>>]).unwrap();
    let levels = s.node_levels();
    // The pole's contact nodes need the fine step; the bulk runs 2^3 times longer steps.
    let pole = (0..n)
        .max_by(|&a, &b| mesh.nodes[a][1].total_cmp(&mesh.nodes[b][1]))
        .unwrap();
    assert_eq!(levels[pole], 0);
    assert_eq!(levels.iter().copied().max(), Some(3));
    let per_step = s.updates_per_step();
    assert!(
        per_step < 0.3 * mesh.quads.len() as f64,
        "{per_step} updates per step of {} quads",
        mesh.quads.len()
    );
}

#[test]
fn a_level_above_the_cap_is_a_clear_error() {
    let material = Material::preset("copper-fe").unwrap();
    let mut h = HeadOn::new(default_mesh(), material, 1.0, Target::MirrorBall);
    h.integration = Integration::Subcycled { max_level: 11 };
    let e = h.run().unwrap_err().to_string();
    assert!(e.contains("subcycle_max_level") && e.contains("11"), "{e}");
}
