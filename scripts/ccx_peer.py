#!/usr/bin/env python3
"""A real peer for twoball: the same two-ball collision run by CalculiX (ccx 2.20).

Turns a twoball scene (TOML, or the built-in default: two FE-study copper balls,
D = 20 mm, +1 / -1 m/s head-on) into a CalculiX explicit-dynamics deck on the mesh that
`twoball mesh ball` makes, runs `ccx`, and extracts the collision quantities twoball reports:
centre-of-mass velocities after impact, delta(t) (change of the distance between the balls'
centres of mass), the contact duration, the coefficient of restitution
e = (v2+ - v1+)/(v1 - v2) and delta_max. It compares them with the analytical model
(`twoball analytic --json`) and, when given, with a twoball results.json.

Model choices (docs/peer.md explains each):
- C3D8 hexahedra by default, one *SOLID SECTION a ball. C3D8R (--element C3D8R) runs, but
  in ccx 2.20 explicit runs its pole nodes sink into their elements under the contact
  springs (zero-energy modes) and the balls chatter or pass through each other (measured in
  docs/peer.md); CalculiX's C3D8I is not usable in dynamics.
- Ball 2 is ball 1's mesh reflected x -> -x (hex node order 1-4-3-2 / 5-8-7-6 to keep the
  Jacobian positive); the poles face each other across a gap of --gap (1e-7 m), which the
  balls close in gap / v_r before contact starts; delta is measured from touch.
- Bilinear isotropic hardening: *PLASTIC from (yield, 0) along the hardening slope
  H = E E_T / (E - E_T) (E_T = tangent modulus of the total stress-strain curve).
- Node-to-surface penalty contact, slave = ball 1's contact patch, master = ball 2's, both
  element-face surfaces (each boundary quad mapped to its hex and C3D8 face S1..S6).
  PRESSURE-OVERCLOSURE=LINEAR with slope K = FKN E / h (Pa/m), FKN = 10 x the scene's
  penalty_factor (twoball's default rule) and h the median thickness (volume / face area) of
  the elements under ball 1's contact patch within the analytical contact radius; CalculiX
  multiplies K by each slave node's tributary area. *FRICTION mu with stick slope K / 10.
- *DYNAMIC, EXPLICIT; CalculiX chooses its own stable increment (a first, one-increment run
  reads it) and softens contact springs that would need a smaller one ("Selective Spring
  Scaling"): the factor is reported.
- Output: *NODE PRINT of V for all nodes about --samples times (*CONTACT PRINT of CF
  crashes ccx 2.20 in explicit runs). Centre-of-mass velocities weight nodes by CalculiX's
  lumped masses (volume/8 per element corner; the row-sum lumping is tried too and the one
  that keeps momentum constant after separation is used); delta(t) integrates the relative
  centre-of-mass velocity (trapezoid).

Python 3.11 standard library + numpy. Prints a table; --json FILE writes the results
(keys carry their units) atomically.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np

# Material presets, as twoball's src/material/mod.rs (Table 1 of Li, Yang & Shi 2019 and the
# copper of their ANSYS study): E (GPa), yield (MPa), rho (kg/m^3), mu, nu; tangent = E/100.
PRESETS = {
    "copper": (120.0, 100.0, 8500.0, 0.20, 0.34),
    "steel": (210.0, 210.0, 7800.0, 0.10, 0.27),
    "concrete": (17.0, 25.0, 2400.0, 0.60, 0.20),
    "cast-iron": (160.0, 250.0, 7200.0, 0.15, 0.30),
    "alumina": (70.0, 100.0, 3100.0, 0.50, 0.25),
    "glass": (80.0, 70.0, 2700.0, 0.30, 0.20),
    "wood": (14.0, 40.0, 600.0, 0.40, 0.25),
    "aluminum": (75.0, 300.0, 2700.0, 0.32, 0.33),
    "rubber": (0.0061, 7.0, 1000.0, 0.45, 0.45),
    "copper-fe": (120.0, 100.0, 7900.0, 0.20, 0.33),
}

DEFAULT_SCENE = """
[ball1]
material = "copper-fe"
diameter = 0.02
velocity = [1.0, 0.0, 0.0]
[ball2]
material = "copper-fe"
diameter = 0.02
velocity = [-1.0, 0.0, 0.0]
"""

# CalculiX (Abaqus) C3D8 faces, 0-based corner indices, numbered S1..S6. gmsh and CalculiX
# share the linear hexahedron's node order, so a twoball hex is a C3D8 element as it is.
C3D8_FACES = ((0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0))
HEX_CORNERS = np.array(
    [[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1], [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]],
    dtype=float,
)


class PeerError(Exception):
    """A user-facing failure: one line naming what is wrong and what is allowed."""


# ----------------------------------------------------------------------------- scene


def material_of(spec, where):
    """Resolves a scene material (preset name or table) to a dict of SI values."""
    keys = ("E", "nu", "rho", "yield", "tangent", "mu", "mu_static")
    if isinstance(spec, str):
        spec = {"preset": spec}
    if not isinstance(spec, dict):
        raise PeerError(f"{where} must be a preset name or a table, found {spec!r}")
    unknown = set(spec) - set(keys) - {"preset"}
    if unknown:
        raise PeerError(f"unknown key {where}.{sorted(unknown)[0]} (allowed: preset, {', '.join(keys)})")
    if "preset" in spec:
        name = spec["preset"]
        if name not in PRESETS:
            raise PeerError(f"{where}.preset = {name!r}: allowed {', '.join(PRESETS)}")
        e, y, rho, mu, nu = PRESETS[name]
        m = {"E": e * 1e9, "nu": nu, "rho": rho, "yield": y * 1e6, "tangent": e * 1e7, "mu": mu, "mu_static": mu}
    else:
        missing = [k for k in ("E", "nu", "rho", "yield", "mu") if k not in spec]
        if missing:
            raise PeerError(f"missing required key {where}.{missing[0]} (or give {where}.preset)")
        m = {"tangent": float(spec["E"]) / 100.0, "mu_static": float(spec["mu"])}
    for k in keys:
        if k in spec:
            try:
                m[k] = float(spec[k])
            except (TypeError, ValueError):
                raise PeerError(f"{where}.{k} = {spec[k]!r}: must be a number (SI units)") from None
    if "mu" in spec and "mu_static" not in spec:
        m["mu_static"] = max(m["mu_static"], m["mu"])
    checks = {
        "E": m["E"] > 0,
        "nu": -1 < m["nu"] < 0.5,
        "rho": m["rho"] > 0,
        "yield": m["yield"] > 0,
        "tangent": 0 <= m["tangent"] < m["E"],
        "mu": m["mu"] >= 0,
    }
    for k, ok in checks.items():
        if not (ok and math.isfinite(m[k])):
            raise PeerError(f"{where}.{k} = {m[k]} is out of range")
    return m


def read_scene(path):
    """Reads a scene file (or the default) into plain dicts, with twoball's defaults."""
    try:
        text = DEFAULT_SCENE if path is None else Path(path).read_text()
    except OSError as e:
        raise PeerError(f"cannot read scene {path}: {e.strerror}") from None
    try:
        root = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise PeerError(f"{path}: not valid TOML: {e}") from None
    balls = []
    for key in ("ball1", "ball2"):
        b = root.get(key)
        if not isinstance(b, dict):
            raise PeerError(f"missing required table [{key}] (material, diameter, velocity)")
        for req in ("material", "diameter", "velocity"):
            if req not in b:
                raise PeerError(f"missing required key {key}.{req}")
        try:
            d = float(b["diameter"])
            v = [float(x) for x in b["velocity"]]
            w = [float(x) for x in b.get("angular_velocity", [0.0, 0.0, 0.0])]
        except (TypeError, ValueError):
            raise PeerError(f"{key}.diameter, velocity and angular_velocity must be numbers "
                            "(velocity: [vx, vy, vz] in m/s)") from None
        if not 1e-4 <= d <= 1.0:
            raise PeerError(f"{key}.diameter = {d}: allowed 1e-4 <= diameter <= 1 m")
        if len(v) != 3 or len(w) != 3:
            raise PeerError(f"{key}.velocity and angular_velocity must have 3 components")
        mesh = b.get("mesh", {})
        if "file" in mesh:
            base = Path(path).parent if path else Path(".")
            mesh_spec = {"file": str(base / mesh["file"])}
        else:
            # twoball's defaults (src/scene.rs: DEFAULT_SIZE_PER_D, DEFAULT_POLE_SIZE_PER_D).
            size = float(mesh.get("size", d / 6.0))
            pole = float(mesh.get("pole_size", min(d / 200.0, size)))
            mesh_spec = {"size": size, "pole_size": pole}
        if "position" in b:
            raise PeerError(f"{key}.position is not supported by the peer script: the balls start touching")
        balls.append({
            "name": key,
            "material": material_of(b["material"], f"{key}.material"),
            "diameter": d,
            "velocity": v,
            "angular_velocity": w,
            "mesh": mesh_spec,
        })
    contact = root.get("contact", {})
    fr = contact.get("friction", "on")
    m1, m2 = balls[0]["material"], balls[1]["material"]
    if fr is True or fr == "on":
        mu = 0.5 * (m1["mu"] + m2["mu"])
    elif fr is False or fr == "off":
        mu = 0.0
    elif isinstance(fr, (int, float)) and 0 <= fr <= 5:
        mu = float(fr)
    else:
        raise PeerError(f'contact.friction = {fr!r}: allowed "on", "off" or 0 <= mu <= 5')
    pf = float(contact.get("penalty_factor", 1.0))
    if not 1e-3 <= pf <= 1e3:
        raise PeerError(f"contact.penalty_factor = {pf}: allowed 1e-3 <= penalty_factor <= 1e3")
    return {"balls": balls, "mu": mu, "penalty_factor": pf}


# ----------------------------------------------------------------------------- mesh


def read_msh41(path):
    """Reads a gmsh MSH 4.1 ASCII file: nodes (n,3), hexes (e,8) 0-based, contact quads."""
    lines = Path(path).read_text().split("\n")
    i = 0
    names, surf_phys = {}, {}
    tags, coords, hexes, quads = [], [], [], []
    while i < len(lines):
        line = lines[i].strip()
        i += 1
        if line == "$MeshFormat":
            ver, ftype = lines[i].split()[:2]
            if ver != "4.1" or ftype != "0":
                raise PeerError(f"{path}: MSH {ver} {'binary' if ftype != '0' else 'ASCII'}; "
                                "need MSH 4.1 ASCII (gmsh -format msh41)")
        elif line == "$PhysicalNames":
            n = int(lines[i]); i += 1
            for _ in range(n):
                dim, tag, name = lines[i].split(maxsplit=2); i += 1
                names[(int(dim), int(tag))] = name.strip().strip('"')
        elif line == "$Entities":
            npt, ncu, nsu, nvo = map(int, lines[i].split()); i += 1
            i += npt + ncu
            for _ in range(nsu):
                p = lines[i].split(); i += 1
                nphys = int(p[7])
                surf_phys[int(p[0])] = [int(x) for x in p[8:8 + nphys]]
            i += nvo
        elif line == "$Nodes":
            nblocks = int(lines[i].split()[0]); i += 1
            for _ in range(nblocks):
                n = int(lines[i].split()[3]); i += 1
                tags.extend(int(lines[i + k]) for k in range(n)); i += n
                coords.extend([float(x) for x in lines[i + k].split()[:3]] for k in range(n)); i += n
        elif line == "$Elements":
            nblocks = int(lines[i].split()[0]); i += 1
            for _ in range(nblocks):
                dim, ent, etype, n = map(int, lines[i].split()); i += 1
                rows = [[int(x) for x in lines[i + k].split()[1:]] for k in range(n)]; i += n
                if etype == 5:
                    hexes.extend(rows)
                elif etype == 3 and dim == 2:
                    phys = {names.get((2, t), "") for t in surf_phys.get(ent, [])}
                    if "contact" in phys:
                        quads.extend(rows)
    if not hexes:
        raise PeerError(f"{path}: no 8-node hexahedra")
    index = {t: k for k, t in enumerate(tags)}
    nodes = np.array(coords, dtype=float)
    hx = np.array([[index[t] for t in h] for h in hexes], dtype=np.int64)
    qd = np.array([[index[t] for t in q] for q in quads], dtype=np.int64).reshape(-1, 4)
    return nodes, hx, qd


def boundary_quads(hexes):
    """Faces of the hexes that belong to one element only, as (element, face) pairs."""
    seen = {}
    for e, h in enumerate(hexes):
        for f, fc in enumerate(C3D8_FACES):
            key = tuple(sorted(int(h[c]) for c in fc))
            seen[key] = None if key in seen else (e, f)
    return {k: v for k, v in seen.items() if v is not None}


def contact_patch(nodes, hexes, quads, radius):
    """(element, face) pairs of the contact patch: the mesh's `contact` quads, or, if the
    file has none, boundary faces with a node within 30 degrees of the +x pole."""
    bnd = boundary_quads(hexes)
    if len(quads):
        keys = [tuple(sorted(int(x) for x in q)) for q in quads]
    else:
        c = math.cos(math.radians(30.0))
        keys = [k for k in bnd if any(nodes[n, 0] >= c * radius * (1 - 1e-9) for n in k)]
    patch = []
    for k in keys:
        if k not in bnd:
            raise PeerError(f"contact quad {k} is not a boundary face of the hex mesh")
        patch.append(bnd[k])
    return patch


def mesh_ball(twoball, ball, workdir):
    """Nodes, hexes and contact quads of one ball (centre at the origin, pole at +x)."""
    m = ball["mesh"]
    if "file" in m:
        return read_msh41(m["file"])
    out = Path(workdir) / f"{ball['name']}.msh"
    cmd = [twoball, "mesh", "ball", "--diameter", repr(ball["diameter"]), "--size", repr(m["size"]),
           "--pole-size", repr(m["pole_size"]), "-o", str(out)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise PeerError(f"`{' '.join(cmd)}` failed: {r.stderr.strip()}")
    return read_msh41(out)


def hex_integrals(nodes, hexes):
    """Per element: volume, integrals of each shape function N_i and of N_i^2 (m^3), by
    2x2x2 Gauss (exact for the trilinear hex)."""
    x = nodes[hexes]  # (e, 8, 3)
    g = 1.0 / math.sqrt(3.0)
    vol = np.zeros(len(hexes))
    nint = np.zeros((len(hexes), 8))
    nsq = np.zeros((len(hexes), 8))
    for gp in HEX_CORNERS * g:
        n = 0.125 * np.prod(1.0 + HEX_CORNERS * gp, axis=1)  # (8,)
        dn = np.empty((8, 3))
        for a in range(3):
            o = [b for b in range(3) if b != a]
            dn[:, a] = 0.125 * HEX_CORNERS[:, a] * (1 + HEX_CORNERS[:, o[0]] * gp[o[0]]) * (
                1 + HEX_CORNERS[:, o[1]] * gp[o[1]])
        jac = np.einsum("na,enb->eab", dn, x)
        det = np.linalg.det(jac)
        vol += det
        nint += det[:, None] * n[None, :]
        nsq += det[:, None] * (n * n)[None, :]
    return vol, nint, nsq


def face_area(nodes, hexes, e, f):
    """Area of face f of hex e (two triangles), m^2."""
    p = nodes[hexes[e, list(C3D8_FACES[f])]]
    return 0.5 * np.linalg.norm(np.cross(p[2] - p[0], p[3] - p[1]))


# ----------------------------------------------------------------------------- model


def build_model(scene, twoball, workdir, gap, twist_deg=0.0):
    """Both balls in one numbering: ball 1 left of x = 0 (pole at -gap/2), ball 2 mirrored."""
    b1, b2 = scene["balls"]
    n1, h1, q1 = mesh_ball(twoball, b1, workdir)
    if b2["mesh"] == b1["mesh"] and b2["diameter"] == b1["diameter"]:
        n2, h2, q2 = n1.copy(), h1.copy(), q1.copy()
    else:
        n2, h2, q2 = mesh_ball(twoball, b2, workdir)
    r1, r2 = 0.5 * b1["diameter"], 0.5 * b2["diameter"]
    p1 = contact_patch(n1, h1, q1, r1)
    p2 = contact_patch(n2, h2, q2, r2)
    # Ball 2: reflect x -> -x; reversing each face's cycle keeps the Jacobian positive.
    n2 = n2 * np.array([-1.0, 1.0, 1.0])
    perm = [0, 3, 2, 1, 4, 7, 6, 5]
    h2 = h2[:, perm]
    # Face f of the old node order is face fmap[f] of the new one (S3<->S6, S4<->S5).
    fmap = {0: 0, 1: 1, 2: 5, 3: 4, 4: 3, 5: 2}
    p2 = [(e, fmap[f]) for e, f in p2]
    if twist_deg:  # turn ball 2 about the line of centres (x): poles' nodes no longer face each other
        c, s_ = math.cos(math.radians(twist_deg)), math.sin(math.radians(twist_deg))
        n2 = n2 @ np.array([[1.0, 0.0, 0.0], [0.0, c, s_], [0.0, -s_, c]])
    n1 = n1 + np.array([-r1 - 0.5 * gap, 0.0, 0.0])
    n2 = n2 + np.array([r2 + 0.5 * gap, 0.0, 0.0])
    centres = (np.array([-r1 - 0.5 * gap, 0, 0]), np.array([r2 + 0.5 * gap, 0, 0]))
    return {
        "nodes": (n1, n2), "hexes": (h1, h2), "patch": (p1, p2), "centres": centres,
    }


def check_faces(nodes, hexes, patch, outward):
    """Checks the face numbering: the C3D8 face cycles above (as CalculiX lists them) turn
    inward by the right-hand rule, so each patch face's cycle normal must point inward."""
    for e, f in patch[:50]:
        p = nodes[hexes[e, list(C3D8_FACES[f])]]
        nrm = np.cross(p[2] - p[0], p[3] - p[1])
        if np.dot(nrm, outward(p.mean(axis=0))) >= 0:
            raise PeerError(f"internal: face S{f + 1} of element {e} is not on the ball's outside")


def penalty_slope(model, scene, analytic):
    """K = FKN E / h (Pa/m): h = median thickness of ball 1's elements under the contact
    patch within 1.5 x the analytical contact radius (or the 10 % nearest the pole)."""
    n1, h1 = model["nodes"][0], model["hexes"][0]
    vol, _, _ = hex_integrals(n1, h1)
    r1, r2 = (0.5 * b["diameter"] for b in scene["balls"])
    a = math.sqrt(analytic["delta_max_m"] * r1 * r2 / (r1 + r2))  # Hertz-like contact radius
    thick, dist = [], []
    for e, f in model["patch"][0]:
        c = n1[h1[e, list(C3D8_FACES[f])]].mean(axis=0)
        thick.append(vol[e] / face_area(n1, h1, e, f))
        dist.append(np.linalg.norm(c[1:]))  # off the line of centres
    thick, dist = np.array(thick), np.array(dist)
    near = thick[dist <= 1.5 * a]
    if len(near) == 0:
        near = thick[np.argsort(dist)[: max(1, len(dist) // 10)]]
    h = float(np.median(near))
    e_min = min(b["material"]["E"] for b in scene["balls"])
    fkn = 10.0 * scene["penalty_factor"]
    return fkn * e_min / h, h, fkn


def write_deck(path, model, scene, k_pen, t_end, dt_guess, freq, element="C3D8R"):
    """Writes the CalculiX input deck (SI units)."""
    (n1, n2), (h1, h2) = model["nodes"], model["hexes"]
    off_n, off_e = len(n1), len(h1)
    out = [f"** twoball peer: two balls, {element}, explicit dynamics, node-to-surface contact",
           "*HEADING", "twoball peer deck", "*NODE, NSET=NALL"]
    for k, p in enumerate(np.vstack([n1, n2])):
        out.append(f"{k + 1}, {p[0]:.12e}, {p[1]:.12e}, {p[2]:.12e}")
    for b, (h, eoff, noff) in enumerate(((h1, 0, 0), (h2, off_e, off_n))):
        out.append(f"*ELEMENT, TYPE={element}, ELSET=BALL{b + 1}")
        for k, row in enumerate(h):
            out.append(f"{eoff + k + 1}, " + ", ".join(str(noff + int(v) + 1) for v in row))
    for b, (lo, hi) in enumerate(((1, off_n), (off_n + 1, off_n + len(n2)))):
        out.append(f"*NSET, NSET=N{b + 1}, GENERATE")
        out.append(f"{lo}, {hi}, 1")
    for b, (patch, eoff) in enumerate(((model["patch"][0], 0), (model["patch"][1], off_e))):
        out.append(f"*SURFACE, NAME=CONTACT{b + 1}, TYPE=ELEMENT")
        for e, f in patch:
            out.append(f"{eoff + e + 1}, S{f + 1}")
    mu = scene["mu"]
    for b, ball in enumerate(scene["balls"]):
        m = ball["material"]
        hmod = m["E"] * m["tangent"] / (m["E"] - m["tangent"])
        eps2 = 1.0
        out += [f"*MATERIAL, NAME=MAT{b + 1}", "*ELASTIC", f"{m['E']:.12e}, {m['nu']:.12e}",
                "*DENSITY", f"{m['rho']:.12e}", "*PLASTIC", f"{m['yield']:.12e}, 0.0",
                f"{m['yield'] + hmod * eps2:.12e}, {eps2:.12e}",
                f"*SOLID SECTION, ELSET=BALL{b + 1}, MATERIAL=MAT{b + 1}"]
    out += ["*SURFACE INTERACTION, NAME=BALLS", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
            f"{k_pen:.12e}"]
    if mu > 0:
        out += ["*FRICTION", f"{mu:.12e}, {0.1 * k_pen:.12e}"]
    out += ["*CONTACT PAIR, INTERACTION=BALLS, TYPE=NODE TO SURFACE", "CONTACT1, CONTACT2"]
    out.append("*INITIAL CONDITIONS, TYPE=VELOCITY")
    for b, (ball, nodes, noff, c) in enumerate(
            zip(scene["balls"], (n1, n2), (0, off_n), model["centres"])):
        v, w = np.array(ball["velocity"]), np.array(ball["angular_velocity"])
        if not w.any():
            out += [f"N{b + 1}, {d + 1}, {v[d]:.12e}" for d in range(3)]
        else:  # rigid rotation about the ball's centre: v + w x (x - c)
            vel = v + np.cross(w, nodes - c)
            for k, vk in enumerate(vel):
                out += [f"{noff + k + 1}, {d + 1}, {vk[d]:.12e}" for d in range(3)]
    out += ["*STEP, INC=100000000", "*DYNAMIC, EXPLICIT", f"{dt_guess:.12e}, {t_end:.12e}"]
    if freq > 0:
        out += [f"*NODE PRINT, NSET=NALL, FREQUENCY={freq}", "V"]
    out += ["*END STEP", ""]
    tmp = Path(str(path) + ".tmp")
    tmp.write_text("\n".join(out))
    tmp.replace(path)


# ----------------------------------------------------------------------------- running


def run_ccx(ccx, workdir, job, threads):
    """Runs ccx on workdir/job.inp; returns (wall time s, CPU time s, stdout text). The CPU
    time (user + system of the ccx process) is the fair measure on a shared machine."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), CCX_NPROC_STIFFNESS=str(threads),
               CCX_NPROC_RESULTS=str(threads), NUMBER_OF_CPUS=str(threads))
    t0 = time.perf_counter()
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        r = subprocess.run([ccx, "-i", job], cwd=workdir, capture_output=True, text=True, env=env)
    except FileNotFoundError:
        raise PeerError(f"ccx not found ({ccx}): apt-get install calculix-ccx, or pass --ccx PATH") from None
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    log = r.stdout + r.stderr
    (Path(workdir) / f"{job}.log").write_text(log)
    if r.returncode != 0 or "*ERROR" in log:
        err = [ln.strip() for ln in log.splitlines() if "ERROR" in ln][:3]
        raise PeerError(f"ccx failed (exit {r.returncode}) on {workdir}/{job}.inp: {' | '.join(err)}")
    return wall, cpu, log


FLOAT_FIX = re.compile(r"(\d)([+-]\d{3})\b")


def parse_dat(path, n_nodes):
    """Velocity blocks of a .dat file, read as a stream: times (k,), velocities (k, n, 3)."""
    header = re.compile(r"^\s*velocities \(vx,vy,vz\) for set \S+ and time\s+(\S+)")
    times, vels = [], []

    def flush(rows):
        body = " ".join(rows)
        try:
            a = np.array(body.split(), dtype=float)
        except ValueError:  # Fortran drops the E of 3-digit exponents: 1.0-100
            a = np.array(FLOAT_FIX.sub(r"\1E\2", body).split(), dtype=float)
        a = a.reshape(-1, 4)
        v = np.zeros((n_nodes, 3))
        v[a[:, 0].astype(np.int64) - 1] = a[:, 1:]
        vels.append(v)

    rows = None
    with open(path) as f:
        for line in f:
            m = header.match(line)
            if m:
                if rows is not None:
                    flush(rows)
                times.append(float(m.group(1)))
                rows = []
            elif rows is not None and line.strip():
                rows.append(line)
    if rows is not None:
        flush(rows)
    if not times:
        raise PeerError(f"{path}: no velocity output")
    return np.array(times), np.array(vels)


# ----------------------------------------------------------------------------- analysis


def analytic(twoball, scene):
    """The analytical model's e, delta_max, t3 for the scene's normal speeds."""
    b1, b2 = scene["balls"]
    cmd = [twoball, "analytic", "--json", "--diameter", repr(b1["diameter"]),
           "--diameter2", repr(b2["diameter"]), "--v1", repr(b1["velocity"][0]),
           "--v2", repr(b2["velocity"][0]), "--v1t", repr(b1["velocity"][1]),
           "--v2t", repr(b2["velocity"][1]), "--mu", repr(scene["mu"])]
    for b, ball in ((1, b1), (2, b2)):
        for k, v in ball["material"].items():
            cmd += ["--set", f"ball{b}.material.{k}={v!r}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise PeerError(f"`twoball analytic` failed: {r.stderr.strip()}")
    a = json.loads(r.stdout)
    if not a.get("impact"):
        raise PeerError("the scene's balls do not approach along x: no impact to compare")
    return {"e": a["e"], "delta_max_m": a["delta2"], "contact_duration_s": a["t3"],
            "v1_after_m_per_s": a["v1_after"], "v2_after_m_per_s": a["v2_after"]}


def collision_quantities(times, vels, masses, split, v0, gap):
    """e, delta_max, contact duration from centre-of-mass velocity samples.

    times (k,) s; vels (k, n, 3) m/s; masses (n,) kg; nodes [0, split) are ball 1; v0 the
    initial x-velocities; gap the initial pole clearance, m. The samples start at t = 0 with
    the initial velocities prepended.
    """
    m1, m2 = masses[:split], masses[split:]
    v1 = np.einsum("i,kij->kj", m1, vels[:, :split]) / m1.sum()
    v2 = np.einsum("i,kij->kj", m2, vels[:, split:]) / m2.sum()
    t = np.concatenate([[0.0], times])
    u1 = np.concatenate([[v0[0]], v1[:, 0]])
    u2 = np.concatenate([[v0[1]], v2[:, 0]])
    vr0 = v0[0] - v0[1]
    # Relative approach: delta = integral of (u1 - u2) dt minus the gap closed in free flight.
    approach = np.concatenate([[0.0], np.cumsum(0.5 * (t[1:] - t[:-1]) * ((u1 - u2)[1:] + (u1 - u2)[:-1]))])
    delta = approach - gap
    t_touch = gap / vr0
    # Contact force of ball 1 on ball 2 from the momentum change of ball 2, N.
    force = m2.sum() * np.diff(u2) / np.diff(t)
    fpk = force.max()
    kpk = int(np.argmax(force))
    # After separation the centre-of-mass velocities are constant: their final values are the
    # mean over the last fifth of the run. Contact ends where ball 2's velocity has come within
    # 1 % of its total change of that final value (linear interpolation between samples).
    tail = t >= t[-1] - 0.2 * (t[-1] - t[0])
    u2f = u2[tail].mean()
    change = abs(u2f - u2[0])
    off = np.abs(u2 - u2f) <= 0.01 * change
    k = kpk + 1
    while k < len(t) and not off[k:].all():
        k += 1
    if k >= len(t) or k > np.nonzero(tail)[0][0]:
        raise PeerError("the run ended before the balls separated: raise --end-factor")
    d0, d1 = abs(u2[k - 1] - u2f), abs(u2[k] - u2f)
    frac = (d0 - 0.01 * change) / (d0 - d1) if d0 > d1 else 1.0
    t_end = t[k - 1] + (t[k] - t[k - 1]) * min(max(frac, 0.0), 1.0)
    v1p, v2p = u1[tail].mean(), u2[tail].mean()
    e = (v2p - v1p) / vr0
    kmax = int(np.argmax(delta))
    dmax = delta[kmax]
    if 0 < kmax < len(delta) - 1:  # parabola through the three samples around the peak
        y0, y1, y2 = delta[kmax - 1:kmax + 2]
        den = y0 - 2 * y1 + y2
        if den < 0:
            dmax = y1 - 0.125 * (y2 - y0) ** 2 / den
    return {
        "e": float(e),
        "delta_max_m": float(dmax),
        "contact_duration_s": float(t_end - t_touch),
        "v1_after_m_per_s": float(v1p),
        "v2_after_m_per_s": float(v2p),
        "v_after_spread_m_per_s": float(max(np.ptp(u1[tail]), np.ptp(u2[tail]))),
        "peak_force_n": float(fpk),
        "samples": int(len(times)),
        "sample_interval_s": float(np.median(np.diff(times))) if len(times) > 1 else 0.0,
        "history": {"t_s": t.tolist(), "delta_m": delta.tolist(), "v1_m_per_s": u1.tolist(),
                    "v2_m_per_s": u2.tolist()},
    }


def run_twoball(twoball, scene_path, scene, sets, out):
    """Runs `twoball run` on the scene with the peer's mesh sizes; returns its results.json.
    twoball's own wall time (results.json wall_time_s, the solve without start-up) is what the
    ratio uses; the wall time of the whole process is printed beside it."""
    cmd = [twoball, "run"] + ([str(scene_path)] if scene_path else [])
    # ccx runs the 3D balls: twoball's 3D model with its automatic 3D reductions (a variant's
    # own reduction.symmetry comes later and wins).
    cmd += ["--set", 'reduction.symmetry="auto-3d"']
    for i, b in enumerate(scene["balls"], start=1):
        m = b["mesh"]
        if "file" not in m:
            cmd += ["--set", f"ball{i}.mesh={{size={m['size']!r},pole_size={m['pole_size']!r}}}"]
    for s in sets:
        cmd += ["--set", s]
    cmd += ["--out", str(out)]
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        raise PeerError(f"`{' '.join(cmd)}` failed: {r.stderr.strip()}")
    print(f"twoball run: {wall:.2f} s wall for the whole process ({' '.join(cmd[1:])})")
    return out / "results.json"


def find_twoball(arg):
    """The twoball binary: --twoball, PATH, or target/{release,debug} next to this script."""
    if arg:
        return arg
    found = shutil.which("twoball")
    if found:
        return found
    root = Path(__file__).resolve().parent.parent
    for p in (root / "target" / "release" / "twoball", root / "target" / "debug" / "twoball"):
        if p.is_file():
            return str(p)
    raise PeerError("twoball binary not found: pass --twoball PATH or build it (cargo build --release)")


def rel(a, b):
    return (a - b) / abs(b) if b else float("nan")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene", nargs="?", help="twoball scene TOML (default: the built-in scene)")
    ap.add_argument("--twoball", help="twoball binary (default: PATH, then target/release, target/debug)")
    ap.add_argument("--ccx", default="ccx", help="CalculiX binary (default: ccx)")
    ap.add_argument("--work", help="working folder for the deck and ccx output (default: a temporary one)")
    ap.add_argument("--size", type=float, help="override both balls' bulk element size, m")
    ap.add_argument("--pole-size", type=float, help="override both balls' pole element size, m")
    ap.add_argument("--gap", type=float, default=1e-7, help="initial clearance of the poles, m (1e-7)")
    ap.add_argument("--end-factor", type=float, default=1.5,
                    help="end time as a multiple of the analytical contact duration t3 (1.5)")
    ap.add_argument("--samples", type=int, default=150, help="about this many velocity outputs (150)")
    ap.add_argument("--element", default="C3D8", choices=["C3D8", "C3D8R"],
                    help="CalculiX hexahedron: C3D8 (2x2x2 points; default) or C3D8R (one point: its "
                         "pole nodes sink through the other ball in ccx 2.20 explicit runs, docs/peer.md)")
    ap.add_argument("--twist", type=float, default=0.0,
                    help="turn ball 2 by this angle (degrees) about the line of centres (0)")
    ap.add_argument("--threads", type=int, default=1, help="threads ccx may use (1)")
    ap.add_argument("--twoball-results", help="a twoball results.json of the same scene, to compare")
    ap.add_argument("--run-twoball", action="store_true",
                    help="run `twoball run` on the same scene and mesh first (its automatic 3D reductions on, "
                         "unless --twoball-set says otherwise) and compare with it")
    ap.add_argument("--twoball-variant", action="append", default=[], metavar="LABEL=KEY=VALUE;KEY=VALUE",
                    help="also run twoball with these `--set`s (';'-separated) and compare under LABEL "
                         "(repeatable; implies --run-twoball), e.g. 'full=reduction.symmetry=\"off\"'")
    ap.add_argument("--reference-e", type=float,
                    help="converged e of the scene (e.g. 0.3190 for the default scene, docs/performance.md): "
                         "errors in e of both codes are printed against it")
    ap.add_argument("--json", help="write the results here (JSON)")
    ap.add_argument("--keep", action="store_true", help="keep the ccx .dat output")
    a = ap.parse_args(argv)
    if (a.run_twoball or a.twoball_variant) and a.twoball_results:
        raise PeerError("--run-twoball/--twoball-variant and --twoball-results exclude each other: give one")
    if a.reference_e is not None and not (math.isfinite(a.reference_e) and 0 < a.reference_e <= 1):
        raise PeerError(f"--reference-e = {a.reference_e}: allowed 0 < e <= 1")
    for name in ("gap", "end_factor", "size", "pole_size"):
        v = getattr(a, name)
        if v is not None and not (math.isfinite(v) and v > 0):
            raise PeerError(f"--{name.replace('_', '-')} = {v}: allowed a finite number > 0")
    if not 10 <= a.samples <= 100000:
        raise PeerError(f"--samples = {a.samples}: allowed 10..100000")
    if not 1 <= a.threads <= 256:
        raise PeerError(f"--threads = {a.threads}: allowed 1..256")

    scene = read_scene(a.scene)
    for b in scene["balls"]:
        if "file" not in b["mesh"]:
            if a.size:
                b["mesh"]["size"] = a.size
            if a.pole_size:
                b["mesh"]["pole_size"] = a.pole_size
            b["mesh"]["pole_size"] = min(b["mesh"]["pole_size"], b["mesh"]["size"])
    twoball = find_twoball(a.twoball)
    ana = analytic(twoball, scene)
    work = Path(a.work) if a.work else Path(tempfile.mkdtemp(prefix="ccx_peer_"))
    work.mkdir(parents=True, exist_ok=True)

    # twoball runs first (seconds), on the idle machine, then ccx.
    variants = []  # (label, sets, results.json)
    if a.twoball_results:
        variants.append(("twoball", [], Path(a.twoball_results)))
    elif a.run_twoball or a.twoball_variant:
        variants.append(("twoball", [], run_twoball(twoball, a.scene, scene, [], work / "twoball")))
    for spec in a.twoball_variant:
        label, _, sets = spec.partition("=")
        sets = [x.strip() for x in sets.split(";") if x.strip()]
        if not label or not sets or not label.replace("-", "").replace("_", "").isalnum():
            raise PeerError(f"--twoball-variant {spec!r}: expected LABEL=KEY=VALUE[;KEY=VALUE...] "
                            "with a label of letters, digits, - or _")
        variants.append((label, sets, run_twoball(twoball, a.scene, scene, sets, work / f"twoball-{label}")))

    model = build_model(scene, twoball, work, a.gap, a.twist)
    (n1, n2), (h1, h2) = model["nodes"], model["hexes"]
    c1, c2 = model["centres"]
    check_faces(n1, h1, model["patch"][0], lambda p: p - c1)
    check_faces(n2, h2, model["patch"][1], lambda p: p - c2)
    k_pen, h_pole, fkn = penalty_slope(model, scene, ana)
    t_end = a.end_factor * ana["contact_duration_s"]

    # Probe: one short run to read the stable increment CalculiX chooses for this mesh.
    write_deck(work / "probe.inp", model, scene, k_pen, 1e-12, 1e-13, 0, a.element)
    _, _, plog = run_ccx(a.ccx, work, "probe", a.threads)
    m = re.search(r"stable time increment:\s*(\S+)", plog)
    dt = float(m.group(1)) if m else t_end / 1e4
    dt_courant = dt
    if a.element == "C3D8":  # ccx 2.20 steps C3D8 at about half the Courant increment it prints
        dt *= 0.5
    freq = max(1, int(t_end / (dt * a.samples)))
    write_deck(work / "peer.inp", model, scene, k_pen, t_end, dt, freq, a.element)
    wall, cpu, log = run_ccx(a.ccx, work, "peer", a.threads)
    scaling = re.search(r"Reduction of spring stiffness by \(maximum\) =\s*(\S+)", log)
    n_all = len(n1) + len(n2)
    times, vels = parse_dat(work / "peer.dat", n_all)
    # The increment ccx really used (it may step below the Courant estimate the probe prints).
    if len(times) > 2:
        dt = float(np.median(np.diff(times))) / freq
    if not a.keep:
        (work / "peer.dat").unlink()

    # Nodal masses: CalculiX lumps a C3D8R element's mass equally on its 8 nodes; for C3D8
    # it is neither that nor the row sum (rho * integral of N_i); the diagonal-scaled (HRZ)
    # lumping is tried too. The one under which both balls' momenta stay constant after
    # separation is CalculiX's: it is chosen and reported.
    lumpings = {"volume/8": np.zeros(n_all), "row-sum": np.zeros(n_all), "diagonal-scaled": np.zeros(n_all)}
    for (nodes, hexes, off, ball) in ((n1, h1, 0, scene["balls"][0]), (n2, h2, len(n1), scene["balls"][1])):
        vol, nint, nsq = hex_integrals(nodes, hexes)
        rho = ball["material"]["rho"]
        hrz = rho * vol[:, None] * nsq / nsq.sum(axis=1, keepdims=True)  # Hinton-Rock-Zienkiewicz
        np.add.at(lumpings["diagonal-scaled"], (hexes + off).ravel(), hrz.ravel())
        np.add.at(lumpings["volume/8"], (hexes + off).ravel(), np.repeat(rho * vol / 8.0, 8))
        np.add.at(lumpings["row-sum"], (hexes + off).ravel(), rho * nint.ravel())
    v0 = (scene["balls"][0]["velocity"][0], scene["balls"][1]["velocity"][0])
    tried = {k: collision_quantities(times, vels, m, len(n1), v0, a.gap) for k, m in lumpings.items()}
    lumping = min(tried, key=lambda k: tried[k]["v_after_spread_m_per_s"])
    q = tried[lumping]
    q["mass_lumping"] = lumping
    history = q.pop("history")

    result = {
        "scene": a.scene or "default",
        "mesh": {"nodes": n_all, "elements": len(h1) + len(h2), "size_m": scene["balls"][0]["mesh"].get("size"),
                 "pole_size_m": scene["balls"][0]["mesh"].get("pole_size"),
                 "contact_faces": [len(model["patch"][0]), len(model["patch"][1])]},
        "ccx": {"wall_time_s": wall, "cpu_time_s": cpu, "element": a.element, "threads": a.threads, "time_increment_s": dt, "courant_increment_s": dt_courant,
                "increments": int(round(t_end / dt)), "end_time_s": t_end, "output_every": freq,
                "penalty_slope_pa_per_m": k_pen, "penalty_fkn": fkn, "pole_thickness_m": h_pole,
                "spring_stiffness_reduction": float(scaling.group(1)) if scaling else 1.0,
                "gap_m": a.gap, "friction_mu": scene["mu"]},
        "calculix": q,
        "analytic": ana,
        "error_vs_analytic": {k: rel(q[k], ana[k]) for k in ("e", "delta_max_m", "contact_duration_s")},
        "history": history,
    }
    result["twoball_variants"] = []
    for label, sets, path in variants:
        tb = json.loads(Path(path).read_text())
        keys = {"e": "e", "delta_max_m": "delta_max", "contact_duration_s": "contact_duration"}
        r = {k: tb.get(v) for k, v in keys.items()}
        # twoball writes 3-vectors (scene frame); x is the line of centres.
        for k in ("v1_after", "v2_after"):
            v = tb.get(k)
            r[k + "_m_per_s"] = v[0] if isinstance(v, list) and v else v
        r["label"] = label
        r["set"] = sets
        r["wall_time_s"] = tb.get("wall_time_s")
        r["model"] = tb.get("reduction")
        r["elements"] = (tb.get("fe") or {}).get("elements")
        r["element_updates"] = tb.get("element_cycles")
        if tb.get("wall_time_s"):
            r["wall_time_ratio_ccx_over_twoball"] = wall / tb["wall_time_s"]
        result["twoball_variants"].append(r)
    if result["twoball_variants"]:
        result["twoball"] = result["twoball_variants"][0]
        if "wall_time_ratio_ccx_over_twoball" in result["twoball"]:
            result["wall_time_ratio_ccx_over_twoball"] = result["twoball"]["wall_time_ratio_ccx_over_twoball"]

    print(f"CalculiX peer: {n_all} nodes, {len(h1) + len(h2)} {a.element}, dt = {dt:.3e} s, "
          f"{result['ccx']['increments']} increments, wall {wall:.2f} s, CPU {cpu:.2f} s ({a.threads} thread(s))")
    print(f"penalty K = {k_pen:.3e} Pa/m (FKN {fkn:g}, h = {h_pole:.3e} m), spring reduction "
          f"{result['ccx']['spring_stiffness_reduction']:.3g}")
    cols = [("calculix", q), ("analytic", ana)] + [(r["label"], r) for r in result["twoball_variants"]]
    print(f"{'quantity':<24}" + "".join(f"{n:>14}" for n, _ in cols) + f"{'ccx/analytic-1':>16}")
    for k in ("e", "delta_max_m", "contact_duration_s", "v1_after_m_per_s", "v2_after_m_per_s"):
        row = "".join(f"{(c.get(k) if c.get(k) is not None else float('nan')):>14.6g}" for _, c in cols)
        print(f"{k:<24}{row}{rel(q[k], ana[k]):>16.3%}")
    if a.reference_e is not None:
        result["reference_e"] = a.reference_e
        result["error_in_e_vs_reference"] = {n: rel(c["e"], a.reference_e) for n, c in cols
                                             if n != "analytic" and c.get("e") is not None}
        print("error in e against the reference e = " + f"{a.reference_e:g}: " + ", ".join(
            f"{n} {err:+.2%}" for n, err in result["error_in_e_vs_reference"].items()))
    for tb in result["twoball_variants"]:
        if "wall_time_ratio_ccx_over_twoball" in tb:
            print(f"{tb['label']}: {tb.get('model')} model, {tb.get('elements')} elements, "
                  f"{tb.get('element_updates')} element updates, wall {tb['wall_time_s']:.3f} s, "
                  f"wall-time ratio ccx / {tb['label']}: {tb['wall_time_ratio_ccx_over_twoball']:.1f}"
                  + (f" (set: {'; '.join(tb['set'])})" if tb["set"] else ""))
    if a.json:
        def clean(o):  # no NaN in output files
            if isinstance(o, float):
                return o if math.isfinite(o) else None
            if isinstance(o, dict):
                return {k: clean(v) for k, v in o.items()}
            if isinstance(o, list):
                return [clean(v) for v in o]
            return o
        tmp = Path(a.json + ".tmp")
        tmp.write_text(json.dumps(clean(result), indent=1))
        tmp.replace(a.json)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except PeerError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
