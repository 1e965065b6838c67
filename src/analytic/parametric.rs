//! The paper's parametric studies (Figures 11–14): the energy dissipation factor against
//! density, dynamic friction coefficient, elastic modulus (per modulus ratio) and yield strength
//! (per yield ratio); `study::report::figures` writes them as CSV and SVG.
//!
//! Base case (docs/design.md, section 2): two Table 1 copper balls, D = 20 mm, left ball
//! v_n1 = +1 m/s, right ball v_n2 = −1 m/s (the FE study's set-up), no tangential speed unless
//! the figure varies it; η is eq. 43 (equal to eq. 33 when there is no tangential speed).

use super::body::Body;
use super::collision::collide_with_mu;
use crate::error::{Error, Result};
use crate::material::Material;

/// One figure: an x grid and a family of η curves on it.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// File stem, e.g. `fig11_density`.
    pub name: &'static str,
    /// Plot title.
    pub title: &'static str,
    /// x-axis label with unit, for the plot.
    pub x_label: &'static str,
    /// x column header with unit, for the CSV.
    pub x_column: &'static str,
    /// Multiplier from SI x values to plotted/CSV units (e.g. 1e-9 for GPa).
    pub x_scale: f64,
    /// x values, SI.
    pub x: Vec<f64>,
    /// (legend / CSV column suffix, η values) per curve.
    pub curves: Vec<(String, Vec<f64>)>,
}

/// Diameter of both balls in the base case, m.
pub const BASE_DIAMETER: f64 = 0.02;
/// Normal speeds of the base case, m/s (left ball, right ball).
pub const BASE_SPEEDS: (f64, f64) = (1.0, -1.0);

fn base_material() -> Result<Material> {
    Material::preset("copper")
}

/// η (eq. 43) of two balls with the base diameter.
fn eta(m1: &Material, m2: &Material, v1: [f64; 2], v2: [f64; 2], mu: f64) -> Result<f64> {
    let b1 = Body::ball(*m1, BASE_DIAMETER, "ball1")?;
    let b2 = Body::ball(*m2, BASE_DIAMETER, "ball2")?;
    Ok(collide_with_mu(&b1, &b2, v1, v2, mu)?.eta_friction)
}

/// `n` evenly spaced values from a to b inclusive.
fn grid(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}

/// The figure `axis` (its names, SI-to-plot factor and x grid; no curves yet) with one curve
/// per parameter of `family`: its legend `label(p)` and η at each x from `eta_at(p, x)`.
fn family<P: Copy>(
    axis: Figure,
    family: &[P],
    label: impl Fn(P) -> String,
    eta_at: impl Fn(P, f64) -> Result<f64>,
) -> Result<Figure> {
    let curves = family
        .iter()
        .map(|&p| {
            let ys = axis
                .x
                .iter()
                .map(|&x| eta_at(p, x))
                .collect::<Result<_>>()?;
            Ok((label(p), ys))
        })
        .collect::<Result<_>>()?;
    Ok(Figure { curves, ..axis })
}

/// η of a head-on base-case impact between balls 1 and 2 of `base` changed by `m1` and `m2`.
fn eta_of_pair(
    base: &Material,
    m1: impl FnOnce(&mut Material),
    m2: impl FnOnce(&mut Material),
) -> Result<f64> {
    let (mut a, mut b) = (*base, *base);
    m1(&mut a);
    m2(&mut b);
    let (a, b) = (
        a.validated("ball1.material")?,
        b.validated("ball2.material")?,
    );
    eta(&a, &b, [BASE_SPEEDS.0, 0.0], [BASE_SPEEDS.1, 0.0], base.mu)
}

/// Figure 11: η against density 4000–12000 kg/m³ (both balls), left-ball speed 1.0 and
/// 0.1 m/s, right ball −1 m/s.
pub fn figure11() -> Result<Figure> {
    let base = base_material()?;
    let axis = Figure {
        name: "fig11_density",
        title: "Fig. 11: energy dissipation factor vs density",
        x_label: "density of the balls (kg/m^3)",
        x_column: "density_kg_per_m3",
        x_scale: 1.0,
        x: grid(4000.0, 12000.0, 41),
        curves: Vec::new(),
    };
    let label = |v: f64| format!("left ball {v:.1} m/s");
    family(axis, &[1.0, 0.1], label, |v, rho| {
        let m = Material { rho, ..base }.validated("material")?;
        eta(&m, &m, [v, 0.0], [BASE_SPEEDS.1, 0.0], m.mu)
    })
}

/// Figure 12: η against the dynamic friction coefficient 0.1–0.6, left-ball tangential speed
/// 0.2, 0.6 and 1.0 m/s (right ball none).
pub fn figure12() -> Result<Figure> {
    let base = base_material()?;
    let axis = Figure {
        name: "fig12_friction",
        title: "Fig. 12: energy dissipation factor vs friction coefficient",
        x_label: "dynamic friction coefficient (-)",
        x_column: "mu",
        x_scale: 1.0,
        x: grid(0.1, 0.6, 26),
        curves: Vec::new(),
    };
    let label = |vt: f64| format!("left tangential {vt:.1} m/s");
    family(axis, &[0.2, 0.6, 1.0], label, |vt, mu| {
        eta(&base, &base, [BASE_SPEEDS.0, vt], [BASE_SPEEDS.1, 0.0], mu)
    })
}

/// Figure 13: η against the left ball's modulus E₁ = 100–400 GPa for modulus ratios
/// E₂/E₁ = 100, 10, 2, 1, 0.5, 0.1.
pub fn figure13() -> Result<Figure> {
    let base = base_material()?;
    let axis = Figure {
        name: "fig13_modulus",
        title: "Fig. 13: energy dissipation factor vs elastic modulus",
        x_label: "elastic modulus E1 (GPa)",
        x_column: "E1_GPa",
        x_scale: 1e-9,
        x: grid(100e9, 400e9, 31),
        curves: Vec::new(),
    };
    let ratios = [100.0, 10.0, 2.0, 1.0, 0.5, 0.1];
    family(
        axis,
        &ratios,
        |r| format!("modulus ratio {r}"),
        |r, e1| eta_of_pair(&base, |m| m.youngs = e1, |m| m.youngs = r * e1),
    )
}

/// Figure 14: η against the left ball's yield strength σ_s1 = 10–450 MPa for yield ratios
/// σ_s2/σ_s1 = 0.1, 0.5, 1, 2, 10, 100 (σ_s = 0 has no elastic phase; the grid starts at 10).
pub fn figure14() -> Result<Figure> {
    let base = base_material()?;
    let axis = Figure {
        name: "fig14_yield",
        title: "Fig. 14: energy dissipation factor vs yield strength",
        x_label: "yield strength sigma_s1 (MPa)",
        x_column: "yield1_MPa",
        x_scale: 1e-6,
        x: grid(10e6, 450e6, 45),
        curves: Vec::new(),
    };
    let ratios = [0.1, 0.5, 1.0, 2.0, 10.0, 100.0];
    family(
        axis,
        &ratios,
        |r| format!("yield ratio {r}"),
        |r, s1| {
            eta_of_pair(
                &base,
                |m| m.yield_strength = s1,
                |m| m.yield_strength = r * s1,
            )
        },
    )
}

/// All four figures.
pub fn all_figures() -> Result<Vec<Figure>> {
    Ok(vec![figure11()?, figure12()?, figure13()?, figure14()?])
}

impl Figure {
    /// Fails if any value is not finite (nothing non-finite is ever written).
    pub fn check_finite(&self) -> Result<()> {
        for (label, ys) in &self.curves {
            if let Some((i, y)) = ys.iter().enumerate().find(|(_, y)| !y.is_finite()) {
                return Err(Error::Numerical(format!(
                    "{}: eta = {y} at x = {} on curve '{label}'",
                    self.name, self.x[i]
                )));
            }
        }
        Ok(())
    }
}
