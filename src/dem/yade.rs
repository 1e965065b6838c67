//! Yade scripts (Python, run by `yade -n -x yade.py VR`; Debian's 2023.02a).
//!
//! Both laws used clip the normal force at 0 (no attraction): a damped law maps only with
//! `tension = 0`; with `tension = 1` the writer refuses.
//!
//! - `hertz`, `hertz-damped` → `FrictMat` + `Ip2_FrictMat_FrictMat_MindlinPhys` +
//!   `Law2_ScGeom_MindlinPhys_Mindlin`: E* = E/(2(1 − ν²)) for equal balls, k_n,tangent =
//!   2E*√(R*δ), damping c_n = 2β_n √(m* k_n,tangent) with β_n given directly (`betan`; `en`
//!   would go through Thornton's fit instead): β_n = √(5/6)|β| reproduces the Tsuji form
//!   γ_n = 2√(5/6)|β|√(2E*√(R*δ) m*) exactly.
//! - `linear-dashpot` → `ViscElMat(kn, cn, ks, cs)` + `Ip2_ViscElMat_ViscElMat_ViscElPhys` +
//!   `Law2_ScGeom_ViscElPhys_Basic`: Yade puts the two materials' springs and dashpots in
//!   series, so each ball gets kn = 2k and cn = 2c.
//! - Other laws: none of Yade's laws (one-line error).

use super::liggghts::deck_modulus;
use super::scene::DeckScene;
use super::{cannot, damping_ratio, Code};
use crate::analytic::laws::Params;
use crate::error::Result;

/// The Yade script of `law` with `params`, or the one-line refusal.
pub fn deck(law: &str, params: &Params, s: &DeckScene) -> Result<String> {
    let clipped = |p: &Params| -> Result<()> {
        if p.tension() {
            Err(cannot(
                Code::Yade,
                law,
                "tension = 0: Yade's Hertz-Mindlin and ViscEl laws clip the normal force at 0 \
                 (export the law with --param tension=0)",
            ))
        } else {
            Ok(())
        }
    };
    let nu = s.poisson;
    let (material, physics, note) = match law {
        "hertz" | "hertz-damped" => {
            let e_deck = deck_modulus(params, s);
            let betan = if law == "hertz" {
                0.0
            } else {
                clipped(params)?;
                (5.0f64 / 6.0).sqrt() * damping_ratio(params.get("e"))
            };
            (
                format!(
                    "FrictMat(young={:.15e}, poisson={nu:.15e}, density={:.15e}, frictionAngle=math.atan({:.15e}))",
                    2.0 * (1.0 - nu * nu) * e_deck,
                    s.density,
                    s.mu
                ),
                format!(
                    "[Ip2_FrictMat_FrictMat_MindlinPhys(betan={betan:.15e})], [Law2_ScGeom_MindlinPhys_Mindlin()]"
                ),
                format!(
                    "Maps exactly: E* = E_star sqrt(R_star/R*) = {e_deck:.9e} Pa (young = 2(1 - nu^2) E*); betan = sqrt(5/6)|beta|\n\
                     # = {betan:.12e} makes Yade's 2 betan sqrt(m* 2 E* sqrt(R* delta)) the law's Tsuji damping; the force is\n\
                     # clipped at 0 as with tension = 0."
                ),
            )
        }
        "linear-dashpot" => {
            clipped(params)?;
            let k = params.get("k");
            let c = 2.0 * damping_ratio(params.get("e")) * (k * s.mass()).sqrt();
            (
                format!(
                    "ViscElMat(kn={:.15e}, cn={:.15e}, ks=0.0, cs=0.0, density={:.15e}, frictionAngle=math.atan({:.15e}))",
                    2.0 * k,
                    2.0 * c,
                    s.density,
                    s.mu
                ),
                "[Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]".to_string(),
                format!(
                    "Maps exactly: contact k = {k:.9e} N/m and c = {c:.9e} N s/m; Yade puts the balls' springs and dashpots\n\
                     # in series, so each ball has kn = 2k, cn = 2c; the force is clipped at 0 as with tension = 0."
                ),
            )
        }
        _ => {
            return Err(cannot(
                Code::Yade,
                law,
                "a law Yade's Hertz-Mindlin or ViscEl laws express: hertz, hertz-damped, linear-dashpot \
                 (with tension = 0)",
            ))
        }
    };
    let run = "yade -n -x yade.py VR";
    let mut out = s.header("#", "Yade 2023.02a", run, params);
    out += &format!("# {note}\n");
    out += &format!(
        "import math, sys\n\
         vr = float(sys.argv[1]) if len(sys.argv) > 1 else {v:.12e}\n\
         R = {h:.15e}\n\
         mat = O.materials.append({material})\n\
         O.bodies.append([sphere((-R, 0, 0), R, material=mat), sphere((R, 0, 0), R, material=mat)])\n\
         O.bodies[0].state.vel = Vector3(vr / 2, 0, 0)\n\
         O.bodies[1].state.vel = Vector3(-vr / 2, 0, 0)\n\
         O.engines = [\n\
         \x20   ForceResetter(),\n\
         \x20   InsertionSortCollider([Bo1_Sphere_Aabb()]),\n\
         \x20   InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], {physics}),\n\
         \x20   NewtonIntegrator(damping=0.0, gravity=(0, 0, 0)),\n\
         ]\n\
         O.dt = {dt:.15e}\n\
         # The force of a step acts on the positions at its start: write both at that time.\n\
         with open('trace.txt', 'w') as f:\n\
         \x20   for i in range({n}):\n\
         \x20       t = O.time\n\
         \x20       x1, x2 = O.bodies[0].state.pos[0], O.bodies[1].state.pos[0]\n\
         \x20       O.step()\n\
         \x20       f.write('%.17g %.17g %.17g %.17g %.17g %.17g\\n' % (t, x1, x2, O.bodies[0].state.vel[0],\n\
         \x20               O.bodies[1].state.vel[0], O.forces.f(0)[0]))\n",
        v = s.speed,
        h = s.diameter / 2.0,
        dt = s.timestep,
        n = s.steps
    );
    Ok(out)
}
