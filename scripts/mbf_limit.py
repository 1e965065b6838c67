#!/usr/bin/env python3
"""Where Maw, Barber & Fawcett's oblique impact holds: the FE tangential restitution e_t and
rebound angle of an elastic ball on a rigid wall, taken towards the theory's two limits.

The theory neglects the coupling of normal and tangential tractions (Dundurs' beta, which on
a rigid wall is (1 - 2 nu)/(2 (1 - nu)): 0.35 for alumina's nu = 0.23, 0.02 at nu = 0.49) and
treats the ball as a half-space (contact radius a << R). Chung & Ooi's test 4 ball
(verification/dem-benchmarks/test4-alumina.toml, D = 5 mm, mu = 0.092) with nu = 0.49 runs at
three resultant speeds (a ~ v^(2/5)), each `twoball run ... --error-estimate` (the 3D half
model and its next-coarser mesh), and the gap to the theory (results.json
`tangential.theory`) is extrapolated linearly in a/R to a/R = 0 (least squares over the
three speeds).

With --ladder the 10-degree case (or those of --angles) instead runs a pole ladder at bulk
D/8 (pole a/2.2, a/4.5, a/9, a/18 at each speed, `--no-error-estimate`) and reports the
Richardson value from the three finest poles with its grid convergence index (observed
order; outside 0.5-6, 1.25 times the larger step and no extrapolation, as twoball's
ladders). Runs whose results.json is in DIR are read, not rerun.

Usage: python3 scripts/mbf_limit.py [--twoball target/release/twoball] [--out DIR]
                                    [--ladder [--angles 10 20 ...]]
Python 3 standard library only.
"""

import argparse
import json
import math
import os
import subprocess
import sys

SCENE = "verification/dem-benchmarks/test4-alumina.toml"
NU = 0.49
MU = 0.092
SPEEDS = [3.9, 1.2333, 0.39]
ANGLES = [2, 5, 8, 10, 13, 16, 20, 25, 30, 40]
RADIUS = 0.0025
# Pole sizes (m) of the 10-degree ladder at each speed: a/2.2 ... a/18 of its Hertz radius.
LADDER = {3.9: [6e-5, 3e-5, 1.5e-5, 7.5e-6], 1.2333: [3.8e-5, 1.9e-5, 9.5e-6, 4.75e-6],
          0.39: [2.4e-5, 1.2e-5, 6e-6, 3e-6]}
LADDER_BULK = 0.000625


def run(twoball, out, name, angle, speed, extra):
    """Runs one case (or reads the results.json an earlier run left); returns it as a dict."""
    d = os.path.join(out, name)
    done = os.path.join(d, "results.json")
    if os.path.exists(done):
        with open(done) as f:
            return json.load(f)
    t = math.radians(angle)
    v = f"ball1.velocity=[{speed * math.cos(t)!r}, {speed * math.sin(t)!r}, 0]"
    cmd = [twoball, "run", SCENE, "--out", d, "--set", v, "--set", f"ball1.material.nu={NU}"]
    cmd += extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(d, "results.json")) as f:
        return json.load(f)


def fit_intercept(xs, ys):
    """Least-squares line through (xs, ys): its value at x = 0."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return my - slope * mx


def psi1(angle):
    """Maw, Barber & Fawcett's normalised angle of incidence of a ball at rest."""
    return 2 * (1 - NU) * math.tan(math.radians(angle)) / (MU * (2 - NU))


def limits(twoball, out):
    print("| θ (°) | ψ₁ | e_t FE at 3.9 / 1.2333 / 0.39 m/s (a/R) | e_t theory | e_t gap at "
          "a/R → 0 | rebound FE (rad) | rebound theory | rebound gap at a/R → 0 |")
    print("|---|---|---|---|---|---|---|---|")
    for angle in ANGLES:
        rows = []
        for speed in SPEEDS:
            r = run(twoball, out, f"limit-{angle}-{speed}", angle, speed, ["--error-estimate"])
            t, bar = r["tangential"], r["error_estimate"]["tangential"]
            a = math.sqrt(RADIUS * r["delta_max"]) / RADIUS
            rows.append((a, t["fe"], t["theory"], bar))
        theory = rows[0][2]
        et = " / ".join(f"{f['restitution']:.4f} ± {b['restitution']['error']:.4f}"
                        for _, f, _, b in rows)
        rb = " / ".join(f"{f['rebound_angle']:.5f}" for _, f, _, _ in rows)
        ars = [x[0] for x in rows]
        g_et = fit_intercept(ars, [f["restitution"] - theory["restitution"] for _, f, _, _ in rows])
        g_rb = fit_intercept(ars, [f["rebound_angle"] - theory["rebound_angle"]
                                   for _, f, _, _ in rows])
        print(f"| {angle} | {psi1(angle):.2f} | {et} (a/R {ars[0]:.4f} / {ars[1]:.4f} / "
              f"{ars[2]:.4f}) | {theory['restitution']:.4f} | {g_et:+.4f} | {rb} | "
              f"{theory['rebound_angle']:.5f} | {g_rb:+.5f} |", flush=True)


def ladder(twoball, out, angles):
    print("| θ (°) | v (m/s) | a/R | e_t at the poles | Richardson e_t ± GCI | theory | gap "
          "| rebound at the poles | Richardson ± GCI | theory | gap |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for angle, speed in [(a, v) for a in angles for v in SPEEDS]:
        tag = f"ladder-{speed}-{{}}" if angle == 10 else f"ladder-{angle}-{speed}-{{}}"
        runs = [run(twoball, out, tag.format(p), angle, speed,
                    ["--no-error-estimate", "--set",
                     f"ball1.mesh={{size={LADDER_BULK},pole_size={p}}}"])
                for p in LADDER[speed]]
        a = math.sqrt(RADIUS * runs[-1]["delta_max"]) / RADIUS
        cells = []
        for key in ["restitution", "rebound_angle"]:
            v = [r["tangential"]["fe"][key] for r in runs]
            d1, d2 = v[-2] - v[-3], v[-1] - v[-2]
            p = math.log(abs(d1 / d2)) / math.log(2) if d1 * d2 > 0 else math.nan
            if 0.5 <= p <= 6:
                ext = v[-1] + d2 / (2 ** p - 1)
                gci = 1.25 * abs(d2) / (2 ** p - 1)
            else:
                # Outside the trusted orders, as twoball's ladders: 1.25 x the larger step.
                ext, gci = v[-1], 1.25 * max(abs(d1), abs(d2))
            theory = runs[-1]["tangential"]["theory"][key]
            cells.append(f"{', '.join(f'{x:.5f}' for x in v)} | {ext:.5f} ± {gci:.5f} (p {p:.2f})"
                         f" | {theory:.5f} | {ext - theory:+.5f}")
        print(f"| {angle} | {speed} | {a:.4f} | " + " | ".join(cells) + " |", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--twoball", default="target/release/twoball")
    ap.add_argument("--out", default="mbf-limit")
    ap.add_argument("--ladder", action="store_true")
    ap.add_argument("--angles", type=float, nargs="+", default=[10])
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    try:
        if args.ladder:
            ladder(args.twoball, args.out, [a if a % 1 else int(a) for a in args.angles])
        else:
            limits(args.twoball, args.out)
    except subprocess.CalledProcessError as e:
        sys.exit(f"error: a twoball run failed: {' '.join(e.cmd)}")


if __name__ == "__main__":
    main()
