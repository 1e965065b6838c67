//! The default scene (two D = 20 mm copper-fe balls, ±1 m/s) on the meridian section: one
//! ball against the symmetry plane, meshed by `mesh::section::ball`.
//!
//! `cargo run --release --example section_probe -- [SIZE_M] [POLE_SIZE_M] [one-point|b-bar]
//! [subcycled[:K]|single-rate]` prints e, δ_max (m), the contact duration (s), the peak force (N), the energy error and the
//! wall time (s) of one run (defaults: D/6 bulk, D/200 pole, one point,
//! subcycled).

use twoball::fe::elements::ring::QuadFormulation;
use twoball::fe::subcycle::Integration;
use twoball::material::Material;
use twoball::mesh::section::{ball, SectionSpec};
use twoball::study::run::section_impact::{HeadOn, Target};

/// Argument `i` as a length in metres, or `default`.
fn length(args: &[String], i: usize, default: f64) -> Result<f64, String> {
    match args.get(i) {
        None => Ok(default),
        Some(s) => match s.parse::<f64>() {
            Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
            _ => Err(format!("argument {i}: {s:?} is not a positive length in m")),
        },
    }
}

fn run(args: &[String]) -> Result<String, String> {
    let d = 0.02;
    let size = length(args, 1, d / 6.0)?;
    let pole = length(args, 2, d / 200.0)?;
    let formulation = match args.get(3).map(String::as_str) {
        None | Some("one-point") => QuadFormulation::default(),
        Some("b-bar") => QuadFormulation::SelectiveReduced,
        Some(o) => return Err(format!("argument 3: {o:?} is not one of one-point, b-bar")),
    };
    let integration = match args.get(4).map(String::as_str) {
        None | Some("subcycled") => Integration::subcycled(),
        Some("single-rate") => Integration::SingleRate,
        Some(o) if o.starts_with("subcycled:") => match o[10..].parse::<u8>() {
            Ok(k) => Integration::Subcycled { max_level: k },
            Err(_) => return Err(format!("argument 4: {o:?}: subcycled:K with K a level")),
        },
        Some(o) => {
            return Err(format!(
                "argument 4: {o:?} is not one of subcycled, single-rate"
            ))
        }
    };
    let spec = SectionSpec {
        diameter: d,
        size,
        pole_size: Some(pole),
    };
    let mesh = ball(&spec).map_err(|e| e.to_string())?;
    let material = Material::preset("copper-fe").map_err(|e| e.to_string())?;
    let mut h = HeadOn::new(mesh, material, 1.0, Target::MirrorBall);
    h.formulation = formulation;
    h.integration = integration;
    let r = h.run().map_err(|e| e.to_string())?;
    Ok(format!(
        "size {size:.3e} m, pole {pole:.3e} m, {formulation:?}, {integration:?}: {} quads, {} steps, e {:.5}, \
         delta_max {:.5e} m, t_c {:.5e} s, F_peak {:.1} N, energy error {:.1e}, wall {:.2} s",
        r.elements,
        r.steps,
        r.e,
        r.delta_max,
        r.contact_duration,
        r.peak_force,
        r.energy_error,
        r.wall_time_s
    ))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    match run(&args) {
        Ok(line) => println!("{line}"),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    }
}
