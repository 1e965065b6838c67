#!/usr/bin/env python3
"""Independent check that a .vtu written by twoball is readable by a VTK-XML reader.

Usage: check_vtu.py FILE.vtu [--expect-cells N] [--expect-points N] [--fields a,b,...]
                    [--components NAME=c1,c2,...]... [--expect-time T]

Reads FILE (ASCII or binary, appended raw and zlib-compressed as ParaView writes it) with
meshio (the reader ParaView users rely on for conversions), checks that it holds only
hexahedra, that the counts and named fields match, that every value is finite, and that
every hexahedron has a positive volume (node order VTK_HEXAHEDRON); with --components, that
the field's DataArray names its components so (ComponentName0.. attributes of the XML
header); with --expect-time, that the file's TimeValue field data is T (relative 1e-12).
Exit status 0 on success, 1 with a message on failure, 2 if meshio is missing.
"""
import argparse
import re
import sys

try:
    import meshio
    import numpy as np
except ImportError as e:  # pragma: no cover
    print(f"check_vtu: needs meshio and numpy ({e})", file=sys.stderr)
    sys.exit(2)


def hex_volume(p):
    """Volume of trilinear hexahedra p[..., 8, 3] by 2x2x2 Gauss points."""
    g = 1.0 / np.sqrt(3.0)
    ref = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                    [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
    vol = np.zeros(p.shape[0])
    for q in np.array(np.meshgrid([-g, g], [-g, g], [-g, g])).reshape(3, -1).T:
        f = 1.0 + ref * q
        dn = 0.125 * np.stack([ref[:, 0] * f[:, 1] * f[:, 2],
                               ref[:, 1] * f[:, 0] * f[:, 2],
                               ref[:, 2] * f[:, 0] * f[:, 1]], axis=1)
        jac = np.einsum("ena,nd->ead", p, dn)
        vol += np.linalg.det(jac)
    return vol


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("file")
    ap.add_argument("--expect-cells", type=int)
    ap.add_argument("--expect-points", type=int)
    ap.add_argument("--fields", default="")
    ap.add_argument("--components", action="append", default=[])
    ap.add_argument("--expect-time", type=float)
    a = ap.parse_args()
    m = meshio.read(a.file)
    kinds = {c.type for c in m.cells}
    if kinds != {"hexahedron"}:
        sys.exit(f"check_vtu: cell types {kinds}, expected only hexahedron")
    hexes = np.concatenate([c.data for c in m.cells])
    if a.expect_cells is not None and len(hexes) != a.expect_cells:
        sys.exit(f"check_vtu: {len(hexes)} cells, expected {a.expect_cells}")
    if a.expect_points is not None and len(m.points) != a.expect_points:
        sys.exit(f"check_vtu: {len(m.points)} points, expected {a.expect_points}")
    if not np.all(np.isfinite(m.points)):
        sys.exit("check_vtu: non-finite point coordinates")
    vol = hex_volume(m.points[hexes])
    if not np.all(vol > 0):
        sys.exit(f"check_vtu: {np.sum(vol <= 0)} hexahedra with non-positive volume")
    names = set(m.point_data) | set(m.cell_data)
    for f in filter(None, a.fields.split(",")):
        if f not in names:
            sys.exit(f"check_vtu: field {f!r} missing (have {sorted(names)})")
    for k, v in m.point_data.items():
        if len(v) != len(m.points) or not np.all(np.isfinite(v)):
            sys.exit(f"check_vtu: point field {k} has a wrong length or non-finite values")
    for k, blocks in m.cell_data.items():
        v = np.concatenate(blocks)
        if len(v) != len(hexes) or not np.all(np.isfinite(v)):
            sys.exit(f"check_vtu: cell field {k} has a wrong length or non-finite values")
    with open(a.file, "rb") as f:
        header = f.read().split(b"<AppendedData", 1)[0].decode()
    for spec in a.components:
        name, want = spec.split("=", 1)
        tag = re.search(r'<DataArray[^>]*Name="%s"[^>]*>' % re.escape(name), header)
        if tag is None:
            sys.exit(f"check_vtu: no DataArray {name!r} in the header")
        got = re.findall(r'ComponentName(\d+)="([^"]*)"', tag.group(0))
        got = ",".join(v for _, v in sorted(got, key=lambda kv: int(kv[0])))
        if got != want:
            sys.exit(f"check_vtu: {name} components {got!r}, expected {want!r}")
    if a.expect_time is not None:
        t = m.field_data.get("TimeValue")
        if t is None or abs(float(np.ravel(t)[0]) - a.expect_time) > 1e-12 * max(1.0, abs(a.expect_time)):
            sys.exit(f"check_vtu: TimeValue {t}, expected {a.expect_time}")
    print(f"check_vtu: {a.file}: {len(m.points)} points, {len(hexes)} hexahedra, "
          f"volume {vol.sum():.6e}, fields {sorted(names)}")


if __name__ == "__main__":
    main()
