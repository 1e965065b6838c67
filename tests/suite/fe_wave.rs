//! Acceptance 3: a compression pulse in an elastic bar arrives at the far end at L/c within
//! 1 %. The bar's lateral faces are held (uniaxial strain), so the front travels at the
//! dilatational speed c = sqrt((λ + 2G)/ρ). A step pressure is applied on the end x = 0
//! through the `Interaction` hook; the free far end starts moving when the front arrives and
//! then moves at twice the particle velocity v_p = p/(ρ c). The arrival time is the instant its
//! velocity crosses v_p (the midpoint of the dispersed front, which travels at c).

use twoball::fe::interaction::{Interaction, InteractionEnergy, StepContext};
use twoball::fe::{Formulation, Model, Settings, Solver};
use twoball::mesh::block::block;
use twoball::Material;

/// A constant force on a node set, switched on at t = 0.
struct EndLoad {
    nodes: Vec<u32>,
    force: [f64; 3],
    work: f64,
}

impl Interaction for EndLoad {
    fn name(&self) -> &str {
        "end load"
    }
    fn add_forces(&mut self, ctx: &StepContext<'_>, f: &mut [[f64; 3]]) -> twoball::Result<()> {
        for &n in &self.nodes {
            let v = ctx.v[n as usize];
            self.work += ctx.dt * (0..3).map(|k| self.force[k] * v[k]).sum::<f64>();
            for (fk, lk) in f[n as usize].iter_mut().zip(&self.force) {
                *fk += lk;
            }
        }
        Ok(())
    }
    fn stable_time_step(&self, _mass: &[f64], _omega: &[f64]) -> Option<f64> {
        None
    }
    fn energy(&self) -> InteractionEnergy {
        InteractionEnergy {
            stored: 0.0,
            dissipated: 0.0,
            work: self.work,
        }
    }
}

fn arrival(formulation: Formulation) {
    let (len, h) = (0.1, 1e-3);
    let mesh = block([len, h, h], [100, 1, 1]);
    let mat = Material::preset("steel").unwrap();
    let mut model = Model::new();
    let p = model.add_part("bar", &mesh, mat, formulation).unwrap();
    model.part_mut(p).unwrap().elastic_only = true;
    for (set, axis) in [("y0", 1), ("y1", 1), ("z0", 2), ("z1", 2)] {
        model.fix_set(p, set, axis).unwrap();
    }
    let pressure = 10e6;
    let load_nodes = model.parts[0].node_sets["x0"].clone();
    let far: Vec<usize> = model.parts[0].node_sets["x1"]
        .iter()
        .map(|&n| n as usize)
        .collect();
    let per_node = pressure * h * h / load_nodes.len() as f64;
    let load = EndLoad {
        nodes: load_nodes,
        force: [per_node, 0.0, 0.0],
        work: 0.0,
    };
    let mut s = Solver::new(model, vec![Box::new(load)], Settings::default()).unwrap();
    let c = mat.dilatational_wave_speed();
    let vp = pressure / (mat.rho * c);
    let expected = len / c;
    let far_v = |s: &Solver| far.iter().map(|&n| s.v()[n][0]).sum::<f64>() / far.len() as f64;
    let (mut t_prev, mut v_prev) = (0.0, 0.0);
    let mut t_arrival = None;
    while s.time() < 1.5 * expected {
        s.step().unwrap();
        let v = far_v(&s);
        if v >= vp && t_arrival.is_none() {
            // Linear interpolation between the two samples around the crossing.
            t_arrival = Some(t_prev + (vp - v_prev) / (v - v_prev) * (s.time() - t_prev));
        }
        t_prev = s.time();
        v_prev = v;
    }
    let t = t_arrival.expect("the front must reach the far end");
    let err = t / expected - 1.0;
    eprintln!("{formulation:?}: arrival {t:.6e} s, L/c = {expected:.6e} s, error {:+.3} %, far-end velocity {:.4} v_p", 100.0 * err, v_prev / vp);
    assert!(err.abs() < 0.01, "{formulation:?}: {err}");
    // After arrival the free end moves at about 2 v_p.
    assert!((v_prev / vp - 2.0).abs() < 0.3, "{}", v_prev / vp);
}

#[test]
fn compression_front_arrives_at_l_over_c_one_point() {
    arrival(Formulation::OnePoint);
}

#[test]
fn compression_front_arrives_at_l_over_c_bbar() {
    arrival(Formulation::BBar);
}
