//! Where the impact energy of the default scene (two D = 20 mm copper-fe balls, ±1 m/s; one
//! ball section against the symmetry plane) goes on a meridian mesh, and which surface rings
//! the plane reached: the table of verification/contact-penalty.md ("Why the section's e scatters").
//!
//! Per mesh, after separation and over the initial kinetic energy KE₀: the rebound (the
//! rigid-body kinetic energy, e²), the vibration kinetic energy (kinetic minus rigid-body),
//! the elastic strain energy left (residual stresses and vibration), the plastic work and
//! the hourglass energy; then the outermost surface ring that reached the plane (its radius
//! at rest and its arrival time after first touch) and the radius of the next ring.
//!
//! `cargo run --release --example section_energy -- MESH [MESH ...]` with MESH one of
//! `ball:SIZE:POLE` (`mesh::section::ball`, lengths in m) or `ladder:LEVEL[:A]`
//! (`mesh::section::ladder_ball` sized from the contact radius A in µm, by default Hertz's
//! at 2 m/s: 470.4 µm); a suffix `:b-bar` picks the B-bar quads, `:single` single-rate
//! integration, `:band=SPLIT/INNER/OUTER` (ladder only) splits the layers whose surface rings
//! lie between the rest radii INNER and OUTER (µm) into SPLIT shells each
//! (`mesh::section::ladder_ball_banded`), `:move=FROM/TO` moves the surface ring nearest the rest radius FROM (µm)
//! along the surface to the radius TO (µm). `SECTION_RINGS=1` also prints every ring
//! arrival, `SECTION_PULSE=FILE` writes the force pulse (t in s, F in N) of the last mesh as
//! CSV, `SECTION_CONTACT=segment` integrates the plane's penalty pressure over each segment
//! (`fe::contact::section::plane_segment`) instead of lumping it at the nodes.

use twoball::fe::elements::ring::QuadFormulation;
use twoball::fe::section::solver::SectionSolver;
use twoball::fe::subcycle::Integration;
use twoball::material::Material;
use twoball::mesh::section::{
    ball, ladder_ball, ladder_ball_banded, EdgeBand, SectionMesh, SectionSpec,
};
use twoball::study::run::section_impact::{HeadOn, PlaneContact, Target};

const D: f64 = 0.02;

/// Hertz's contact radius (m) of two copper-fe balls of diameter D at relative speed `v`
/// (m/s).
fn contact_radius(v: f64) -> Result<f64, String> {
    let m = Material::preset("copper-fe").map_err(|e| e.to_string())?;
    let e_star = m.youngs / (2.0 * (1.0 - m.nu * m.nu));
    let r_star = D / 4.0;
    let m_star = m.rho * std::f64::consts::PI * D.powi(3) / 12.0;
    let delta = (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4);
    Ok((r_star * delta).sqrt())
}

/// The mesh, formulation and integration of one argument.
fn parse(arg: &str) -> Result<(SectionMesh, QuadFormulation, Integration), String> {
    let parts: Vec<&str> = arg.split(':').collect();
    let num = |i: usize| -> Result<f64, String> {
        parts
            .get(i)
            .and_then(|s| s.parse::<f64>().ok())
            .filter(|v| v.is_finite() && *v > 0.0)
            .ok_or_else(|| format!("{arg:?}: field {i} is not a positive number"))
    };
    let (mesh, rest) = match parts.first().copied() {
        Some("ball") => {
            let spec = SectionSpec {
                diameter: D,
                size: num(1)?,
                pole_size: Some(num(2)?),
            };
            (ball(&spec).map_err(|e| e.to_string())?, &parts[3..])
        }
        Some("ladder") => {
            let level = parts
                .get(1)
                .and_then(|s| s.parse::<u32>().ok())
                .ok_or_else(|| format!("{arg:?}: field 1 is not a level"))?;
            let (a, rest) = match parts.get(2).and_then(|s| s.parse::<f64>().ok()) {
                Some(um) => (um * 1e-6, &parts[3..]),
                None => (contact_radius(2.0)?, &parts[2..]),
            };
            let mesh = match rest.iter().find_map(|o| o.strip_prefix("band=")) {
                Some(b) => {
                    let band = parse_band(b)
                        .ok_or_else(|| format!("{arg:?}: {b:?} is not SPLIT/INNER/OUTER"))?;
                    ladder_ball_banded(D, a, level, &band)
                }
                None => ladder_ball(D, a, level),
            };
            (mesh.map_err(|e| e.to_string())?, rest)
        }
        _ => return Err(format!("{arg:?}: not ball:SIZE:POLE or ladder:LEVEL[:A]")),
    };
    let mut mesh = mesh;
    let mut form = QuadFormulation::default();
    let mut integ = Integration::subcycled();
    for r in rest {
        match *r {
            "b-bar" => form = QuadFormulation::SelectiveReduced,
            "single" => integ = Integration::SingleRate,
            o if o.starts_with("band=") => {}
            o if o.starts_with("move=") => move_ring(&mut mesh, &o[5..])
                .ok_or_else(|| format!("{arg:?}: {o:?} is not move=FROM/TO (µm)"))?,
            o => return Err(format!("{arg:?}: unknown option {o:?}")),
        }
    }
    Ok((mesh, form, integ))
}

/// The edge band "SPLIT/INNER/OUTER[/DEPTH]" (radii in µm; DEPTH the share of the rays from
/// the surface, 1 by default).
fn parse_band(spec: &str) -> Option<EdgeBand> {
    let mut it = spec.split('/');
    let split = it.next()?.parse().ok()?;
    let inner = it.next()?.parse::<f64>().ok()? * 1e-6;
    let outer = it.next()?.parse::<f64>().ok()? * 1e-6;
    let depth = match it.next() {
        Some(d) => d.parse().ok()?,
        None => 1.0,
    };
    Some(EdgeBand {
        inner,
        outer,
        split,
        depth,
    })
}

/// Moves the surface ring nearest the rest radius FROM (µm) along the surface to the radius
/// TO (µm), `spec` = "FROM/TO": the same mesh with one ring elsewhere.
fn move_ring(mesh: &mut SectionMesh, spec: &str) -> Option<()> {
    let (from, to) = spec.split_once('/')?;
    let (from, to) = (
        from.parse::<f64>().ok()? * 1e-6,
        to.parse::<f64>().ok()? * 1e-6,
    );
    let radius = D / 2.0;
    let i = (0..mesh.nodes.len())
        .filter(|&i| {
            let p = mesh.nodes[i];
            (p[0].hypot(p[1]) - radius).abs() < 1e-9 * radius && p[1] > 0.0
        })
        .min_by(|&a, &b| {
            let d = |i: usize| (mesh.nodes[i][0] - from).abs();
            d(a).total_cmp(&d(b))
        })?;
    (to > 0.0 && to < radius).then_some(())?;
    mesh.nodes[i] = [to, (radius * radius - to * to).sqrt()];
    Some(())
}

/// Energies (J) of the ball at the end: kinetic, rigid-body kinetic, elastic strain,
/// plastic, hourglass.
fn split(s: &SectionSolver) -> [f64; 5] {
    let n = s.masses().len();
    let (p, m) = s.axial_momentum(0..n);
    let en = s.energy();
    [
        en.solid.kinetic,
        0.5 * p * p / m,
        en.solid.internal - en.solid.plastic,
        en.solid.plastic,
        en.solid.hourglass,
    ]
}

/// The surface ring at rest radius just beyond `r` (m) of the mesh at rest `x0`.
fn next_ring(x0: &[[f64; 2]], r: f64) -> f64 {
    let radius = D / 2.0;
    x0.iter()
        .filter(|p| (p[0].hypot(p[1]) - radius).abs() < 1e-9 * radius && p[1] > 0.0)
        .map(|p| p[0])
        .filter(|&q| q > r * (1.0 + 1e-9))
        .fold(f64::INFINITY, f64::min)
}

fn run(arg: &str) -> Result<String, String> {
    let (mesh, form, integ) = parse(arg)?;
    let material = Material::preset("copper-fe").map_err(|e| e.to_string())?;
    let mut h = HeadOn::new(mesh, material, 1.0, Target::MirrorBall);
    h.formulation = form;
    h.integration = integ;
    match std::env::var("SECTION_CONTACT").as_deref() {
        Ok("segment") => h.plane_contact = PlaneContact::Segment,
        Ok("kinematic") => h.plane_contact = PlaneContact::Kinematic,
        Ok("nodal") => h.plane_contact = PlaneContact::Nodal,
        _ => {}
    }
    let plane = D / 2.0;
    let mut end = [0.0; 5];
    // Arrivals of ever farther rings at the plane: (time after first touch s, radius at rest m).
    let mut arrivals: Vec<(f64, f64)> = vec![(0.0, 0.0)];
    let mut next = f64::INFINITY;
    let r = h
        .run_observed(&mut |s, last| {
            let x0 = s.initial_positions();
            for (i, p) in s.positions().iter().enumerate() {
                let outer = arrivals.last().map_or(0.0, |a| a.1);
                if p[1] >= plane && x0[i][0] > outer {
                    arrivals.push((s.time(), x0[i][0]));
                }
            }
            if last {
                end = split(s);
                next = next_ring(x0, arrivals.last().map_or(0.0, |a| a.1));
            }
            Ok(())
        })
        .map_err(|e| e.to_string())?;
    if std::env::var("SECTION_RINGS").is_ok() {
        let list: Vec<String> = arrivals[1..]
            .iter()
            .map(|(t, r)| format!("{:.1}us:{:.0}um", t * 1e6, r * 1e6))
            .collect();
        println!(
            "{arg}: ring arrivals (time:radius at rest): {}",
            list.join(" ")
        );
    }
    if let Ok(path) = std::env::var("SECTION_PULSE") {
        let mut csv = String::from("t_s,force_N\n");
        for (t, f) in &r.pulse {
            csv += &format!("{t:.6e},{f:.6e}\n");
        }
        std::fs::write(&path, csv).map_err(|e| format!("{path}: {e}"))?;
    }
    let ke0 = r.initial_kinetic / 2.0;
    let [ke, rigid, strain, plastic, hourglass] = end.map(|x| x / ke0);
    let (t_last, r_last) = arrivals.last().copied().unwrap_or_default();
    Ok(format!(
        "{arg}: {} quads, e {:.5}, delta_max {:.3} um, t_c {:.3} us | over KE0: rebound {:.5}, \
         vibration kinetic {:.5}, strain {:.5}, plastic {:.5}, hourglass {:.5}, sum {:.5} | \
         last ring {:.1} um at {:.1} us, next {:.1} um | energy error {:.1e}, wall {:.1} s, {} steps of {:.2e} s, {} quad updates",
        r.elements,
        r.e,
        r.delta_max * 1e6,
        r.contact_duration * 1e6,
        rigid,
        ke - rigid,
        strain,
        plastic,
        hourglass,
        ke + strain + plastic + hourglass,
        r_last * 1e6,
        t_last * 1e6,
        next * 1e6,
        r.energy_error,
        r.wall_time_s,
        r.steps,
        r.dt,
        r.element_updates
    ))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.is_empty() {
        eprintln!("usage: section_energy ball:SIZE:POLE|ladder:LEVEL[:A][:b-bar][:single][:band=SPLIT/INNER/OUTER][:move=FROM/TO] ...");
        std::process::exit(2);
    }
    for a in &args {
        match run(a) {
            Ok(line) => println!("{line}"),
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(2);
            }
        }
    }
}
