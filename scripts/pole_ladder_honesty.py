#!/usr/bin/env python3
"""Whether the pole ladder's bars hold the bulk it leaves out.

`twoball run FILE --tolerance T` on an oblique or spinning 3D scene runs the pole ladder:
the pole halved per level, the bulk held at D/8 on every level. Its bars carry the pole's
part (observed order) and the bulk's share (docs/design.md, "Error estimates"). Here each of
20 oblique and spinning cases of the DEM benchmarks (verification/dem-benchmarks/) runs
(1) the ladder's three levels −1, 0, +1 (`--tolerance 1% --max-refinements 1`, where most
cases stop) and (2) its finest pole with a bulk of D/16 (`--no-error-estimate`), and the table sets each figure's bar beside the
move the finer bulk makes: e, delta_max, the contact duration, the tangential restitution
e_t, the rebound angle and ball 1's spin after. A bar holds when the move is within it.

Runs whose results.json is in DIR are read, not rerun; the whole set takes about an hour on
one core (the D/16 runs 1-5 min each).

Usage: python3 scripts/pole_ladder_honesty.py [--twoball target/release/twoball] [--out DIR]
Python 3 standard library only.
"""

import argparse
import json
import math
import os
import subprocess

FOLDER = "verification/dem-benchmarks"


def velocity(speed, deg):
    """The velocity [v cos θ, v sin θ, 0] (m/s) as a --set value."""
    t = math.radians(deg)
    return f"[{speed * math.cos(t)!r}, {speed * math.sin(t)!r}, 0]"


def spin(w, balls=1):
    """Spin w (rad/s) about z for ball 1 (and ball 2) as --sets."""
    return [f"ball{b}.angular_velocity=[0, 0, {w!r}]" for b in range(1, balls + 1)]


# name: (scene, --sets)
CASES = {f"test4-alumina@{a}": ("test4-alumina", [f"ball1.velocity={velocity(3.9, a)}"])
         for a in [5, 10, 15, 20, 25, 30, 40, 50, 60, 80]}
CASES.update({
    f"oblique-pair-alumina@{a}": ("oblique-pair-alumina", [
        f"ball1.velocity={velocity(1.95, a)}", f"ball2.velocity={velocity(-1.95, a)}"])
    for a in [10, 20]})
CASES.update({f"test5-steel@vt{vt}": ("test5-steel", [f"ball1.velocity=[5.0, {vt}, 0]"])
              for vt in [0.45, 1.5, 7.5]})
CASES["test5-polyethylene@vt1.5"] = ("test5-polyethylene", ["ball1.velocity=[5.0, 1.5, 0]"])
CASES.update({f"test6-aluminium@w{w}": ("test6-aluminium", spin(w)) for w in [0.8, 3.0, 14.0]})
CASES["test6-nylon@w3.0"] = ("test6-nylon", spin(3.0))
# The scenes of two balls (both meshed alike).
TWO_BALLS = {"oblique-pair-alumina"}


def run(twoball, out, name, scene, sets, extra):
    """Runs one case into out/name (or reads the results.json an earlier run left)."""
    done = os.path.join(out, name, "results.json")
    if not os.path.exists(done):
        cmd = [twoball, "run", os.path.join(FOLDER, scene + ".toml"), "--out",
               os.path.join(out, name)]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd + extra, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
    with open(done) as f:
        return json.load(f)


def figures(r):
    """The six figures of a run: e, delta_max (m), t_c (s), e_t, rebound (rad), spin (rad/s)."""
    t = r["tangential"]["fe"]
    return [r["e"], r["delta_max"], r["contact_duration"], t["restitution"],
            t["rebound_angle"], t["spin1_after"]]


def bars(r):
    """The ladder's bars on the six figures, same units."""
    est = r["error_estimate"]
    t = est["tangential"]
    return [est["e"]["error"], est["delta_max"]["error"], est["contact_duration"]["error"],
            t["restitution"]["error"] if "restitution" in t else float("nan"),
            t["rebound_angle"]["error"], t["spin1_after"]["error"]]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--twoball", default="target/release/twoball")
    ap.add_argument("--out", default="out/pole-ladder-honesty")
    a = ap.parse_args()
    names = ["e", "δ_max", "t_c", "e_t", "rebound", "spin"]
    held = [0] * 6
    print("| case | μ | levels | " + " | ".join(f"{n}: bar / D/16 move" for n in names) + " |")
    print("|---|---|---|" + "---|" * 6)
    for name, (scene, sets) in CASES.items():
        lad = run(a.twoball, a.out, name + "/ladder", scene, sets,
                  ["--tolerance", "1%", "--max-refinements", "1"])
        finest = lad["error_estimate"]["meshes"][-1]
        d = lad["scene"]["ball1"]["diameter"]
        mesh = f"{{size={d / 16!r},pole_size={finest['pole_size']!r}}}"
        extra = [f"ball1.mesh={mesh}"]
        if scene in TWO_BALLS:
            extra.append(f"ball2.mesh={mesh}")
        fine = run(a.twoball, a.out, f"{name}/bulk16-{finest['pole_size']!r}", scene,
                   sets + extra, ["--no-error-estimate"])
        f0, f1, b = figures(lad), figures(fine), bars(lad)
        cells = []
        for k in range(6):
            move = abs(f1[k] - f0[k]) if f0[k] is not None and f1[k] is not None else float("nan")
            ok = move <= b[k]
            held[k] += ok
            cells.append(f"{b[k]:.2g} / {move:.2g}{'' if ok else ' ✗'}")
        mu = lad["scene"]["ball1"]["material"]["mu"]
        met = "met" if lad["error_estimate"]["tolerance_met"] else "not met"
        print(f"| {name} | {mu} | {len(lad['error_estimate']['meshes'])}, {met} | "
              + " | ".join(cells) + " |")
    print()
    print(f"Bars holding the D/16 move, of {len(CASES)}: "
          + ", ".join(f"{n} {h}" for n, h in zip(names, held)))


if __name__ == "__main__":
    main()
