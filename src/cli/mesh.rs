//! `twoball mesh ball|check|gmsh`: generate ball meshes, summarise mesh files, run gmsh.

use crate::error::{Error, Result};
use crate::mesh::ball::{ball, BallSpec, Cut};
use crate::mesh::quality::{summary, MeshSummary};
use crate::mesh::{gmsh, msh, vtu, Mesh};
use clap::{Args, Subcommand};
use std::path::{Path, PathBuf};

/// Arguments of `twoball mesh`.
#[derive(Debug, Args)]
pub struct MeshArgs {
    #[command(subcommand)]
    what: MeshCommand,
}

#[derive(Debug, Subcommand)]
enum MeshCommand {
    /// Built-in all-hex ball mesh, graded toward the contact pole (+R, 0, 0).
    Ball(BallArgs),
    /// Print the size and quality summary of a mesh file (.msh 4.1 or 2.2, ASCII or binary).
    Check(CheckArgs),
    /// Mesh a parametric .geo script with the gmsh program, then read and check the result.
    Gmsh(GmshArgs),
}

#[derive(Debug, Args)]
struct BallArgs {
    /// Ball diameter, m.
    #[arg(long)]
    diameter: f64,
    /// Far-field element size, m (element edges stay below about 0.6 x size).
    #[arg(long)]
    size: f64,
    /// Element size at the contact pole, m (default: no pole refinement; one above about
    /// size/4.7 gets about size/4.7, the coarsest pole refinement the mesher builds).
    #[arg(long)]
    pole_size: Option<f64>,
    /// full, half (z >= 0) or quarter (y >= 0, z >= 0).
    #[arg(long, default_value = "full")]
    cut: String,
    /// Output file: .msh (gmsh 4.1 ASCII) or .vtu (ParaView; compressed binary).
    #[arg(short, long)]
    output: PathBuf,
    /// Write a .vtu as ASCII text instead of compressed binary.
    #[arg(long)]
    ascii: bool,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Args)]
struct CheckArgs {
    /// Mesh file (.msh).
    file: PathBuf,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Args)]
struct GmshArgs {
    /// The .geo script, e.g. meshes/ball.geo.
    geo: PathBuf,
    /// Script parameter NAME=VALUE (passed as gmsh -setnumber NAME VALUE); repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Output .msh file.
    #[arg(short, long)]
    output: PathBuf,
    /// The gmsh program.
    #[arg(long, default_value = "gmsh")]
    gmsh: PathBuf,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

/// Runs `twoball mesh ...`.
pub fn run(a: MeshArgs) -> Result<()> {
    match a.what {
        MeshCommand::Ball(b) => run_ball(b),
        MeshCommand::Check(c) => run_check(c),
        MeshCommand::Gmsh(g) => run_gmsh(g),
    }
}

fn run_ball(b: BallArgs) -> Result<()> {
    let cut: Cut = b.cut.parse()?;
    let format = output_format(&b.output)?;
    let mesh = ball(&BallSpec {
        diameter: b.diameter,
        size: b.size,
        pole_size: b.pole_size,
        cut,
    })
    .map_err(|e| e.map_field(|f| format!("--{}", f.replace('_', "-"))))?;
    match format {
        Format::Msh => msh::write(&b.output, &mesh)?,
        Format::Vtu => {
            let format = if b.ascii {
                vtu::VtuFormat::Ascii
            } else {
                vtu::VtuFormat::Binary
            };
            vtu::write_with(&b.output, &mesh, &[], &[], None, format)?
        }
    }
    report(&mesh, &b.output, b.json)
}

fn run_check(c: CheckArgs) -> Result<()> {
    if c.file.extension().is_some_and(|e| e == "vtu") {
        return Err(Error::invalid(
            "file",
            c.file.display(),
            "a gmsh .msh file (4.1 or 2.2); .vtu is an output format only",
        ));
    }
    let loaded = msh::read(&c.file)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    report(&loaded.mesh, &c.file, c.json)
}

/// Parses the `--set` pairs and runs gmsh (`mesh::gmsh`), then prints the summary.
fn run_gmsh(g: GmshArgs) -> Result<()> {
    if output_format(&g.output)? != Format::Msh {
        return Err(Error::invalid("output", g.output.display(), "a .msh file"));
    }
    let sets = g
        .set
        .iter()
        .map(|s| parse_set(s))
        .collect::<Result<Vec<_>>>()?;
    let loaded = gmsh::run(&g.gmsh, &g.geo, &sets, &g.output)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    report(&loaded.mesh, &g.output, g.json)
}

/// One `--set NAME=VALUE` of `mesh gmsh`: a plain name and a finite number.
fn parse_set(s: &str) -> Result<(String, f64)> {
    let (name, value) = s
        .split_once('=')
        .ok_or_else(|| Error::invalid("--set", s, "NAME=VALUE"))?;
    let ok_name = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    let v: f64 = value
        .trim()
        .parse()
        .map_err(|_| Error::invalid("--set", s, "NAME=number"))?;
    if !ok_name || !v.is_finite() {
        return Err(Error::invalid(
            "--set",
            s,
            "NAME=VALUE with a plain name and a finite number",
        ));
    }
    Ok((name.to_string(), v))
}

#[derive(Debug, PartialEq)]
enum Format {
    Msh,
    Vtu,
}

fn output_format(p: &Path) -> Result<Format> {
    match p.extension().and_then(|e| e.to_str()) {
        Some("msh") => Ok(Format::Msh),
        Some("vtu") => Ok(Format::Vtu),
        _ => Err(Error::invalid(
            "output",
            p.display(),
            "a file name ending in .msh or .vtu",
        )),
    }
}

fn report(mesh: &Mesh, file: &Path, json: bool) -> Result<()> {
    use std::io::Write;
    let s = summary(mesh);
    let text = if json {
        serde_json::to_string_pretty(&s)
            .map_err(|e| Error::Numerical(format!("summary is not representable as JSON: {e}")))?
    } else {
        summary_text(&s, file)
    };
    // A closed pipe (e.g. `| head`) is not an error worth a panic.
    let _ = writeln!(std::io::stdout().lock(), "{text}");
    Ok(())
}

fn summary_text(s: &MeshSummary, file: &Path) -> String {
    format!(
        "{}\n  nodes                 {}\n  elements              {} hexahedra, {} boundary quads\n  \
         volume                {:.6e} m^3\n  \
         edge length           {:.4e} .. {:.4e} m (shortest at {:.4e}, {:.4e}, {:.4e})\n  \
         scaled Jacobian       min {:.4}, mean {:.4}\n  max aspect ratio      {:.3}",
        file.display(),
        s.nodes,
        s.elements,
        s.boundary_faces,
        s.volume,
        s.min_edge,
        s.max_edge,
        s.min_edge_at[0],
        s.min_edge_at[1],
        s.min_edge_at[2],
        s.min_scaled_jacobian,
        s.mean_scaled_jacobian,
        s.max_aspect_ratio
    )
}
