#!/usr/bin/env python3
"""How twoball's cost grows: wall time and peak memory of `twoball run` against element
count, ball diameter and impact speed, with fitted power-law exponents.

Three series on the built-in default scene (copper-fe, equal balls, head-on, quarter model):
- mesh: densities m (bulk size D/(6 m), pole size D/(200 m): m = 1 is the default mesh,
  src/scene.rs DEFAULT_SIZE_PER_D and DEFAULT_POLE_SIZE_PER_D); explicit dynamics expects element-cycles ~ N x steps ~ N^(4/3) for uniform
  refinement (the stable step shrinks with the element size, N ~ h^-3);
- diameter: D = 5, 10, 20, 30 mm on the D-scaled default mesh (same N; the stable step and
  the contact duration both scale with D, so the cost should not change);
- speed: relative impact speed 1, 2, 4, 8 m/s (+v/2 and -v/2) on the default mesh (the
  contact lasts ~ v^(-1/5) for Hertz; plastic contact changes it little).

Each run is a separate process (`twoball run --out DIR`), so its peak resident memory is
its own (from the kernel's rusage of that child). Wall time and element-cycles come from
results.json. Writes scaling.csv (units in the header) and prints a Markdown table with the
fitted exponents (least squares in log-log).

Usage: python3 scripts/scaling.py [--twoball target/release/twoball] [--out DIR]
Python 3 standard library only.
"""

import argparse
import json
import math
import os
import subprocess
import sys


def run(twoball, out, name, sets):
    """Runs one scene; returns (results dict, peak RSS in bytes)."""
    d = os.path.join(out, name)
    cmd = [twoball, "run", "--out", d, "--set", 'reduction.symmetry="auto-3d"']
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(p.pid, 0)
    err = p.stderr.read().decode()
    p.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"{' '.join(cmd)} failed: {err}")
    with open(os.path.join(d, "results.json")) as f:
        res = json.load(f)
    return res, usage.ru_maxrss * 1024  # Linux reports kilobytes


def mesh_sets(d, m):
    size, pole = d / (6 * m), d / (200 * m)
    return [f"ball{k}.mesh={{size={size:e},pole_size={pole:e}}}" for k in (1, 2)]


def fit(xs, ys):
    """Slope of log y against log x (least squares)."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    n = len(lx)
    mx, my = sum(lx) / n, sum(ly) / n
    sxx = sum((a - mx) ** 2 for a in lx)
    sxy = sum((a - mx) * (b - my) for a, b in zip(lx, ly))
    return sxy / sxx if sxx > 0 else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--twoball", default="target/release/twoball")
    ap.add_argument("--out", default="scaling-out")
    ap.add_argument("--densities", default="0.5,0.7071,1,1.4142,2")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for m in [float(x) for x in a.densities.split(",")]:
        rows.append(("mesh", m, 0.02, 2.0, *run(a.twoball, a.out, f"mesh_m{m:g}", mesh_sets(0.02, m))))
    for d in (0.005, 0.01, 0.02, 0.03):
        sets = [f"ball1.diameter={d}", f"ball2.diameter={d}"] + mesh_sets(d, 1.0)
        rows.append(("diameter", 1.0, d, 2.0, *run(a.twoball, a.out, f"diameter_{d * 1e3:g}mm", sets)))
    for v in (1.0, 2.0, 4.0, 8.0):
        sets = [f"ball1.velocity=[{v / 2},0,0]", f"ball2.velocity=[{-v / 2},0,0]"]
        rows.append(("speed", 1.0, 0.02, v, *run(a.twoball, a.out, f"speed_{v:g}", sets)))

    header = ("series,density_m,diameter [m],relative_speed [m/s],elements,steps,element_cycles,"
              "wall_time [s],peak_memory [MB],e [-]")
    lines = [header]
    table = {}
    for series, m, d, v, res, rss in rows:
        fe = res["fe"]
        n, cyc, wall = fe["elements"], fe["element_cycles"], res["wall_time_s"]
        steps = fe.get("steps", "")
        lines.append(f"{series},{m},{d},{v},{n},{steps},{cyc},{wall:.3f},{rss / 1e6:.1f},{res['e']:.6e}")
        table.setdefault(series, []).append((m, d, v, n, steps, cyc, wall, rss, res["e"]))
    tmp = os.path.join(a.out, "scaling.csv.tmp")
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, os.path.join(a.out, "scaling.csv"))

    print("| series | m | D (mm) | v_rel (m/s) | elements | element-cycles | wall (s) | peak memory (MB) | e |")
    print("|---|---|---|---|---|---|---|---|---|")
    for series, rs in table.items():
        for m, d, v, n, steps, cyc, wall, rss, e in rs:
            print(f"| {series} | {m:g} | {d * 1e3:g} | {v:g} | {n} | {cyc:.3e} | {wall:.2f} | {rss / 1e6:.1f} | {e:.4f} |")
    print()
    mesh = table["mesh"]
    ns = [r[3] for r in mesh]
    print(f"mesh: element-cycles ~ N^{fit(ns, [r[5] for r in mesh]):.2f}, "
          f"wall time ~ N^{fit(ns, [r[6] for r in mesh]):.2f}, "
          f"peak memory ~ N^{fit(ns, [r[7] for r in mesh]):.2f} (expected: 4/3, 4/3, 1)")
    dia = table["diameter"]
    print(f"diameter: wall time ~ D^{fit([r[1] for r in dia], [r[6] for r in dia]):.2f}, "
          f"element-cycles ~ D^{fit([r[1] for r in dia], [r[5] for r in dia]):.2f} (expected 0)")
    sp = table["speed"]
    print(f"speed: wall time ~ v^{fit([r[2] for r in sp], [r[6] for r in sp]):.2f}, "
          f"element-cycles ~ v^{fit([r[2] for r in sp], [r[5] for r in sp]):.2f} "
          "(Hertz contact time ~ v^-0.2)")


if __name__ == "__main__":
    main()
