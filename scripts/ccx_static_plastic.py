#!/usr/bin/env python3
"""A quasi-static loading-unloading loop of an elastic-plastic ball on a rigid plane, with
CalculiX (ccx 2.20) and gmsh: the independent check of twoball's head-on impact.

The model is ccx_static_hertz.py's hemisphere (axisymmetric section meshed by gmsh with
quadrilaterals, graded toward the pole; rigid frictionless plane made of driven elements;
penalty contact; equator on a roller, axis with zero radial displacement), given the
bilinear elastic-plastic material of twoball's `copper-fe` preset (E = 120 GPa, nu = 0.33,
yield 100 MPa, tangent modulus E_T = E / 100, isotropic hardening: in CalculiX's *PLASTIC
table the hardening modulus is H = E E_T / (E - E_T) against plastic strain), large
deformation (NLGEOM). Two steps: the plane travels into the pole to `travel` and back to 0.

For two equal balls in a head-on impact the plane of contact is a symmetry plane, and each
ball's centre approaches it by half the total approach delta: `--delta-max` is the scene's
total approach (twoball's results.json `fe.delta_max`), and the plane travels delta_max / 2.
The force-travel loop gives, for one ball, the work done on loading W_load = int F du and
returned on unloading W_unload; the quasi-static coefficient of restitution is
e_qs = sqrt(W_unload / W_load) (the kinetic energy that comes back, with no wave losses).
The table lists F against the total approach delta = 2 u so that it compares directly with
twoball's history.csv (contact force against approach).

Units: SI (m, N, J); F is the full-ring force (CalculiX's axisymmetric reaction x 180).
Python 3 standard library + numpy; runs `gmsh` and `ccx`.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import shutil
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccx_static_hertz import (  # noqa: E402
    CheckError,
    dat_blocks,
    assemble,
    edge_faces,
    gmsh_ball,
    plane_part,
    run_ccx,
)


def model(radius, travel, per_a, far, fine_zone, growth, order, work, gmsh):
    """Hemisphere section (pole at (0, -R)) above the rigid plane at y = -R."""
    a_est = math.sqrt(2.0 * radius * travel)  # a plastic contact is wider than Hertz's
    h_c = a_est / per_a
    bn, be = gmsh_ball(work, radius, h_c, far * radius, fine_zone * a_est, growth, order, gmsh)
    reach = min(2.0 * a_est, 0.5 * radius)
    pn, pe = plane_part(1.3 * reach, -radius, 2.0 * h_c, order)
    nodes, elems, off = assemble(bn, be, pn, pe)
    tol = 1e-9 * radius
    nb = len(bn)
    on_cap = lambda p: abs(math.hypot(p[0], p[1]) - radius) < 1e-7 * radius and p[0] <= reach and p[1] < 0
    return {
        "nodes": nodes, "elems": elems, "n_body": len(be), "h_c": h_c,
        "body": range(len(be)), "plane": range(len(be), len(elems)),
        "nsets": {
            "AXIS": [k for k in range(nb) if abs(bn[k][0]) < tol],
            "EQUATOR": [k for k in range(nb) if abs(bn[k][1]) < tol],
            "PLANEN": list(range(off, len(nodes))),
            "PROBE": [off],
        },
        "slave": edge_faces(bn, be, on_cap),
        "master": [(len(be) + e, f) for e, f in edge_faces(pn, pe, lambda p: abs(p[1] + radius) < tol)],
    }


def deck(path, m, mat, travel, k_pen, element, n_inc):
    """CalculiX input: load step (plane to `travel`) and unload step (back to 0)."""
    out = ["*HEADING", "ccx_static_plastic: hemisphere on a rigid plane, load and unload",
           "*NODE, NSET=NALL"]
    out += [f"{k + 1}, {p[0]:.12e}, {p[1]:.12e}" for k, p in enumerate(m["nodes"])]
    for name, rng, el in (("BODY", m["body"], element), ("PLANE", m["plane"], element.rstrip("R"))):
        out.append(f"*ELEMENT, TYPE={el}, ELSET={name}")
        out += [f"{e + 1}, " + ", ".join(str(int(v) + 1) for v in m["elems"][e]) for e in rng]
    for name, ids in m["nsets"].items():
        out.append(f"*NSET, NSET={name}")
        ids = [int(i) + 1 for i in ids]
        out += [", ".join(str(i) for i in ids[k:k + 12]) for k in range(0, len(ids), 12)]
    hard = mat["E"] * mat["Et"] / (mat["E"] - mat["Et"])
    out += ["*MATERIAL, NAME=BODYMAT", "*ELASTIC", f"{mat['E']:.12e}, {mat['nu']:.12e}",
            "*PLASTIC", f"{mat['yield']:.12e}, 0.0", f"{mat['yield'] + hard:.12e}, 1.0",
            "*DENSITY", f"{mat['rho']:.12e}", "*SOLID SECTION, ELSET=BODY, MATERIAL=BODYMAT",
            "*MATERIAL, NAME=PLANEMAT", "*ELASTIC", f"{1000 * mat['E']:.12e}, 0.3",
            "*SOLID SECTION, ELSET=PLANE, MATERIAL=PLANEMAT"]
    for name, faces in (("SLAVE", m["slave"]), ("MASTER", m["master"])):
        out.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        out += [f"{e + 1}, S{f}" for e, f in faces]
    out += ["*SURFACE INTERACTION, NAME=FRICTIONLESS",
            "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{k_pen:.12e}",
            "*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=SURFACE TO SURFACE", "SLAVE, MASTER",
            "*BOUNDARY", "AXIS, 1, 1, 0.0", "EQUATOR, 2, 2, 0.0"]
    for target in (travel, 0.0):
        out += ["*STEP, NLGEOM, INC=10000", "*STATIC",
                f"{1.0 / n_inc:.6e}, 1.0, {1e-3 / n_inc:.6e}, {1.0 / n_inc:.6e}",
                "*BOUNDARY", "PLANEN, 1, 1, 0.0", f"PLANEN, 2, 2, {target:.12e}",
                "*NODE PRINT, NSET=PLANEN, TOTALS=ONLY", "RF",
                "*NODE PRINT, NSET=PROBE", "U", "*END STEP"]
    Path(path).write_text("\n".join(out) + "\n")


def blocks(dat, header):
    """Every non-empty .dat block whose header starts with `header`, as float arrays, in order."""
    return [np.array(b) for b in dat_blocks(dat, header) if b]


def loop(dat, factor):
    """Plane travel u (m) and full-ring force F (N) at every converged increment, from 0."""
    forces = blocks(dat, "total force (fx,fy,fz) for set PLANEN")
    disps = blocks(dat, "displacements (vx,vy,vz) for set PROBE")
    if not forces or len(forces) != len(disps):
        raise CheckError(f"{dat}: {len(forces)} force and {len(disps)} displacement outputs")
    u = np.array([0.0] + [b[0][2] for b in disps])
    f = np.array([0.0] + [factor * b[0][1] for b in forces])
    return u, f


def release(uu, fu, floor):
    """The release (m) of the unloading branch `uu`, `fu` (from the peak down) and the work
    it returns below its last point above `floor` (J), with that point's index: along F = c (u - u_r)^(3/2) through the last two such points (Hertz's law of
    the unloaded, flattened cap, as twoball's loop closes its own), so neither depends on
    where the increments fall."""
    above = np.nonzero(fu > floor)[0]
    if len(above) < 2:
        raise CheckError("the unloading branch has fewer than two points above the release floor")
    a, b = above[-2], above[-1]
    ratio = (fu[a] / fu[b]) ** (2.0 / 3.0)
    u_r = uu[b] - (uu[a] - uu[b]) / (ratio - 1.0)
    return float(u_r), float(0.4 * fu[b] * (uu[b] - u_r)), b


def at(u, f, x):
    """F at travel x on a monotone branch, linearly interpolated."""
    return float(np.interp(x, u, f))


def main(argv=None):
    ap = argparse.ArgumentParser(description="Quasi-static F(delta) loop of an elastic-plastic ball "
                                 "on a rigid plane (CalculiX, axisymmetric), its W_load, W_unload, e.")
    ap.add_argument("--delta-max", type=float, required=True,
                    help="total approach of the two balls' centres to load to, m (twoball's fe.delta_max)")
    ap.add_argument("--radius", type=float, default=0.01, help="ball radius R, m (0.01)")
    ap.add_argument("--E", type=float, default=120e9, help="Young's modulus, Pa (120e9)")
    ap.add_argument("--nu", type=float, default=0.33, help="Poisson's ratio (0.33)")
    ap.add_argument("--yield", dest="yield_", type=float, default=100e6, help="yield stress, Pa (100e6)")
    ap.add_argument("--tangent", type=float, default=1.2e9, help="tangent modulus E_T, Pa (E/100 = 1.2e9)")
    ap.add_argument("--per-a", type=float, default=20.0,
                    help="contact-zone element size as a divisor of a = sqrt(2 R u_max) (20)")
    ap.add_argument("--far-size", type=float, default=0.1, help="far element size / R (0.1)")
    ap.add_argument("--fine-zone", type=float, default=1.5, help="fine zone radius / a (1.5)")
    ap.add_argument("--growth", type=float, default=0.2, help="size gradient outside the fine zone (0.2)")
    ap.add_argument("--penalty", type=float, default=100.0, help="penalty slope K = penalty E / h_c (100)")
    ap.add_argument("--element", default="CAX8R", choices=["CAX8R", "CAX8", "CAX4"],
                    help="axisymmetric element (CAX8R: reduced integration, free of volumetric locking)")
    ap.add_argument("--increments", type=int, default=20, help="increments per step (20)")
    ap.add_argument("--history", help="twoball history.csv to compare the loading branch with")
    ap.add_argument("--csv", help="write the loop (delta m, u m, F N) to this CSV")
    ap.add_argument("--json", help="write the summary numbers to this JSON")
    ap.add_argument("--ccx", default="ccx")
    ap.add_argument("--gmsh", default="gmsh")
    ap.add_argument("--keep", help="working folder to keep (default: a temporary one, removed)")
    a = ap.parse_args(argv)
    for name in ("delta_max", "radius", "E", "yield_", "tangent", "per_a", "penalty"):
        v = getattr(a, name)
        if not (math.isfinite(v) and v > 0):
            raise CheckError(f"--{name.strip('_').replace('_', '-')} = {v}: must be a finite number > 0")
    if a.tangent >= a.E:
        raise CheckError(f"--tangent = {a.tangent}: must be below E = {a.E}")
    if a.delta_max > 0.05 * a.radius:
        raise CheckError(f"--delta-max = {a.delta_max}: above 5 % of R, outside this check")
    mat = {"E": a.E, "nu": a.nu, "yield": a.yield_, "Et": a.tangent, "rho": 7900.0}
    travel = 0.5 * a.delta_max
    work = Path(a.keep) if a.keep else Path(tempfile.mkdtemp(prefix="ccx_plastic_"))
    work.mkdir(parents=True, exist_ok=True)
    try:
        order = 1 if a.element == "CAX4" else 2
        m = model(a.radius, travel, a.per_a, a.far_size, a.fine_zone, a.growth, order, work, a.gmsh)
        deck(work / "job.inp", m, mat, travel, a.penalty * a.E / m["h_c"], a.element, a.increments)
        wall, _ = run_ccx(a.ccx, work, "job")
        u, f = loop(work / "job.dat", 180.0)
        k = int(np.argmax(u))
        ul, fl = u[: k + 1], f[: k + 1]
        w_load = float(np.trapezoid(fl, ul))
        ud, fd = u[k:], f[k:]
        u_r, tail, b = release(ud, fd, 1e-3 * fl[-1])
        w_unload = float(-np.trapezoid(fd[: b + 1], ud[: b + 1])) + tail
        res = {
            "delta_max_m": a.delta_max, "travel_m": travel, "h_c_m": m["h_c"],
            "elements": m["n_body"], "element": a.element, "increments": len(u) - 1,
            "F_half_N": at(ul, fl, 0.5 * travel), "F_max_N": float(fl[-1]),
            "W_load_J": w_load, "W_unload_J": w_unload,
            "e_quasi_static": math.sqrt(max(w_unload, 0.0) / w_load),
            "residual_travel_m": u_r,
            "ccx_wall_s": wall,
        }
        print(f"ccx {a.element}: {m['n_body']} elements, h_c = {m['h_c']:.3e} m, {len(u) - 1} increments, {wall:.1f} s")
        print(f"loading to delta = {a.delta_max:.5e} m (plane travel {travel:.5e} m a ball)")
        print(f"F(delta_max/2) = {res['F_half_N']:.5e} N   F(delta_max) = {res['F_max_N']:.5e} N")
        print(f"W_load = {w_load:.5e} J   W_unload = {w_unload:.5e} J   (one ball)")
        print(f"e_qs = sqrt(W_unload / W_load) = {res['e_quasi_static']:.5f}")
        if a.history:
            res.update(compare(a.history, a.delta_max, ul, fl, travel))
        if a.csv:
            with open(a.csv, "w", newline="") as fh:
                w = csv.writer(fh)
                w.writerow(["delta_m", "plane_travel_m", "force_N"])
                for x, y in zip(u, f):
                    w.writerow([f"{2 * x:.9e}", f"{x:.9e}", f"{y:.9e}"])
        if a.json:
            Path(a.json).write_text(json.dumps(res, indent=2) + "\n")
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)
    return 0


def compare(history, delta_max, ul, fl, travel):
    """twoball's dynamic loading branch (history.csv: approach and contact force) at
    delta_max / 2 and at its own maximum approach, against the static loop."""
    with open(history) as fh:
        rows = list(csv.DictReader(fh))
    keys = rows[0].keys()
    dk = next(k for k in keys if k.startswith("delta") or k.startswith("approach"))
    fk = next(k for k in keys if k.startswith("normal_force") or k.startswith("force"))
    d = np.array([float(r[dk]) for r in rows])
    F = np.array([float(r[fk]) for r in rows])
    k = int(np.argmax(d))
    d_load, f_load = d[: k + 1], F[: k + 1]
    out = {}
    for name, x in (("half", 0.5 * delta_max), ("max", d[k])):
        fd = float(np.interp(x, d_load, f_load))
        fs = at(ul, fl, 0.5 * x)
        out[f"F_dynamic_{name}_N"] = fd
        out[f"F_static_{name}_N"] = fs
        print(f"delta = {x:.5e} m: twoball dynamic F = {fd:.5e} N, ccx static F = {fs:.5e} N, "
              f"dynamic / static - 1 = {fd / fs - 1:+.2%}   (columns {dk}, {fk})")
    return out


if __name__ == "__main__":
    try:
        sys.exit(main())
    except CheckError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
