//! The collision every deck runs: two equal balls touching at t = 0, moving towards each
//! other along x at ±v_r/2, no gravity, no tangential motion; the time step and run length
//! sized from the law's own contact time over the deck's speed range.

use crate::analytic::law_fit::predict;
use crate::analytic::laws::{ContactPair, NormalSpec, Params};
use crate::analytic::Body;
use crate::error::{Error, Result};
use crate::material::Material;

/// Steps per contact at the fastest speed of the range (velocity Verlet: e, δ_max and t_c
/// within about 1e-5 of the exact ones).
pub const STEPS_PER_CONTACT: f64 = 4000.0;

/// The two-ball scene of a deck and the law's figures it is sized from.
#[derive(Debug, Clone)]
pub struct DeckScene {
    /// Law name (as `twoball laws` lists it).
    pub law: String,
    /// Ball diameter D, m.
    pub diameter: f64,
    /// Ball density ρ, kg/m³.
    pub density: f64,
    /// Poisson's ratio ν of the balls.
    pub poisson: f64,
    /// Friction coefficient μ of the pair (no tangential motion: it never acts).
    pub mu: f64,
    /// The pair's E*, R*, m* (Pa, m, kg): the balls', not a fitted modulus.
    pub pair: ContactPair,
    /// Reference relative approach speed v_r, m/s (the deck's default).
    pub speed: f64,
    /// Speeds the time step and run length are sized for, m/s (lowest, highest).
    pub range: (f64, f64),
    /// Time step, s.
    pub timestep: f64,
    /// Number of steps (1.5 contact times at the lowest speed).
    pub steps: u64,
    /// Where the parameters came from (one line, e.g. the fit's data file).
    pub origin: String,
}

impl DeckScene {
    /// The scene of two balls of `material` and `diameter` (m) under law `spec` with
    /// `params`, reference speed `speed` within `range` (m/s, lowest ≤ speed ≤ highest).
    ///
    /// Errors: a non-positive or non-finite diameter or speed, a speed outside the range, or
    /// a law that does not make an impact at the range's ends.
    pub fn new(
        spec: &NormalSpec,
        params: &Params,
        material: &Material,
        diameter: f64,
        speed: f64,
        range: (f64, f64),
        origin: &str,
    ) -> Result<DeckScene> {
        if !(diameter.is_finite() && diameter > 0.0) {
            return Err(Error::invalid("--diameter", diameter, "> 0 m, finite"));
        }
        if !(range.0.is_finite() && range.1.is_finite() && range.0 > 0.0 && range.1 >= range.0) {
            return Err(Error::invalid(
                "--vmin",
                range.0,
                format!("> 0 m/s and <= --vmax = {}", range.1),
            ));
        }
        if !(speed >= range.0 && speed <= range.1) {
            return Err(Error::invalid(
                "--speed",
                speed,
                format!("within [{}, {}] m/s", range.0, range.1),
            ));
        }
        let b = Body::ball(*material, diameter, "ball")?;
        let pair = ContactPair::between(&b, &b, material.mu);
        let (_, _, t_hi) = predict(spec, &pair, params, &b, &b, range.1)?;
        let (_, _, t_lo) = predict(spec, &pair, params, &b, &b, range.0)?;
        let timestep = t_hi.min(t_lo) / STEPS_PER_CONTACT;
        let steps = (1.5 * t_hi.max(t_lo) / timestep).ceil() as u64;
        Ok(DeckScene {
            law: spec.name.to_string(),
            diameter,
            density: material.rho,
            poisson: material.nu,
            mu: material.mu,
            pair,
            speed,
            range,
            timestep,
            steps,
            origin: origin.to_string(),
        })
    }

    /// The head of a LAMMPS-family input (LAMMPS, LIGGGHTS) before its pair style: the
    /// reference speed as the variable `vr` (m/s), SI units, atoms of `atom_style`, the
    /// `communication` lines (each ending in a newline), a box reaching one diameter (m)
    /// beyond the balls on every side and the neighbour list with a skin of D/10 (m).
    pub fn box_and_neighbours(&self, atom_style: &str, communication: &str) -> String {
        format!(
            "variable vr index {v:.12e}\n\
             units si\n\
             atom_style {atom_style}\n\
             atom_modify map array\n\
             boundary f f f\n\
             newton off\n\
             {communication}\
             region box block -{b:e} {b:e} -{b:e} {b:e} -{b:e} {b:e} units box\n\
             create_box 1 box\n\
             neighbor {skin:e} bin\n\
             neigh_modify delay 0\n",
            v = self.speed,
            b = 2.0 * self.diameter,
            skin = self.diameter / 10.0,
        )
    }

    /// The tail of a LAMMPS-family input (LAMMPS, LIGGGHTS) after its pair style: the step,
    /// the two balls touching at the origin with relative speed `${vr}` (m/s), the trace
    /// `t x1 x2 v1 v2 f1` (SI) written to `trace.txt` every step, and the run.
    pub fn two_atoms_and_trace(&self) -> String {
        format!(
            "timestep {dt:.12e}\n\
         create_atoms 1 single -{h:.12e} 0 0 units box\n\
         create_atoms 1 single {h:.12e} 0 0 units box\n\
         set atom 1 diameter {d:.12e} density {rho:.12e} vx $(v_vr/2)\n\
         set atom 2 diameter {d:.12e} density {rho:.12e} vx $(-v_vr/2)\n\
         fix integr all nve/sphere\n\
         variable t equal step*dt\n\
         variable x1 equal x[1]\n\
         variable x2 equal x[2]\n\
         variable v1 equal vx[1]\n\
         variable v2 equal vx[2]\n\
         variable f1 equal fx[1]\n\
         fix trace all print 1 \"${{t}} ${{x1}} ${{x2}} ${{v1}} ${{v2}} ${{f1}}\" file trace.txt screen no\n\
         thermo 1000\n\
         run {n}\n",
            dt = self.timestep,
            h = self.diameter / 2.0,
            d = self.diameter,
            rho = self.density,
            n = self.steps
        )
    }

    /// Effective mass m* of the two balls, kg.
    pub fn mass(&self) -> f64 {
        self.pair.hertz.mass
    }

    /// Effective radius R* of the two balls, m.
    pub fn radius(&self) -> f64 {
        self.pair.hertz.radius
    }

    /// Header lines common to every deck (comment marker `c`): what runs, how, and the
    /// trace it writes. `run` is the command line with `VR` for the speed.
    pub fn header(&self, c: &str, code: &str, run: &str, params: &Params) -> String {
        let p: Vec<String> = params
            .iter()
            .map(|(k, v)| format!("{k} = {v:.9e}"))
            .collect();
        format!(
            "{c} twoball law '{law}' for {code}: a head-on collision of two equal balls, SI units.\n\
             {c} Parameters ({origin}): {p}.\n\
             {c} Balls: D = {d:.9e} m, rho = {rho:.9e} kg/m3, nu = {nu}; the pair's own E* = {es:.9e} Pa,\n\
             {c} R* = {rs:.9e} m, m* = {ms:.9e} kg (the law's parameters above are what the deck maps).\n\
             {c} Run, unedited: {run}   (VR: relative approach speed, m/s; default {v}).\n\
             {c} Time step {dt:.6e} s and {n} steps are sized for {lo} <= VR <= {hi} m/s.\n\
             {c} Writes trace.txt, one line per step: t [s], x1 [m], x2 [m], vx1 [m/s], vx2 [m/s], fx1 [N];\n\
             {c} e = (vx2 - vx1)/VR at the end, delta_max = max(D - (x2 - x1)), contact force = -fx1.\n",
            law = self.law,
            origin = self.origin,
            p = p.join(", "),
            d = self.diameter,
            rho = self.density,
            nu = self.poisson,
            es = self.pair.hertz.modulus,
            rs = self.radius(),
            ms = self.mass(),
            v = self.speed,
            dt = self.timestep,
            n = self.steps,
            lo = self.range.0,
            hi = self.range.1,
        )
    }
}
