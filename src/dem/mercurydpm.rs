//! MercuryDPM drivers (C++), written against MercuryDPM's published source and API
//! documentation and NOT compiled or run here (there is no Debian package): each file says
//! so in its first line. Species are the `…Species` classes a `speciesHandler` accepts
//! (`LinearViscoelasticSpecies`, `HertzianViscoelasticSpecies`,
//! `LinearPlasticViscoelasticSpecies`), not their `…NormalSpecies` force components.
//!
//! - `linear-dashpot` → `LinearViscoelasticSpecies` (setStiffness k, setDissipation c): the
//!   force may pull, so `tension = 1` only.
//! - `hertz`, `hertz-damped` → `HertzianViscoelasticSpecies`:
//!   `setEffectiveElasticModulusAndRestitutionCoefficient(E*, e)` sets the dissipation
//!   √5|β|, which with MercuryDPM's √(m* k_n) scaling is LIGGGHTS's Tsuji damping.
//! - `walton-braun` → `LinearPlasticViscoelasticSpecies` (Luding's model, whose unloading
//!   stiffness grows with the largest overlap like LIGGGHTS's `hooke/hysteresis`): the same
//!   one-speed mapping as the LIGGGHTS export.
//! - Other laws: one-line error.

use super::liggghts::deck_modulus;
use super::scene::DeckScene;
use super::{cannot, damping_ratio, Code};
use crate::analytic::laws::Params;
use crate::error::Result;

/// The MercuryDPM driver of `law` with `params`, or the one-line refusal.
pub fn driver(law: &str, params: &Params, s: &DeckScene) -> Result<String> {
    let (species, setters, note) = match law {
        "linear-dashpot" => {
            if params.get("tension") < 0.5 {
                return Err(cannot(
                    Code::MercuryDpm,
                    law,
                    "tension = 1: MercuryDPM's LinearViscoelastic force is never clipped",
                ));
            }
            let k = params.get("k");
            let c = 2.0 * damping_ratio(params.get("e")) * (k * s.mass()).sqrt();
            (
                "LinearViscoelasticSpecies",
                format!("        species.setStiffness({k:.15e});\n        species.setDissipation({c:.15e});\n"),
                format!("F = k delta + c delta_dot with k = {k:.9e} N/m, c = 2 zeta sqrt(k m*) = {c:.9e} N s/m, attraction allowed (tension = 1)."),
            )
        }
        "hertz" | "hertz-damped" => {
            let e_deck = deck_modulus(params, s);
            let e = if law == "hertz" { 1.0 } else { params.get("e") };
            (
                "HertzianViscoelasticSpecies",
                format!(
                    "        species.setEffectiveElasticModulusAndRestitutionCoefficient({e_deck:.15e}, {e:.15e});\n"
                ),
                format!(
                    "E* = E_star sqrt(R_star/R*) = {e_deck:.9e} Pa; the setter's dissipation sqrt(5)|beta| is the Tsuji damping\n\
                     // of the law (e = {e}). Whether MercuryDPM clips the force at the end of the contact was not checked: compare\n\
                     // with `twoball laws run` at tension = 0 and 1."
                ),
            )
        }
        "walton-braun" => {
            let k = params.get("k");
            let e = params.get("e");
            let k2_max = k * (2.0 / (e * e) - 1.0);
            let d_ref = s.speed * (s.mass() / k).sqrt();
            let phi = 2.0 * d_ref * (k2_max - k) / (k2_max * 2.0 * s.radius());
            (
                "LinearPlasticViscoelasticSpecies",
                format!(
                    "        species.setLoadingStiffness({k:.15e});\n\
                     \x20       species.setUnloadingStiffnessMax({k2_max:.15e});\n\
                     \x20       species.setCohesionStiffness(0.0);\n\
                     \x20       species.setPenetrationDepthMax({phi:.15e});\n\
                     \x20       species.setDissipation(0.0);\n"
                ),
                format!(
                    "Luding's unloading stiffness k2 = k1 + (k2max - k1) delta_max/delta_lim grows with the largest overlap, so\n\
                     // k2 = k1/e^2 (e = {e}) holds at VR = {v} m/s only (delta_lim = 2 delta_max there, if MercuryDPM's delta_lim\n\
                     // is k2max/(k2max - k1) phi 2R* as LIGGGHTS's; not checked by running).",
                    v = s.speed
                ),
            )
        }
        _ => return Err(cannot(
            Code::MercuryDpm,
            law,
            "a law written for MercuryDPM here: hertz, hertz-damped, linear-dashpot, walton-braun",
        )),
    };
    let run = "./twoball_mercury VR   (after building this file against MercuryDPM)";
    let mut out = String::from(
        "// NOT COMPILED HERE: written against MercuryDPM's published source and API documentation; no\n\
         // MercuryDPM is installed where twoball is tested. Build it as a MercuryDPM driver (its Drivers folder).\n",
    );
    out += &s.header("//", "MercuryDPM", run, params);
    out += &format!("// {note}\n");
    out += &format!(
        "#include \"Mercury3D.h\"\n\
         #include \"Species/{species}.h\"\n\
         #include <cstdlib>\n\
         #include <fstream>\n\
         \n\
         class TwoBalls : public Mercury3D {{\n\
         public:\n\
         \x20   explicit TwoBalls(Mdouble vr) : vr_(vr) {{}}\n\
         \x20   void setupInitialConditions() override {{\n\
         \x20       {species} species;\n\
         \x20       species.setDensity({rho:.15e});\n\
         {setters}\
         \x20       auto* sp = speciesHandler.copyAndAddObject(species);\n\
         \x20       SphericalParticle p;\n\
         \x20       p.setSpecies(sp);\n\
         \x20       p.setRadius({r:.15e});\n\
         \x20       p.setPosition(Vec3D(-{r:.15e}, 0, 0));\n\
         \x20       p.setVelocity(Vec3D(vr_ / 2, 0, 0));\n\
         \x20       particleHandler.copyAndAddObject(p);\n\
         \x20       p.setPosition(Vec3D({r:.15e}, 0, 0));\n\
         \x20       p.setVelocity(Vec3D(-vr_ / 2, 0, 0));\n\
         \x20       particleHandler.copyAndAddObject(p);\n\
         \x20       trace_.open(\"trace.txt\");\n\
         \x20       trace_.precision(17);\n\
         \x20   }}\n\
         \x20   void actionsAfterTimeStep() override {{\n\
         \x20       const BaseParticle* a = particleHandler.getObject(0);\n\
         \x20       const BaseParticle* b = particleHandler.getObject(1);\n\
         \x20       trace_ << getTime() << ' ' << a->getPosition().X << ' ' << b->getPosition().X << ' '\n\
         \x20              << a->getVelocity().X << ' ' << b->getVelocity().X << ' ' << a->getForce().X << '\\n';\n\
         \x20   }}\n\
         private:\n\
         \x20   Mdouble vr_;\n\
         \x20   std::ofstream trace_;\n\
         }};\n\
         \n\
         int main(int argc, char* argv[]) {{\n\
         \x20   TwoBalls problem(argc > 1 ? std::atof(argv[1]) : {v:.12e});\n\
         \x20   problem.setName(\"twoball\");\n\
         \x20   problem.setSystemDimensions(3);\n\
         \x20   problem.setGravity(Vec3D(0, 0, 0));\n\
         \x20   problem.setMin(Vec3D(-{b:e}, -{b:e}, -{b:e}));\n\
         \x20   problem.setMax(Vec3D({b:e}, {b:e}, {b:e}));\n\
         \x20   problem.setTimeStep({dt:.15e});\n\
         \x20   problem.setTimeMax({tmax:.15e});\n\
         \x20   problem.solve();\n\
         \x20   return 0;\n\
         }}\n",
        rho = s.density,
        r = s.diameter / 2.0,
        v = s.speed,
        b = 2.0 * s.diameter,
        dt = s.timestep,
        tmax = s.timestep * s.steps as f64,
    );
    Ok(out)
}
