#!/usr/bin/env python3
"""An independent check of Hertz's law for a finite ball, with CalculiX (ccx 2.20) and gmsh.

An elastic hemisphere (radius R, Young's modulus E, Poisson's ratio nu; linear elastic, small
strain, static) rests with its pole on a rigid frictionless plane. The plane is pushed into
the pole by a prescribed travel `depth`; the flat equatorial face is held axially only
(roller: axial displacement 0, radial free), the axis carries the usual axisymmetric
condition (radial displacement 0). This is twoball's static contact test, and the script
asks whether the contact force F of the finite ball differs from Hertz's half-space law

    F_H = 4/3 * E / (1 - nu^2) * sqrt(R) * delta_e^(3/2),   a_H = sqrt(R * delta_e),

with delta_e the elastic approach of the ball: the axial displacement of the pole relative
to the equator, = plane travel - penetration of the ball into the plane (the plane is rigid
and the equator does not move axially).

Model choices:
- Axisymmetric 8-node quadrilaterals (CAX8; CAX4 on request), which CalculiX expands into a
  thin 3D wedge. The ball's cross-section is meshed by gmsh with quadrilaterals only
  (recombination + one subdivision), graded from the contact size h_c = a_H / --per-a
  around the pole (out to --fine-zone * a_H) to --far-size * R far away.
- The rigid plane is a row of elements below the pole with every node's displacement
  prescribed (radial 0, axial = depth): it cannot deform, so it has no compliance to
  subtract. Its total axial reaction is the contact force.
- Frictionless penalty contact (PRESSURE-OVERCLOSURE=LINEAR), SURFACE TO SURFACE by default
  (NODE TO SURFACE with --contact node), slave = the ball's surface out to 3 a_H, master =
  the plane's top face; slope K = --penalty * E / h_c (Pa/m).
- The penetration is measured at the contact centre by a fit pen(r) = c0 + c2 r^2 to the
  surface nodes at a_H / 4 < r < a_H / 2, and delta_e = depth - c0. The nodes near the axis
  are left out: with surface-to-surface contact ccx 2.20 lets them sink into the plane
  (6 % of delta over one CAX8 element at h_c = a/10, 15 % over three CAX4 elements; a local
  defect that --sanity shows on a cylinder too, and that leaves the total force alone to
  within about 0.05 %: CAX4 and CAX8, surface- and node-to-surface agree that closely).
- CalculiX reports the forces of axisymmetric models for a 2-degree segment: the full ring
  is 180 x the printed reaction. `--sanity` measures this factor on a solid cylinder
  compressed uniaxially (exact force E eps pi r^2), once with its end driven directly and
  once through the same contact and plane, and then uses the measured factor.
- The contact radius a_c is where the gap between the deformed ball surface and the plane
  changes sign (linear interpolation between surface nodes); a_H uses the measured delta_e.
  Being a zero crossing of a penalty gap it is only good to about one element.
- Hertz's paraboloid differs from the true sphere: a rigid sphere indenting a half-space
  (Sneddon) gives F = F_H (1 - 0.1 delta/R), -0.08 % at depth 80 um. Everything else that
  separates F from F_H is the finite ball (or the mesh).

Units: SI throughout (m, Pa, N); the table prints depths in micrometres and forces in N
(full ball, 360 degrees). Python 3.11 standard library + numpy; runs the external programs
`gmsh` (4.x) and `ccx` (CalculiX 2.20) in a temporary directory.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

# CalculiX's data line writes 3-digit exponents without the E (1.0-100).
FLOAT_FIX = re.compile(r"(\d)([+-]\d{3})\b")


class CheckError(Exception):
    """A user-facing failure: one line naming what went wrong."""


# ----------------------------------------------------------------------------- meshing


def gmsh_ball(work, radius, h_contact, h_far, fine_radius, growth, order, gmsh="gmsh", full=False):
    """Meshes the ball's quarter-disc cross-section (centre at the origin, pole at
    (0, -R), equator on y = 0), or with `full` its half-disc (up to the north pole (0, R)),
    with quadrilaterals: nodes (n, 2), elements (e, 4 or 8), 0-based, counter-clockwise,
    gmsh / CalculiX node order (corners, then mid-edges)."""
    # gmsh halves every edge in the final all-quad subdivision: ask for twice the sizes.
    s_c, s_f = 2.0 * h_contact, 2.0 * h_far
    dist_max = fine_radius + (s_f - s_c) / growth
    if full:
        outline = f"""Point(4) = {{0, R, 0, {s_f!r}}};
Line(1) = {{1, 2}};
Circle(2) = {{2, 1, 3}};
Circle(3) = {{3, 1, 4}};
Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}};"""
    else:
        outline = """Line(1) = {1, 2};
Circle(2) = {2, 1, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};"""
    geo = f"""// ball cross-section for ccx_static_hertz.py (SI units)
R = {radius!r};
Point(1) = {{0, 0, 0, {s_f!r}}};
Point(2) = {{0, -R, 0, {s_c!r}}};
Point(3) = {{R, 0, 0, {s_f!r}}};
{outline}
Plane Surface(1) = {{1}};
Physical Surface("ball") = {{1}};
Field[1] = Distance;
Field[1].PointsList = {{2}};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = {s_c!r};
Field[2].SizeMax = {s_f!r};
Field[2].DistMin = {fine_radius!r};
Field[2].DistMax = {dist_max!r};
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6;
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 1;
Mesh.SubdivisionAlgorithm = 1;
Mesh.ElementOrder = {order};
Mesh.SecondOrderIncomplete = 1;
"""
    geo_path, msh_path = Path(work) / "ball.geo", Path(work) / "ball.msh"
    geo_path.write_text(geo)
    cmd = [gmsh, str(geo_path), "-2", "-format", "msh22", "-o", str(msh_path)]
    try:
        r = subprocess.run(cmd, capture_output=True, text=True)
    except FileNotFoundError:
        raise CheckError(f"gmsh not found ({gmsh}): install gmsh or pass --gmsh PATH") from None
    if r.returncode != 0 or not msh_path.exists():
        raise CheckError(f"gmsh failed: {(r.stderr or r.stdout).strip()[-400:]}")
    return read_msh22(msh_path, 16 if order == 2 else 3)


def read_msh22(path, etype):
    """Nodes (x, y) and elements of one gmsh type from an MSH 2.2 ASCII file."""
    lines = Path(path).read_text().split("\n")
    i = lines.index("$Nodes") + 1
    n = int(lines[i])
    raw = np.array([lines[i + 1 + k].split() for k in range(n)], dtype=float)
    tags = raw[:, 0].astype(np.int64)
    index = np.full(tags.max() + 1, -1, dtype=np.int64)
    index[tags] = np.arange(n)
    i = lines.index("$Elements") + 1
    m = int(lines[i])
    elems, other = [], set()
    for k in range(m):
        p = lines[i + 1 + k].split()
        t, ntags = int(p[1]), int(p[2])
        if t == etype:
            elems.append([int(x) for x in p[3 + ntags:]])
        elif int(p[1]) not in (1, 8, 15):  # edges and points are expected
            other.add(t)
    if other:
        raise CheckError(f"{path}: gmsh left element types {sorted(other)} (need quadrilaterals only)")
    el = index[np.array(elems, dtype=np.int64)]
    return raw[:, 1:3].copy(), orient_ccw(raw[:, 1:3], el)


def orient_ccw(nodes, elems):
    """Reorders elements with clockwise corners (negative area) to counter-clockwise."""
    c = nodes[elems[:, :4]]
    area2 = np.sum(c[:, :, 0] * np.roll(c[:, :, 1], -1, axis=1) - np.roll(c[:, :, 0], -1, axis=1) * c[:, :, 1], axis=1)
    out = elems.copy()
    flip = area2 < 0
    corner = [0, 3, 2, 1]
    out[np.ix_(flip, range(4))] = elems[np.ix_(flip, corner)]
    if elems.shape[1] == 8:  # mid-edge nodes: edge 0-1 becomes 0-3 (old edge 3-0) etc.
        out[np.ix_(flip, range(4, 8))] = elems[np.ix_(flip, [7, 6, 5, 4])]
    return out


def structured_block(x0, x1, y0, y1, nx, ny, order):
    """A structured rectangle of quadrilaterals (order 1: 4 nodes, 2: 8 nodes), CCW."""
    xs = np.linspace(x0, x1, order * nx + 1)
    ys = np.linspace(y0, y1, order * ny + 1)
    grid = -np.ones((len(ys), len(xs)), dtype=np.int64)
    nodes = []
    for j, y in enumerate(ys):
        for i, x in enumerate(xs):
            if order == 2 and i % 2 == 1 and j % 2 == 1:
                continue  # serendipity element: no centre node
            grid[j, i] = len(nodes)
            nodes.append((x, y))
    elems = []
    for j in range(ny):
        for i in range(nx):
            a, b = order * i, order * j
            e = [grid[b, a], grid[b, a + order], grid[b + order, a + order], grid[b + order, a]]
            if order == 2:
                e += [grid[b, a + 1], grid[b + 1, a + 2], grid[b + 2, a + 1], grid[b + 1, a]]
            elems.append(e)
    return np.array(nodes, dtype=float), np.array(elems, dtype=np.int64)


def edge_faces(nodes, elems, on_edge):
    """(element, face number 1..4) of the element edges whose two corners satisfy on_edge
    (face k joins corners k and k+1, as CalculiX numbers the faces of plane elements)."""
    out = []
    for e, el in enumerate(elems):
        for k in range(4):
            p, q = nodes[el[k]], nodes[el[(k + 1) % 4]]
            if on_edge(p) and on_edge(q):
                out.append((e, k + 1))
    return out


# ----------------------------------------------------------------------------- deck


def write_deck(path, model, mat, depth, k_pen, element, n_inc, contact="surface"):
    """Writes a CalculiX deck: body (ELSET BODY) + rigid plane (ELSET PLANE) in contact, the
    plane's nodes (NSET PLANEN) driven axially by `depth`. A model without a plane drives
    PLANEN (then nodes of the body) directly, without contact."""
    nodes, elems = model["nodes"], model["elems"]
    out = ["*HEADING", f"ccx_static_hertz: {model['title']}", "*NODE, NSET=NALL"]
    out += [f"{k + 1}, {p[0]:.12e}, {p[1]:.12e}" for k, p in enumerate(nodes)]
    for name, rng in (("BODY", model["body_elems"]), ("PLANE", model["plane_elems"])):
        if not len(rng):
            continue
        out.append(f"*ELEMENT, TYPE={element}, ELSET={name}")
        out += [f"{e + 1}, " + ", ".join(str(int(v) + 1) for v in elems[e]) for e in rng]
    for name, ids in model["nsets"].items():
        out.append(f"*NSET, NSET={name}")
        ids = [int(i) + 1 for i in ids]
        out += [", ".join(str(i) for i in ids[k:k + 12]) for k in range(0, len(ids), 12)]
    out += ["*MATERIAL, NAME=BODYMAT", "*ELASTIC", f"{mat['E']:.12e}, {mat['nu']:.12e}",
            "*DENSITY", f"{mat['rho']:.12e}", "*SOLID SECTION, ELSET=BODY, MATERIAL=BODYMAT"]
    if model["slave"]:
        for name, faces in (("SLAVE", model["slave"]), ("MASTER", model["master"])):
            out.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
            out += [f"{e + 1}, S{f}" for e, f in faces]
        # The plane's material is irrelevant: all its displacements are prescribed.
        kind = "SURFACE TO SURFACE" if contact == "surface" else "NODE TO SURFACE"
        out += ["*MATERIAL, NAME=PLANEMAT", "*ELASTIC", f"{1000 * mat['E']:.12e}, 0.3",
                "*SOLID SECTION, ELSET=PLANE, MATERIAL=PLANEMAT",
                "*SURFACE INTERACTION, NAME=FRICTIONLESS",
                "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{k_pen:.12e}",
                f"*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE={kind}", "SLAVE, MASTER"]
    out += ["*BOUNDARY"]
    out += [f"{s}, {d}, {d}, 0.0" for s, d in model["fixed"]]
    out += [f"*STEP, INC=1000", "*STATIC", f"{1.0 / n_inc:.6e}, 1.0, {1e-4 / n_inc:.6e}, {1.0 / n_inc:.6e}",
            "*BOUNDARY"] + (["PLANEN, 1, 1, 0.0"] if model["slave"] else []) + [
            f"PLANEN, 2, 2, {depth:.12e}"] + (
            # The free ball's body force: uniform, towards the plane (-y), m/s^2.
            ["*DLOAD", f"BODY, GRAV, {model['gravity']:.12e}, 0., -1., 0."] if model.get("gravity") else []) + [
            "*NODE PRINT, NSET=PLANEN, TOTALS=ONLY", "RF",
            "*NODE PRINT, NSET=SURFN", "U",
            "*NODE PRINT, NSET=PROBE", "U"] + (
            ["*NODE PRINT, NSET=NORTH, TOTALS=ONLY", "RF", "*NODE PRINT, NSET=BODYN", "U"]
            if "NORTH" in model["nsets"] else []) + ["*END STEP", ""]
    Path(path).write_text("\n".join(out))


def run_ccx(ccx, work, job):
    """Runs ccx on work/job.inp with one thread; returns (wall time s, log text)."""
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_STIFFNESS="1", CCX_NPROC_RESULTS="1",
               CCX_NPROC_EQUATION_SOLVER="1", NUMBER_OF_CPUS="1")
    t0 = time.perf_counter()
    try:
        r = subprocess.run([ccx, "-i", job], cwd=work, capture_output=True, text=True, env=env)
    except FileNotFoundError:
        raise CheckError(f"ccx not found ({ccx}): install CalculiX or pass --ccx PATH") from None
    wall = time.perf_counter() - t0
    log = r.stdout + r.stderr
    (Path(work) / f"{job}.log").write_text(log)
    if r.returncode != 0 or "*ERROR" in log:
        err = [ln.strip() for ln in log.splitlines() if "ERROR" in ln][:3]
        raise CheckError(f"ccx failed (exit {r.returncode}) on {work}/{job}.inp: {' | '.join(err)}")
    return wall, log


def dat_blocks(dat, header):
    """Every .dat block whose header line starts with `header`, in order: lists of rows of
    floats (a block may be empty)."""
    blocks, rows = [], None
    for line in Path(dat).read_text().splitlines():
        s = line.strip()
        if s.startswith(header):
            rows = []
            blocks.append(rows)
        elif rows is not None:
            if not s:
                if rows:
                    rows = None
                continue
            if s[0].isalpha():
                rows = None
                continue
            rows.append([float(x) for x in FLOAT_FIX.sub(r"\1E\2", s).split()])
    return blocks


def last_block(dat, header):
    """The rows of the last .dat block whose header line starts with `header`, (k, cols)."""
    blocks = dat_blocks(dat, header)
    if not blocks or not blocks[-1]:
        raise CheckError(f"{dat}: no block '{header}'")
    return np.array(blocks[-1], dtype=float)


# ----------------------------------------------------------------------------- models


def plane_part(x_max, y_top, h, order):
    """The rigid plane: a row of elements under y = y_top, from the axis to x_max."""
    nx = max(8, int(math.ceil(x_max / h)))
    return structured_block(0.0, x_max, y_top - x_max / nx, y_top, nx, 1, order)


def assemble(body_nodes, body_elems, plane_nodes, plane_elems):
    """Joins body and plane into one numbering."""
    off = len(body_nodes)
    nodes = np.vstack([body_nodes, plane_nodes])
    return nodes, np.vstack([body_elems, plane_elems + off]), off


def ball_model(radius, depth, h_contact, h_far, fine_zone, growth, order, work, gmsh, support="held"):
    """The hemisphere (held: roller at the equator) or the whole ball (free: only its north
    pole held axially, to fix the rigid-body mode; loaded by a body force) above the rigid
    plane, which touches the pole at y = -R: node sets, the slave (ball surface out to 3 a_H)
    and master (plane top) faces."""
    a_h = math.sqrt(radius * depth)
    free = support == "free"
    bn, be = gmsh_ball(work, radius, h_contact, h_far, fine_zone * a_h, growth, order, gmsh, full=free)
    reach = min(3.0 * a_h, 0.5 * radius)  # slave surface: the ball's surface out to here
    pn, pe = plane_part(1.3 * reach, -radius, h_contact * 4.0, order)
    nodes, elems, off = assemble(bn, be, pn, pe)
    tol = 1e-9 * radius
    nb = len(bn)
    # The southern cap only (the free ball's northern cap has small radii too).
    on_sphere = lambda p: abs(math.hypot(p[0], p[1]) - radius) < 1e-7 * radius and p[0] <= reach and p[1] < 0
    slave = edge_faces(bn, be, on_sphere)
    master = [(len(be) + e, f) for e, f in edge_faces(pn, pe, lambda p: abs(p[1] + radius) < tol)]
    surf = [k for k in range(nb) if on_sphere(bn[k])]
    pole = int(np.argmin(np.hypot(bn[:, 0], bn[:, 1] + radius)))
    if np.hypot(bn[pole, 0], bn[pole, 1] + radius) > tol:
        raise CheckError("no mesh node at the pole")
    if free:
        north = int(np.argmin(np.hypot(bn[:, 0], bn[:, 1] - radius)))
        if np.hypot(bn[north, 0], bn[north, 1] - radius) > tol:
            raise CheckError("no mesh node at the north pole")
        return {
            "title": f"free ball R = {radius} m, depth = {depth} m",
            "nodes": nodes, "elems": elems,
            "body_elems": range(len(be)), "plane_elems": range(len(be), len(elems)),
            "nsets": {
                "AXIS": [k for k in range(nb) if abs(bn[k][0]) < tol],
                "NORTH": [north],
                "BODYN": list(range(nb)),
                "PLANEN": list(range(off, len(nodes))),
                "SURFN": sorted(surf, key=lambda k: bn[k][0]),
                "PROBE": [pole],
            },
            "fixed": [("AXIS", 1), ("NORTH", 2)],
            "slave": slave, "master": master,
            "n_body_elems": len(be), "pole": pole,
        }
    return {
        "title": f"hemisphere R = {radius} m, depth = {depth} m",
        "nodes": nodes, "elems": elems,
        "body_elems": range(len(be)), "plane_elems": range(len(be), len(elems)),
        "nsets": {
            "AXIS": [k for k in range(nb) if abs(bn[k][0]) < tol],
            "EQUATOR": [k for k in range(nb) if abs(bn[k][1]) < tol],
            "PLANEN": list(range(off, len(nodes))),
            "SURFN": sorted(surf, key=lambda k: bn[k][0]),
            "PROBE": [pole],
        },
        "fixed": [("AXIS", 1), ("EQUATOR", 2)],
        "slave": slave, "master": master,
        "n_body_elems": len(be), "pole": pole,
    }


def cylinder_model(radius, height, n, order, contact):
    """Sanity case: a solid cylinder (radius x height), its top held axially (roller), its
    bottom pushed up uniformly: uniaxial compression, force E eps pi r^2. With `contact` the
    bottom is pushed by the rigid plane through the contact; without, its nodes are driven."""
    bn, be = structured_block(0.0, radius, 0.0, height, n, n, order)
    tol = 1e-9 * radius
    nb = len(bn)
    bottom = sorted((k for k in range(nb) if abs(bn[k][1]) < tol), key=lambda k: bn[k][0])
    model = {
        "title": f"sanity cylinder r = {radius} m, L = {height} m, contact {contact}",
        "nsets": {
            "AXIS": [k for k in range(nb) if abs(bn[k][0]) < tol],
            "TOP": [k for k in range(nb) if abs(bn[k][1] - height) < tol],
            "SURFN": bottom,
            "PROBE": bottom[:1],
        },
        "fixed": [("AXIS", 1), ("TOP", 2)],
        "n_body_elems": len(be), "body_elems": range(len(be)),
    }
    if not contact:
        model.update(nodes=bn, elems=be, plane_elems=range(0), slave=[], master=[])
        model["nsets"]["PLANEN"] = bottom
        return model
    pn, pe = plane_part(1.5 * radius, 0.0, radius / n, order)
    nodes, elems, off = assemble(bn, be, pn, pe)
    model.update(nodes=nodes, elems=elems, plane_elems=range(len(be), len(elems)),
                 slave=edge_faces(bn, be, lambda p: abs(p[1]) < tol),
                 master=[(len(be) + e, f) for e, f in edge_faces(pn, pe, lambda p: abs(p[1]) < tol)])
    model["nsets"]["PLANEN"] = list(range(off, len(nodes)))
    return model


# ----------------------------------------------------------------------------- runs


def surface_displacements(dat, model, setname="SURFN"):
    """Initial coordinates (k, 2) and final displacements (k, 2) of a node set, by radius."""
    rows = last_block(dat, f"displacements (vx,vy,vz) for set {setname}")
    where = {int(n) - 1: r[1:3] for n, r in zip(rows[:, 0], rows)}
    ids = model["nsets"][setname]
    return model["nodes"][ids], np.array([where[k] for k in ids])


def sanity(a, mat, work):
    """Measures the factor from CalculiX's axisymmetric reaction force to the full ring
    (cylinder driven directly), then checks the contact path with the same cylinder."""
    r0, length, eps, n = 0.01, 0.01, 1e-3, 6
    order = 2 if a.element == "CAX8" else 1
    factor = None
    for contact in (False, True):
        model = cylinder_model(r0, length, n, order, contact)
        job = "sanity_contact" if contact else "sanity_bare"
        k_pen = a.penalty * mat["E"] / (length / n)
        write_deck(Path(work) / f"{job}.inp", model, mat, eps * length, k_pen, a.element,
                   a.increments if contact else 1, a.contact)
        wall, _ = run_ccx(a.ccx, work, job)
        dat = Path(work) / f"{job}.dat"
        rf = last_block(dat, "total force")[0]
        xy, u = surface_displacements(dat, model)
        if not contact:
            exact = mat["E"] * eps * math.pi * r0 ** 2
            factor = exact / rf[1]
            print(f"sanity 1 (no contact): cylinder r = L = {r0} m, bottom driven by eps L = {eps * length:.1e} m: "
                  f"ccx reaction {rf[1]:.6e} N, exact E eps pi r^2 = {exact:.6e} N -> full ring = "
                  f"{factor:.4f} x ccx (= 360 deg / {360 / factor:.4f} deg) [{wall:.1f} s]")
        else:
            shortening = np.median(u[:, 1])
            exact = mat["E"] * shortening / length * math.pi * r0 ** 2
            print(f"sanity 2 (through the contact): bottom displacement median {shortening:.6e} m, "
                  f"axis node {u[0, 1]:.6e} m, range {u[:, 1].min():.6e}..{u[:, 1].max():.6e} m; "
                  f"force {factor * rf[1]:.6e} N vs E eps pi r^2 = {exact:.6e} N "
                  f"({factor * rf[1] / exact - 1:+.3%}) [{wall:.1f} s]")
    return factor


def hertz(mat, radius, delta):
    e_star = mat["E"] / (1.0 - mat["nu"] ** 2)
    return 4.0 / 3.0 * e_star * math.sqrt(radius) * max(delta, 0.0) ** 1.5, math.sqrt(radius * max(delta, 0.0))


def contact_radius(surf_xy, surf_u, plane_y):
    """Where the gap of the deformed surface to the plane changes sign (m), or nan."""
    x = surf_xy[:, 0] + surf_u[:, 0]
    gap = surf_xy[:, 1] + surf_u[:, 1] - plane_y  # < 0: penetrating (in contact)
    order = np.argsort(surf_xy[:, 0])
    x, gap = x[order], gap[order]
    open_ = np.nonzero(gap > 0)[0]
    if not len(open_) or open_[0] == 0:
        return float("nan")
    k = open_[0]
    return float(x[k - 1] + (x[k] - x[k - 1]) * (-gap[k - 1]) / (gap[k] - gap[k - 1]))


def centre_penetration(xy, u, plane_y, a_h, h_c):
    """Penetration of the ball into the plane at the contact centre (m): a fit
    pen(r) = c0 + c2 r^2 over the surface nodes at a_h / 4 < r < a_h / 2. The nodes near
    the axis are left out: with surface-to-surface contact, ccx 2.20 lets them sink into the
    plane in axisymmetric models (the element at the axis with CAX8, about three with CAX4;
    see --sanity)."""
    r = xy[:, 0]
    pen = plane_y - (xy[:, 1] + u[:, 1])
    use = (r > max(0.25 * a_h, 1.5 * h_c)) & (r < 0.5 * a_h)
    if use.sum() < 2:
        raise CheckError("too few surface nodes within a/2 of the pole to measure the penetration")
    c = np.polyfit(r[use] ** 2, pen[use], 1)
    return float(c[1])


def serendipity(xi, eta):
    """Shape functions (8) and their xi, eta derivatives of the 8-node quadrilateral, in
    CalculiX's node order (corners counter-clockwise from (-1, -1), then mid-edges)."""
    cx = np.array([-1, 1, 1, -1]); cy = np.array([-1, -1, 1, 1])
    n = np.empty(8); dx = np.empty(8); dy = np.empty(8)
    for k in range(4):
        a, b = cx[k], cy[k]
        n[k] = 0.25 * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1)
        dx[k] = 0.25 * a * (1 + b * eta) * (2 * a * xi + b * eta)
        dy[k] = 0.25 * b * (1 + a * xi) * (a * xi + 2 * b * eta)
    for k, (a, b) in enumerate(((0, -1), (1, 0), (0, 1), (-1, 0))):
        if a == 0:
            n[4 + k] = 0.5 * (1 - xi * xi) * (1 + b * eta)
            dx[4 + k] = -xi * (1 + b * eta)
            dy[4 + k] = 0.5 * b * (1 - xi * xi)
        else:
            n[4 + k] = 0.5 * (1 + a * xi) * (1 - eta * eta)
            dx[4 + k] = 0.5 * a * (1 - eta * eta)
            dy[4 + k] = -eta * (1 + a * xi)
    return n, dx, dy


def centre_of_mass_shift(nodes, elems, u):
    """Axial displacement of the centre of mass of a solid of revolution (m) and its volume
    (m^3, full ring): the 3 x 3 Gauss integrals of u_y 2 pi r and 2 pi r over the cross-section,
    with the elements' own shape functions (8-node serendipity, or bilinear for 4 nodes)."""
    g = np.sqrt(0.6)
    pts = [(-g, 5 / 9), (0.0, 8 / 9), (g, 5 / 9)]
    num = vol = 0.0
    for el in elems:
        x, uy = nodes[el], u[el, 1]
        for xi, wx in pts:
            for eta, wy in pts:
                if len(el) == 8:
                    n, dx, dy = serendipity(xi, eta)
                else:
                    n = 0.25 * np.array([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta), (1 - xi) * (1 + eta)])
                    dx = 0.25 * np.array([-(1 - eta), 1 - eta, 1 + eta, -(1 + eta)])
                    dy = 0.25 * np.array([-(1 - xi), -(1 + xi), 1 + xi, 1 - xi])
                jac = np.array([[dx @ x[:, 0], dx @ x[:, 1]], [dy @ x[:, 0], dy @ x[:, 1]]])
                w = wx * wy * abs(np.linalg.det(jac)) * 2 * math.pi * (n @ x[:, 0])
                num += w * (n @ uy)
                vol += w
    return num / vol, vol


def ball_case(a, mat, work, depth, per_a, factor):
    radius = a.radius
    h_c = math.sqrt(radius * depth) / per_a
    job = f"ball_{depth * 1e6:g}um_a{per_a:g}".replace(".", "p")
    sub = Path(work) / job
    sub.mkdir(parents=True, exist_ok=True)
    model = ball_model(radius, depth, h_c, a.far_size * radius, a.fine_zone, a.growth,
                       2 if a.element == "CAX8" else 1, sub, a.gmsh, a.support)
    k_pen = a.penalty * mat["E"] / h_c
    plane_y = -radius + depth
    free = a.support == "free"
    if free:
        # The body force B = rho g V that the contact force F balances: start from Hertz's
        # force at the travel, then solve F(B) - B = 0 by secant steps (F depends on B: the
        # lower half's weight presses on the plane) until the north pole carries less than
        # 1e-4 of F; its constraint then only fixes the rigid-body mode.
        volume = 4.0 / 3.0 * math.pi * radius ** 3
        model["gravity"] = hertz(mat, radius, depth)[0] / (mat["rho"] * volume)
    wall, tried = 0.0, []
    for it in range(8):
        write_deck(sub / "job.inp", model, mat, depth, k_pen, a.element, a.increments, a.contact)
        w, _ = run_ccx(a.ccx, sub, "job")
        wall += w
        dat = sub / "job.dat"
        force = factor * last_block(dat, "total force (fx,fy,fz) for set PLANEN")[0][1]
        if not free:
            break
        north = factor * last_block(dat, "total force (fx,fy,fz) for set NORTH")[0][1]
        if abs(north) < 1e-4 * abs(force):
            break
        b = model["gravity"] * mat["rho"] * volume
        tried.append((b, force - b))
        if len(tried) == 1:
            b_next = force
        else:
            (b0, r0), (b1, r1) = tried[-2], tried[-1]
            b_next = b1 - r1 * (b1 - b0) / (r1 - r0)
        model["gravity"] = b_next / (mat["rho"] * volume)
    else:
        raise CheckError(f"free ball at {depth * 1e6:g} um: the north-pole reaction did not vanish "
                         f"({north:.3e} N of {force:.3e} N after 8 runs)")
    xy, u = surface_displacements(dat, model)
    pen = centre_penetration(xy, u, plane_y, math.sqrt(radius * depth), h_c)
    extra = {}
    if free:
        # The approach that an impact's momentum sees: plane travel minus the axial shift
        # of the ball's centre of mass (not the pole's, which the contact indents).
        nb = model["n_body_elems"]
        body = model["elems"][:nb]
        rows = last_block(dat, "displacements (vx,vy,vz) for set BODYN")
        u_all = np.zeros((len(model["nodes"]), 2))
        u_all[rows[:, 0].astype(int) - 1] = rows[:, 1:3]
        shift, vol = centre_of_mass_shift(model["nodes"], body, u_all)
        delta_e = depth - shift
        extra = {"com_shift": shift, "volume_error": vol / (4.0 / 3.0 * math.pi * radius ** 3) - 1.0,
                 "north": north, "gravity": model["gravity"], "runs": it + 1}
    else:
        delta_e = depth - pen
    f_h, a_h = hertz(mat, radius, delta_e)
    a_c = contact_radius(xy, u, plane_y)
    if not a.keep:
        for p in sub.glob("job.*"):
            if p.suffix in (".frd", ".dat", ".cvg", ".sta"):
                p.unlink()
    return {
        "depth": depth, "per_a": per_a, "h_c": h_c, "elements": model["n_body_elems"],
        "delta_e": delta_e, "F": force, "F_H": f_h, "ratio": force / f_h - 1.0,
        "a_c": a_c, "a_H": a_h, "a_ratio": a_c / a_h - 1.0, "penetration": pen,
        "pole_node_u": float(u[0, 1]), "wall": wall, "k_pen": k_pen, **extra,
    }


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="Force of an elastic hemisphere pressed onto a rigid frictionless plane, "
                    "by CalculiX (axisymmetric, static), against Hertz's law. Prints a table "
                    "of F/F_H - 1 for each depth and contact-zone mesh size.",
        epilog="Model choices and units: see the module docstring (python3 -m pydoc on this file).")
    ap.add_argument("--depths", default="5,20,80", help="plane travels, micrometres, comma-separated (5,20,80)")
    ap.add_argument("--per-a", default="10,20,40",
                    help="contact-zone element sizes as divisors of a_H = sqrt(R depth), comma-separated "
                         "(10,20,40: h_c = a/10, a/20, a/40)")
    ap.add_argument("--radius", type=float, default=0.01, help="ball radius R, m (0.01)")
    ap.add_argument("--E", type=float, default=120e9, help="Young's modulus, Pa (120e9)")
    ap.add_argument("--nu", type=float, default=0.33, help="Poisson's ratio (0.33)")
    ap.add_argument("--rho", type=float, default=8900.0,
                    help="density, kg/m^3 (8900; only the free ball's body force uses it, and its "
                         "result does not depend on it)")
    ap.add_argument("--support", default="held", choices=["held", "free"],
                    help="held: hemisphere on a roller at its equator (default); free: the whole ball, "
                         "loaded by the uniform body force that balances the contact force (the "
                         "quasi-static image of an impact's deceleration), approach measured at the "
                         "centre of mass")
    ap.add_argument("--far-size", type=float, default=0.05, help="element size far from the pole, as a fraction of R (0.05)")
    ap.add_argument("--fine-zone", type=float, default=1.5,
                    help="radius of the zone meshed at h_c around the pole, in units of a_H (1.5)")
    ap.add_argument("--growth", type=float, default=0.15,
                    help="size gradient outside the fine zone: size grows by this much per unit distance (0.15)")
    ap.add_argument("--penalty", type=float, default=100.0,
                    help="contact penalty slope K = penalty * E / h_c, Pa/m (100)")
    ap.add_argument("--element", default="CAX8", choices=["CAX8", "CAX4"], help="axisymmetric element (CAX8)")
    ap.add_argument("--contact", default="surface", choices=["surface", "node"],
                    help="CalculiX contact formulation: SURFACE TO SURFACE (default) or NODE TO SURFACE")
    ap.add_argument("--increments", type=int, default=4, help="load increments of the step (4)")
    ap.add_argument("--sanity", action="store_true",
                    help="first run the cylinder case and use its measured force factor")
    ap.add_argument("--segment-factor", type=float, default=180.0,
                    help="factor from ccx's axisymmetric reaction to the full ring when --sanity is not given "
                         "(180: ccx 2.20 reports a 2-degree segment, as --sanity measures)")
    ap.add_argument("--ccx", default="ccx", help="CalculiX binary (ccx)")
    ap.add_argument("--gmsh", default="gmsh", help="gmsh binary (gmsh)")
    ap.add_argument("--work", help="working folder (default: a temporary one, removed at the end)")
    ap.add_argument("--keep", action="store_true", help="keep the work folder and the ccx output files")
    a = ap.parse_args(argv)
    try:
        depths = [float(x) * 1e-6 for x in a.depths.split(",") if x.strip()]
        per_a = [float(x) for x in a.per_a.split(",") if x.strip()]
    except ValueError:
        raise CheckError("--depths and --per-a take comma-separated numbers") from None
    if not depths or not per_a or min(depths) <= 0 or min(per_a) <= 0:
        raise CheckError("--depths and --per-a need positive numbers")
    for name in ("radius", "E", "far_size", "fine_zone", "growth", "penalty"):
        v = getattr(a, name)
        if not (math.isfinite(v) and v > 0):
            raise CheckError(f"--{name.replace('_', '-')} = {v}: must be a finite number > 0")
    if not -1 < a.nu < 0.5:
        raise CheckError(f"--nu = {a.nu}: allowed -1 < nu < 0.5")
    if max(depths) > 0.05 * a.radius:
        raise CheckError("depths above 5 % of R are outside the small-strain check")
    if not (math.isfinite(a.rho) and a.rho > 0):
        raise CheckError(f"--rho = {a.rho}: must be a finite number > 0")
    mat = {"E": a.E, "nu": a.nu, "rho": a.rho}

    work = Path(a.work) if a.work else Path(tempfile.mkdtemp(prefix="ccx_hertz_"))
    work.mkdir(parents=True, exist_ok=True)
    try:
        factor = sanity(a, mat, work) if a.sanity else a.segment_factor
        head = (f"{'depth um':>8} {'a/R':>6} {'h_c':>6} {'elems':>6} {'delta_e m':>11} {'F N':>11} "
                f"{'F_H N':>11} {'F/F_H-1':>8} {'a_c/a_H-1':>9} {'pen/delta':>9} {'time s':>7}")
        print(head)
        rows = []
        for d in depths:
            for p in per_a:
                r = ball_case(a, mat, work, d, p, factor)
                rows.append(r)
                free = (f"   centre-of-mass shift {r['com_shift']:.4e} m, volume {r['volume_error']:+.1e}, "
                        f"north-pole force {r['north'] / r['F']:+.1e} F, g = {r['gravity']:.5e} m/s^2, "
                        f"{r['runs']} ccx runs") if a.support == "free" else ""
                print(f"{d * 1e6:>8g} {r['a_H'] / a.radius:>6.4f} {'a/' + format(p, 'g'):>6} {r['elements']:>6d} "
                      f"{r['delta_e']:>11.5e} {r['F']:>11.5e} {r['F_H']:>11.5e} {r['ratio']:>+8.3%} "
                      f"{r['a_ratio']:>+9.2%} {r['penetration'] / r['delta_e']:>9.2e} {r['wall']:>7.1f}{free}",
                      flush=True)
        finest = [r for r in rows if r["per_a"] == max(per_a)]
        if len(finest) >= 2:
            x = np.array([r["a_H"] / a.radius for r in finest])
            c1, c0 = np.polyfit(x, [r["ratio"] for r in finest], 1)
            print(f"finest meshes (h_c = a/{max(per_a):g}): F/F_H - 1 = {c0:+.3%} + {c1:.3f} a/R "
                  "(least squares over the depths)")
    finally:
        if not a.work and not a.keep:
            shutil.rmtree(work, ignore_errors=True)
        elif a.keep:
            print(f"work files kept in {work}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except CheckError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
