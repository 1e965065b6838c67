//! Static Hertz by dynamic relaxation: a quarter ball held on its equatorial disk, pressed by a
//! rigid frictionless plane moving slowly into its pole, then left to settle under
//! mass-proportional damping.

use twoball::fe::contact::mass_damping::MassDamping;
use twoball::fe::contact::{ContactParams, PressureSample, RigidPlane};
use twoball::fe::interaction::Interaction;
use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::ball::{ball, BallSpec, Cut};
use twoball::Material;

/// What the static compression gave.
#[derive(Debug, Clone)]
pub struct StaticHertz {
    /// Total contact force (full ball), N.
    pub force: f64,
    /// Hertz contact radius for that force, m, and centre pressure, Pa.
    pub a_hertz: f64,
    pub p0: f64,
    /// Contact radius from a fit of p² = p0² (1 − r²/a²) to the nodal pressures, m.
    pub a_fit: f64,
    /// Largest |p − p_Hertz(r)| / p0 over nodes with r < 0.8 a_hertz.
    pub max_pressure_error: f64,
    /// Samples (r, p) of the final state.
    pub samples: Vec<(f64, f64)>,
    pub elements: usize,
    /// Kinetic energy left at the end (J): how well the relaxation settled.
    pub final_kinetic: f64,
    /// Largest penetration of a ball node into the plane at the end (the pole's), m.
    pub max_penetration: f64,
}

/// Compresses by `depth` (m) over `t_load` (s), then relaxes for `t_hold` (s).
pub fn compress(
    depth: f64,
    pole: f64,
    size: f64,
    t_load: f64,
    t_hold: f64,
    alpha: f64,
) -> StaticHertz {
    let d = 0.02;
    let r = 0.5 * d;
    let mut mat = Material::preset("copper-fe").unwrap();
    mat.yield_strength = 1e15;
    let mut mesh = ball(&BallSpec {
        diameter: d,
        size,
        pole_size: Some(pole),
        cut: Cut::Quarter,
    })
    .unwrap();
    let tol = 1e-9 * d;
    let disk: Vec<u32> = (0..mesh.nodes.len() as u32)
        .filter(|&i| mesh.nodes[i as usize][0].abs() < tol)
        .collect();
    mesh.node_sets.insert("equator".into(), disk);
    let mut model = Model::new();
    let p = model
        .add_part("ball", &mesh, mat, Formulation::OnePoint)
        .unwrap();
    model.part_mut(p).unwrap().elastic_only = true;
    model.fix_set(p, "sym_y", 1).unwrap();
    model.fix_set(p, "sym_z", 2).unwrap();
    model.fix_set(p, "equator", 0).unwrap();
    let faces = model.parts[p].face_sets["contact"].clone();
    let speed = depth / t_load;
    let wall = RigidPlane::new(
        &model.nodes,
        &model.hexes,
        &faces,
        &mat,
        [r, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        ContactParams::default(),
    )
    .unwrap()
    .with_ramp([-speed, 0.0, 0.0], t_load);
    let probe = wall.probe();
    probe.record_pressures(true);
    let n = model.nodes.len();
    let elements = model.hexes.len();
    let inter: Vec<Box<dyn Interaction>> = vec![
        Box::new(wall),
        Box::new(MassDamping::new(alpha, 0..n).unwrap()),
    ];
    let mut s = Solver::new(model, inter, Settings::default()).unwrap();
    s.run_until(|s| s.time() >= t_load + t_hold).unwrap();
    let ke = s.energy().solid.kinetic;
    let data = probe.get();
    let mut out = finish(
        &data.pressures,
        4.0 * data.last.normal_force,
        &mat,
        r,
        elements,
    );
    out.final_kinetic = ke;
    out.max_penetration = data.last.max_penetration;
    out
}

/// Hertz comparison of a set of pressure samples.
pub fn finish(
    samples: &[PressureSample],
    force: f64,
    mat: &Material,
    r: f64,
    elements: usize,
) -> StaticHertz {
    let e_star = mat.plane_strain_modulus();
    let a_hertz = (3.0 * force * r / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * force / (2.0 * std::f64::consts::PI * a_hertz * a_hertz);
    let rp: Vec<(f64, f64)> = samples
        .iter()
        .map(|s| {
            (
                (s.position[1].powi(2) + s.position[2].powi(2)).sqrt(),
                s.pressure,
            )
        })
        .collect();
    let mut max_err: f64 = 0.0;
    let (mut sx, mut sy, mut sxx, mut sxy, mut k) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &(ri, pi) in &rp {
        if ri < 0.8 * a_hertz {
            let ph = p0 * (1.0 - (ri / a_hertz).powi(2)).sqrt();
            max_err = max_err.max((pi - ph).abs() / p0);
            let (x, y) = (ri * ri, pi * pi);
            sx += x;
            sy += y;
            sxx += x * x;
            sxy += x * y;
            k += 1.0;
        }
    }
    let slope = (k * sxy - sx * sy) / (k * sxx - sx * sx);
    let icpt = (sy - slope * sx) / k;
    let a_fit = (-icpt / slope).sqrt();
    StaticHertz {
        force,
        a_hertz,
        p0,
        a_fit,
        max_pressure_error: max_err,
        samples: rp,
        elements,
        final_kinetic: 0.0,
        max_penetration: 0.0,
    }
}
