//! What mass scaling (`fe::section::mass_scaling`) saves and costs on a head-on section: per
//! mesh and budget, the steps, the initial stable step, the wall time and e, δ_max, the
//! contact duration and the peak force; the table of verification/contact-penalty.md ("Mass scaling
//! of the contact region").
//!
//! `cargo run --release --example mass_scaling -- V_REL MESHES BUDGETS [MATERIAL]`: two
//! identical D = 20 mm balls (MATERIAL a preset, default copper-fe) at relative speed V_REL
//! (m/s); MESHES a comma list of `band:L` (the banded family's level L around the contact
//! edge of a plain level-0 run, four-fold band through the depth: `study::convergence::phase_band`),
//! `bandSPLIT:L` (the same with a SPLIT-fold band, `band5:L` the bench's five-fold band
//! confined to the surface) and `plain:L` (the
//! plain family's level L, sized from Hertz's contact radius); BUDGETS a comma list of
//! added-mass fractions (0: none).

use twoball::material::Material;
use twoball::mesh::section::SectionMesh;
use twoball::study::convergence::phase_band::{banded_mesh, contact_edge};
use twoball::study::convergence::phase_ensemble::{family_mesh, hertz_contact_radius, HeadOnCase};
use twoball::study::run::section_impact::{HeadOn, Target};

/// A comma list of `T`, or an error naming `what`.
fn list<T: std::str::FromStr>(s: &str, what: &str) -> Result<Vec<T>, String> {
    s.split(',')
        .map(|x| x.parse().map_err(|_| format!("{what}: {x:?} is not valid")))
        .collect()
}

fn main() {
    if let Err(e) = run() {
        eprintln!("mass_scaling: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        return Err("usage: V_REL MESHES BUDGETS [MATERIAL]".into());
    }
    let v: f64 = args[1].parse().map_err(|_| "V_REL is not a speed")?;
    let budgets: Vec<f64> = list(&args[3], "BUDGETS")?;
    let material = match args.get(4) {
        Some(m) => Material::preset(m).map_err(|e| e.to_string())?,
        None => Material::copper_fe(),
    };
    let case = HeadOnCase {
        relative_speed: v,
        material,
        ..HeadOnCase::default_scene()
    };
    let (edge, _) = contact_edge(&case).map_err(|e| e.to_string())?;
    let a = hertz_contact_radius(&case);
    println!("V_REL {v} m/s: contact edge {edge:.4e} m, Hertz contact radius {a:.4e} m");
    println!("mesh | budget | quads | steps | dt (s) | wall (s) | e | δ_max (m) | t_c (s) | F_peak (N) | energy error");
    for m in args[2].split(',') {
        let (kind, level) = m
            .split_once(':')
            .ok_or(format!("{m:?} is not KIND:LEVEL"))?;
        let level: u32 = level.parse().map_err(|_| format!("{m:?}: bad level"))?;
        let mesh: SectionMesh = match kind {
            "band" => banded_mesh(case.diameter, edge, level, 4, 1.0),
            "plain" => family_mesh(case.diameter, a, level as i32),
            k => match k.strip_prefix("band").map(str::parse::<usize>) {
                Some(Ok(split)) => banded_mesh(case.diameter, edge, level, split, 1.0),
                _ => return Err(format!("{m:?}: KIND is band, bandSPLIT or plain")),
            },
        }
        .map_err(|e| e.to_string())?;
        for &b in &budgets {
            let mut h = HeadOn::new(mesh.clone(), case.material, v / 2.0, Target::MirrorBall);
            h.plane_contact = case.plane;
            h.mass_scaling = b;
            let r = h.run().map_err(|e| e.to_string())?;
            println!(
                "{m} | {b:.0e} | {} | {} | {:.3e} | {:.2} | {:.6} | {:.6e} | {:.6e} | {:.5e} | {:.1e}",
                r.elements,
                r.steps,
                r.dt,
                r.wall_time_s,
                r.e,
                r.delta_max,
                r.contact_duration,
                r.peak_force,
                r.energy_error
            );
        }
    }
    Ok(())
}
