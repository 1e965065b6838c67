#!/usr/bin/env python3
"""Print the figures that verification/NOTES.md quotes, from a sweep CSV.

Usage: python3 scripts/sweep_summary.py verification/ansys/sweep.csv

Reads the CSV that `twoball report` writes (one row per case, SI units) and prints:
  * case counts per mesh setting and status, and the summed wall time;
  * the uniform-2mm e against the converged `graded` e per diameter (Figure 8 speeds);
  * graded, no tangential speed: FE against analytical e, delta_max, contact duration and eta
    per right-ball speed, and the spread of e over the diameters (the pipeline's scaling check);
  * graded, tangential speed: the drop in e against the same case without tangential speed and
    the tangential after-impact speed of ball 1 against the analytical one;
  * the largest energy error per mesh setting.
Only the standard library is used, so it runs wherever twoball's scripts run.
"""

import csv
import sys
from collections import defaultdict


def rel(a, b):
    """Relative difference (a - b) / b in per cent."""
    return 100.0 * (a - b) / b


def main(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    num = lambda r, k: float(r[k])  # noqa: E731

    print(f"# {path}: {len(rows)} cases")
    counts = defaultdict(int)
    wall = defaultdict(float)
    for r in rows:
        counts[(r["mesh"], r["status"])] += 1
        if r["wall_time [s]"]:
            wall[r["mesh"]] += num(r, "wall_time [s]")
    for (mesh, status), n in sorted(counts.items()):
        print(f"  {mesh:12s} {status:10s} {n:3d}")
    for mesh, w in sorted(wall.items()):
        print(f"  {mesh:12s} summed case wall time {w:8.1f} s")

    done = [r for r in rows if r["status"] == "done"]
    key = lambda r: (  # noqa: E731
        r["mesh"],
        round(num(r, "diameter [m]"), 6),
        round(num(r, "v2n [m/s]"), 3),
        round(num(r, "v1t [m/s]"), 3),
    )
    by = {key(r): r for r in done}

    print("\n## uniform-2mm against graded, e at +1/-1 m/s, no tangential speed")
    for d in sorted({k[1] for k in by}):
        u = by.get(("uniform-2mm", d, -1.0, 0.0))
        g = by.get(("graded", d, -1.0, 0.0))
        if u and g:
            eu, eg = num(u, "e_fe [-]"), num(g, "e_fe [-]")
            print(f"  D = {d * 1e3:4.0f} mm: e uniform {eu:.4f}, graded {eg:.4f}, {rel(eu, eg):+7.1f} %")

    print("\n## graded, no tangential speed: FE against analytical")
    speeds = sorted({k[2] for k in by if k[0] == "graded" and k[3] == 0.0})
    for v in speeds:
        cases = [r for k, r in by.items() if k[0] == "graded" and k[2] == v and k[3] == 0.0]
        if not cases:
            continue
        es = [num(r, "e_fe [-]") for r in cases]
        r = cases[0]
        print(
            f"  vr {v:+.1f}: e {num(r, 'e_fe [-]'):.4f}/{num(r, 'e_an [-]'):.4f}"
            f" ({rel(num(r, 'e_fe [-]'), num(r, 'e_an [-]')):+.1f} %),"
            f" delta_max {rel(num(r, 'delta_max_fe [m]'), num(r, 'delta_max_an [m]')):+.1f} %,"
            f" duration {rel(num(r, 'contact_duration_fe [s]'), num(r, 'contact_duration_an [s]')):+.1f} %,"
            f" eta {rel(num(r, 'eta_fe [-]'), num(r, 'eta_an [-]')):+.1f} %;"
            f" e spread over {len(es)} diameters {max(es) - min(es):.1e}"
        )

    print("\n## graded, tangential speed (D = 20 mm row shown; spread over D in brackets)")
    for vt in (0.1, 0.5):
        for v in speeds:
            cases = [r for k, r in by.items() if k[0] == "graded" and k[2] == v and k[3] == vt]
            bases = {
                k[1]: r for k, r in by.items() if k[0] == "graded" and k[2] == v and k[3] == 0.0
            }
            drops = [
                rel(num(r, "e_fe [-]"), num(bases[key(r)[1]], "e_fe [-]"))
                for r in cases
                if key(r)[1] in bases
            ]
            vts = [rel(num(r, "v1t_after_fe [m/s]"), num(r, "v1t_after_an [m/s]")) for r in cases]
            if not cases:
                continue
            r = next((c for c in cases if abs(num(c, "diameter [m]") - 0.02) < 1e-9), cases[0])
            print(
                f"  vt {vt:.1f} vr {v:+.1f}: e change {min(drops):+.2f}..{max(drops):+.2f} %,"
                f" v1t after {num(r, 'v1t_after_fe [m/s]'):.4f}/{num(r, 'v1t_after_an [m/s]'):.4f}"
                f" ({min(vts):+.1f}..{max(vts):+.1f} %)"
            )

    print("\n## largest energy error")
    for mesh in sorted({r["mesh"] for r in done}):
        worst = max((r for r in done if r["mesh"] == mesh), key=lambda r: num(r, "energy_error_fe [-]"))
        print(f"  {mesh:12s} {num(worst, 'energy_error_fe [-]'):.2e} ({worst['id']})")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: sweep_summary.py SWEEP_CSV")
    main(sys.argv[1])
